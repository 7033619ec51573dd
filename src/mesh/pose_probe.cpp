#include "pose_probe.hpp"

#include "symcompress/scene_ops.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <map>

namespace symcompress {
namespace {

// The most vertices drawn over all the poses measured, times ten (a change is measured some ten times): beyond,
// the bounds' corners are measured instead, up to ten times as many (each a matrix times a point, where a drawn
// vertex is skinned or placed in a mesh of its own); beyond that, the keys stay as read rather than the writer take
// seconds.
constexpr std::size_t kMostPosedVertices = 4'000'000, kMostBoundPoints = 40'000'000;

}  // namespace

PoseProbe::PoseProbe(const Scene& scene, const Animation& animation) : scene_(scene) {
    const std::vector<double> keys = keyTimes(animation);
    for (std::size_t k = 0; k < keys.size(); ++k) {
        times_.push_back(keys[k]);
        if (k + 1 < keys.size()) times_.push_back((keys[k] + keys[k + 1]) / 2);
    }
    if (times_.empty()) return;
    const std::size_t vertices = posedMesh(scene, animation, times_.front()).positions.size();
    if (vertices * times_.size() * 10 > kMostPosedVertices) {
        if (!collectBounds(animation)) return;
        std::size_t points = 0;
        for (const Bound& bound : bounds_) points += bound.corners.size();
        if (points * times_.size() * 10 > kMostBoundPoints) return;
    }
    for (double time : times_) poses_.push_back(measuredAt(animation, time));
}

bool PoseProbe::collectBounds(const Animation& animation) {
    // The nodes the animation moves: those it targets and all under them (as posedMesh draws them).
    std::vector<int> targeted;
    for (const AnimationChannel& channel : animation.channels) targeted.push_back(channel.node);
    const std::vector<char> moved = nodesUnder(scene_, targeted);
    auto cornersOf = [](const Eigen::AlignedBox3d& box) {
        std::vector<Eigen::Vector3d> corners;
        for (int c = 0; c < 8; ++c) corners.push_back(box.corner(Eigen::AlignedBox3d::CornerType(c)));
        return corners;
    };
    for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
        const Node& node = scene_.nodes[n];
        if (node.mesh < 0) continue;
        const Mesh& mesh = scene_.meshes[std::size_t(node.mesh)];
        const Skin* skin = node.skin >= 0 ? &scene_.skins[std::size_t(node.skin)] : nullptr;
        const bool skinMoves = skin && std::any_of(skin->joints.begin(), skin->joints.end(),
                                                   [&](int joint) { return moved[std::size_t(joint)] != 0; });
        if (!moved[n] && !skinMoves) continue;
        if (morphTargetCount(mesh) > 0) return false;
        // Each joint's box, and the box of the vertices no joint carries (drawn by the node's own transform).
        std::vector<Eigen::AlignedBox3d> boxes(skin ? skin->joints.size() + 1 : 1);
        for (const Primitive& primitive : mesh.primitives) {
            const SkinAttributes attributes = skin ? skinAttributesOf(primitive) : SkinAttributes{};
            for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
                bool jointed = false;
                for (std::size_t set = 0; set < attributes.joints.size(); ++set) {
                    const VertexAttribute &ids = *attributes.joints[set], &amounts = *attributes.weights[set];
                    for (int c = 0; c < std::min(ids.components, amounts.components); ++c) {
                        if (amounts.vertex(v)[c] < 0) return false;
                        if (const auto joint = std::size_t(ids.vertex(v)[c]); joint < skin->joints.size()) {
                            boxes[joint].extend(primitive.positions[v]);
                            jointed = true;
                        }
                    }
                }
                if (!jointed) boxes.back().extend(primitive.positions[v]);
            }
        }
        for (std::size_t b = 0; b < boxes.size(); ++b)
            if (!boxes[b].isEmpty())
                bounds_.push_back({int(n), node.skin, b + 1 < boxes.size() ? int(b) : -1, cornersOf(boxes[b])});
    }
    return !bounds_.empty();
}

