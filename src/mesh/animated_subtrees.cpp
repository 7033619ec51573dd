// Animated subtrees: the nodes an animation, a skin or morph targets move, which the stages keep as they are.
#include "symcompress/scene_ops.hpp"

#include <algorithm>

namespace symcompress {

std::vector<bool> nodesAnimationsAndSkinsMove(const Scene& scene) {
    std::vector<bool> moved(scene.nodes.size(), false);
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) moved[std::size_t(channel.node)] = true;
    for (const Skin& skin : scene.skins)
        for (int joint : skin.joints) moved[std::size_t(joint)] = true;
    return moved;
}

std::vector<bool> markAnimatedSubtrees(const Scene& input, std::vector<int>& tops) {
    std::vector<bool> animated = nodesAnimationsAndSkinsMove(input), inSubtree(input.nodes.size(), false);
    for (std::size_t n = 0; n < input.nodes.size(); ++n) {
        const Node& node = input.nodes[n];
        if (node.skin >= 0 || (node.mesh >= 0 && morphTargetCount(input.meshes[std::size_t(node.mesh)]) > 0))
            animated[n] = true;
    }
    std::vector<std::pair<int, bool>> stack;  // node, whether an ancestor is animated
    for (int root : input.roots) stack.push_back({root, false});
    while (!stack.empty()) {
        const auto [node, under] = stack.back();
        stack.pop_back();
        if (animated[std::size_t(node)] && !under) tops.push_back(node);
        inSubtree[std::size_t(node)] = under || animated[std::size_t(node)];
        for (int child : input.nodes[std::size_t(node)].children)
            stack.push_back({child, inSubtree[std::size_t(node)]});
    }
    std::sort(tops.begin(), tops.end());
    return inSubtree;
}

namespace {

// The input's skins whose joints were kept (every joint drawn from the roots is in an animated subtree),
// their joints and skeleton renumbered by `nodeOf` (input node -> output node), and the kept nodes' skin
// indices with them; a skin with a joint no root reaches is left out with a warning.
void keepSkins(const Scene& input, const std::map<int, int>& nodeOf, Scene& out) {
    std::vector<int> skinOf(input.skins.size(), -1);
    for (std::size_t k = 0; k < input.skins.size(); ++k) {
        Skin skin = input.skins[k];
        bool drawn = true;
        for (int& joint : skin.joints) {
            const auto copied = nodeOf.find(joint);
            drawn = drawn && copied != nodeOf.end();
            if (drawn) joint = copied->second;
        }
        const auto skeleton = nodeOf.find(skin.skeleton);
        skin.skeleton = skeleton == nodeOf.end() ? -1 : skeleton->second;
        if (!drawn) continue;
        skinOf[k] = int(out.skins.size());
        out.skins.push_back(std::move(skin));
    }
    std::size_t lost = 0;
    for (const auto& [from, to] : nodeOf) {
        int& skin = out.nodes[std::size_t(to)].skin;
        if (skin < 0) continue;
        skin = skinOf[std::size_t(skin)];
        lost += skin < 0;
    }
    if (lost)
        out.warnings.push_back(std::to_string(lost) +
                               " skinned meshes drawn unskinned, where their nodes place them: a joint of their skin is not drawn");
}

}  // namespace

std::size_t keepAnimatedSubtrees(const Scene& input, const std::vector<int>& tops, Scene& out,
                                 std::map<int, int>& keptMesh) {
    if (input.animations.empty() && tops.empty()) return 0;
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    std::vector<int> parent(input.nodes.size(), -1);
    for (std::size_t n = 0; n < input.nodes.size(); ++n)
        for (int child : input.nodes[n].children) parent[std::size_t(child)] = int(n);
    std::map<int, int> nodeOf;  // input node -> output node
    auto copy = [&](auto&& self, int node) -> int {
        const Node& from = input.nodes[std::size_t(node)];
        Node to = from;  // its skin is the input's, renumbered by keepSkins
        to.children.clear();
        if (from.mesh >= 0) {
            auto [entry, added] = keptMesh.emplace(from.mesh, int(out.meshes.size()));
            if (added) out.meshes.push_back(input.meshes[std::size_t(from.mesh)]);
            to.mesh = entry->second;
        }
        const int index = int(out.nodes.size());
        out.nodes.push_back(std::move(to));
        nodeOf[node] = index;
        for (int child : from.children) {
            const int copied = self(self, child);
            out.nodes[std::size_t(index)].children.push_back(copied);
        }
        return index;
    };
    for (int top : tops) {
        // The parent's own world transform, not the node's times its inverse: an animated node may have a
        // scale of 0 at rest (hidden until its animation shows it).
        const int above = parent[std::size_t(top)];
        Node holder;
        holder.transform = above < 0 ? Eigen::Matrix4d::Identity() : world[std::size_t(above)];
        const int held = int(out.nodes.size());
        out.roots.push_back(held);
        out.nodes.push_back(std::move(holder));
        const int copied = copy(copy, top);
        out.nodes[std::size_t(held)].children.push_back(copied);
    }
    keepSkins(input, nodeOf, out);
    std::size_t undrawn = 0;  // channels of nodes that no root reaches
    for (Animation animation : input.animations) {
        std::vector<AnimationChannel> kept;
        for (AnimationChannel& channel : animation.channels) {
            const auto copied = nodeOf.find(channel.node);
            if (copied == nodeOf.end()) {
                ++undrawn;
                continue;
            }
            channel.node = copied->second;
            kept.push_back(std::move(channel));
        }
        animation.channels = std::move(kept);
        if (!animation.channels.empty()) out.animations.push_back(std::move(animation));
    }
    if (undrawn)
        out.warnings.push_back(std::to_string(undrawn) +
                               " animation channels of nodes the scene does not draw left out");
    return nodeOf.size();
}

}  // namespace symcompress
