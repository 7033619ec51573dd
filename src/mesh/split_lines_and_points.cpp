// A mesh's lines and points apart from its triangles, so that the triangles are still tiled (scene_ops.hpp).
#include "symcompress/scene_ops.hpp"

#include <algorithm>

namespace symcompress {

std::size_t splitLinesAndPoints(Scene& scene) {
    std::vector<int> skinned(scene.meshes.size(), 0);
    for (const Node& node : scene.nodes)
        if (node.mesh >= 0 && (node.skin >= 0 || !node.weights.empty())) skinned[std::size_t(node.mesh)] = 1;
    std::vector<int> apart(scene.meshes.size(), -1);  // mesh -> the mesh of its lines and points
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        const auto triangles = [](const Primitive& p) { return p.topology == Topology::Triangles; };
        const std::size_t count = std::count_if(mesh.primitives.begin(), mesh.primitives.end(), triangles);
        // Morph targets and skins move what a node draws: a child node would need their weights and joints.
        if (count == 0 || count == mesh.primitives.size() || morphTargetCount(mesh) > 0 || skinned[m]) continue;
        const auto firstOther = std::stable_partition(mesh.primitives.begin(), mesh.primitives.end(), triangles);
        Mesh others;
        others.name = mesh.name;
        others.primitives.assign(std::make_move_iterator(firstOther), std::make_move_iterator(mesh.primitives.end()));
        mesh.primitives.erase(firstOther, mesh.primitives.end());
        apart[m] = int(scene.meshes.size());
        scene.meshes.push_back(std::move(others));
    }
    std::size_t split = 0;
    for (std::size_t n = 0, nodes = scene.nodes.size(); n < nodes; ++n) {
        const int mesh = scene.nodes[n].mesh;
        if (mesh < 0 || apart[std::size_t(mesh)] < 0) continue;
        Node child;
        child.mesh = apart[std::size_t(mesh)];
        scene.nodes[n].children.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(std::move(child));
        ++split;
    }
    return split;
}

}  // namespace symcompress
