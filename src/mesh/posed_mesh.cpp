// The parts of a scene that an animation moves, as a viewer draws them at one of its times (glTF 2.0, sections
// 3.7.2 "Skins", 3.7.2.2 "Morph Targets", 3.11 "Animations" and Appendix C "Interpolation"): the decoder's check
// that animations, skins and morph targets come out as they went in, and the writer's measure of rounded keys.
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace symcompress {

std::vector<char> nodesUnder(const Scene& scene, std::vector<int> seeds) {
    std::vector<char> found(scene.nodes.size(), 0);
    while (!seeds.empty()) {
        const auto n = std::size_t(seeds.back());
        seeds.pop_back();
        if (found[n]) continue;
        found[n] = 1;
        seeds.insert(seeds.end(), scene.nodes[n].children.begin(), scene.nodes[n].children.end());
    }
    return found;
}

TriangleMesh posedMesh(const Scene& scene, const Animation& animation, double time) {
    const std::size_t count = scene.nodes.size();
    const std::vector<Eigen::Matrix4d> world = posedWorldTransforms(scene, &animation, time);
    std::vector<std::vector<const AnimationChannel*>> channelsOf(count);
    for (const AnimationChannel& channel : animation.channels)
        channelsOf[std::size_t(channel.node)].push_back(&channel);
    // Which nodes the animation moves (those it targets and everything under them), and which are drawn.
    std::vector<int> targeted;
    for (std::size_t n = 0; n < count; ++n)
        if (!channelsOf[n].empty()) targeted.push_back(int(n));
    const std::vector<char> moved = nodesUnder(scene, targeted), drawn = nodesUnder(scene, scene.roots);

    TriangleMesh out;
    for (std::size_t n = 0; n < count; ++n) {
        const Node& node = scene.nodes[n];
        if (!drawn[n] || node.mesh < 0) continue;
        const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
        const Skin* skin = node.skin >= 0 ? &scene.skins[std::size_t(node.skin)] : nullptr;
        const bool skinMoves = skin && std::any_of(skin->joints.begin(), skin->joints.end(),
                                                   [&](int joint) { return moved[std::size_t(joint)] != 0; });
        if (!moved[n] && !skinMoves) continue;
        // Morph weights: the animation's, else the node's, else the mesh's.
        std::vector<double> weights = !node.weights.empty() ? node.weights : mesh.weights;
        for (const AnimationChannel* channel : channelsOf[n])
            if (channel->path == AnimationChannel::Path::Weights) weights = sampleChannel(*channel, time);
        // A skinned mesh is drawn by its joints (glTF ignores its node's transform).
        const std::vector<Eigen::Matrix4d> joints = skin ? jointMatrices(*skin, world) : std::vector<Eigen::Matrix4d>();
        for (const Primitive& primitive : mesh.primitives) {
            const auto first = std::uint32_t(out.positions.size());
            const SkinAttributes attributes = skinAttributesOf(primitive);
            std::vector<std::pair<double, const VertexAttribute*>> displacements;  // each target's, weighted
            for (std::size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t)
                for (const VertexAttribute& displaced : primitive.targets[t])
                    if (displaced.name == "POSITION") displacements.emplace_back(weights[t], &displaced);
            for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
                Eigen::Vector3d p = primitive.positions[v];
                for (const auto& [weight, displaced] : displacements)
                    p += weight *
                         Eigen::Vector3d(displaced->vertex(v)[0], displaced->vertex(v)[1], displaced->vertex(v)[2]);
                out.positions.push_back(skinnedPosition(attributes, v, p, joints, world[n]));
            }
            for (const Triangle& t : primitive.triangles)
                out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
        }
    }
    return out;
}

}  // namespace symcompress