std::vector<Eigen::Vector3d> PoseProbe::measuredAt(const Animation& animation, double time) const {
    if (bounds_.empty()) return posedMesh(scene_, animation, time).positions;
    const std::vector<Eigen::Matrix4d> world = posedWorldTransforms(scene_, &animation, time);
    std::map<int, std::vector<Eigen::Matrix4d>> joints;  // of each skin
    std::vector<Eigen::Vector3d> out;
    for (const Bound& bound : bounds_) {
        Eigen::Matrix4d placement = world[std::size_t(bound.node)];
        if (bound.joint >= 0) {
            auto [entry, added] = joints.try_emplace(bound.skin);
            if (added) entry->second = jointMatrices(scene_.skins[std::size_t(bound.skin)], world);
            placement = entry->second[std::size_t(bound.joint)];
        }
        for (const Eigen::Vector3d& corner : bound.corners) out.push_back((placement * corner.homogeneous()).head<3>());
    }
    return out;
}

bool PoseProbe::measurable() const {
    return std::any_of(poses_.begin(), poses_.end(), [](const auto& pose) { return !pose.empty(); });
}

bool PoseProbe::within(const Animation& changed, double allowed) const { return farthest(changed, allowed) <= allowed; }

double PoseProbe::deviation(const Animation& changed) const {
    return farthest(changed, std::numeric_limits<double>::infinity());
}

double PoseProbe::farthest(const Animation& changed, double stopAbove) const {
    // The poses one by one on each thread; the first beyond `stopAbove` stops the others.
    std::atomic<bool> beyond{false};
    const double out = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, times_.size()), 0.0,
        [&](const tbb::blocked_range<std::size_t>& range, double farthestSoFar) {
            for (std::size_t t = range.begin(); t < range.end() && !beyond.load(std::memory_order_relaxed); ++t) {
                const std::vector<Eigen::Vector3d> posed = measuredAt(changed, times_[t]);
                for (std::size_t v = 0; v < posed.size(); ++v) {
                    const double distance = (posed[v] - poses_[t][v]).norm();
                    if (!(distance <= stopAbove)) beyond = true;
                    farthestSoFar = std::max(farthestSoFar, distance);
                }
            }
            return farthestSoFar;
        },
        [](double a, double b) { return std::max(a, b); });
    return beyond ? std::numeric_limits<double>::infinity() : out;
}

std::vector<char> measuredNodes(const Scene& scene) {
    const std::size_t count = scene.nodes.size();
    std::vector<char> drawsOrSkins(count, 0), unseen(count, 0);
    for (std::size_t n = 0; n < count; ++n) {
        const Node& node = scene.nodes[n];
        if (node.mesh >= 0) drawsOrSkins[n] = 1;
        if (node.camera >= 0 || node.light >= 0) unseen[n] = 1;
        if (node.mesh >= 0 && node.skin >= 0)
            for (int joint : scene.skins[std::size_t(node.skin)].joints) drawsOrSkins[std::size_t(joint)] = 1;
    }
    // Up the hierarchy: a node measures what any node under it does, and is unseen where one under it is.
    std::vector<int> parent(count, -1);
    for (std::size_t n = 0; n < count; ++n)
        for (int child : scene.nodes[n].children) parent[std::size_t(child)] = int(n);
    for (std::size_t n = 0; n < count; ++n)
        for (int up = parent[n], steps = 0; up >= 0 && steps < int(count); up = parent[std::size_t(up)], ++steps) {
            drawsOrSkins[std::size_t(up)] |= drawsOrSkins[n];
            unseen[std::size_t(up)] |= unseen[n];
        }
    std::vector<char> measured(count, 0);
    for (std::size_t n = 0; n < count; ++n) measured[n] = drawsOrSkins[n] && !unseen[n];
    return measured;
}

}  // namespace symcompress
