// The cost model of each output format: what its writer measures for a part and a node.
#include "symcompress/detail/compression_plan.hpp"

namespace symcompress {

namespace {
// Draco speed 7 for the quick measure: a few times faster than speed 0, and two ways of storing one part compare
// alike at either.
constexpr int kQuickCompressionLevel = 3;
}  // namespace

StorageCostModel costModelFor(FileFormat format, const WriteOptions& write) {
    StorageCostModel model;
    if (format == FileFormat::X3d) {
        // Every part measured by the X3D writer itself, a Transform with a USE per instance.
        model.bytesPerInstance = 150;
        model.meshBytes = [write](const Primitive& part) { return double(x3dMeshBytes(part, write)); };
        model.nodeBytes = [](const Node& node) { return double(x3dNodeBytes(node)); };
    } else {
        // glTF: every part measured by the writer, Draco's positions on the grid its quantization uses.
        model.seamGridBits = write.draco ? write.positionBits : 0;
        model.seamGridRelativeError = write.draco ? write.maxRelativePositionError : 0;
        model.meshBytes = [write](const Primitive& part) { return double(gltfMeshBytes(part, write)); };
        WriteOptions once = write;
        once.encodingTrials = false;
        once.compressionLevel = std::min(write.compressionLevel, kQuickCompressionLevel);
        model.quickMeshBytes = [once](const Primitive& part) { return double(gltfMeshBytes(part, once)); };
        model.nodeBytes = [](const Node& node) { return double(gltfNodeBytes(node)); };
        model.nodesBytes = [write](const std::vector<Node>& nodes) { return gltfNodesBytes(nodes, write); };
    }
    return model;
}

}  // namespace symcompress
