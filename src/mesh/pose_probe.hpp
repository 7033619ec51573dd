// An animation's poses as read, against which a change to its keys (rounded, dropped) is measured where it
// matters: the vertices the animation moves, drawn as a viewer draws them (posedMesh). A joint's rotation moves
// a hand by the arm's length, a tail's root its tip: no bound per key value says by how much, the poses do.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <vector>

namespace symcompress {

class PoseProbe {
public:
    // The poses of `animation` (which names `scene`'s nodes) at each of its key times and halfway between them (a
    // cubic spline's tangents act only there; a dropped key's error is largest at its time). Where they would draw
    // more than some 400000 vertices in all (an exporter's keys at every frame), each pose is measured at points
    // whose motion bounds every vertex's instead (Bound); where those too are too many, or a moved mesh has morph
    // targets or negative skin weights, at none.
    PoseProbe(const Scene& scene, const Animation& animation);
    // Whether anything drawn can be measured.
    bool measurable() const;
    // Whether every vertex of every pose of `changed` (the same channel targets, or some of them: a node without its
    // channel rests) lies within `allowed` of where it lies as read.
    bool within(const Animation& changed, double allowed) const;
    // The farthest any vertex of any pose of `changed` lies from where it lies as read.
    double deviation(const Animation& changed) const;

private:
    // Points carried by a node's world transform (`joint` < 0) or by joint `joint` of skin `skin`'s joint matrix:
    // the corners of the box of the vertices a mesh's node or a joint carries. A rigidly drawn vertex's error
    // (the posed transform's error applied to it) is convex in the vertex, so largest at a corner of the box
    // around it; a skinned vertex is a mean of its joints' images weighted by weights of sum 1, its error at most
    // the largest of theirs.
    struct Bound {
        int node = -1, skin = -1, joint = -1;
        std::vector<Eigen::Vector3d> corners;
    };
    // The bounds of what `animation` moves; false where a moved mesh has morph targets or negative skin weights.
    bool collectBounds(const Animation& animation);
    // What is measured of a pose: the vertices drawn, or the bounds' points placed.
    std::vector<Eigen::Vector3d> measuredAt(const Animation& animation, double time) const;
    // The largest distance of a pose's vertex from where it lies as read, up to the first beyond `stopAbove`.
    double farthest(const Animation& changed, double stopAbove) const;

    const Scene& scene_;
    std::vector<double> times_;
    std::vector<Bound> bounds_;  // empty: the vertices are measured
    std::vector<std::vector<Eigen::Vector3d>> poses_;
};

// The nodes whose motion a PoseProbe measures: those with something drawn under them (a mesh, or a joint of a
// drawn skin) and no camera or light, whose motion it would not see.
std::vector<char> measuredNodes(const Scene& scene);

}  // namespace symcompress
