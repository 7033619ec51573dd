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
        // The writer USEs a geometry node written before with the same text (x3dWriter): one more material costs
        // a Group of a Shape, its Appearance and geometry USEd (some 130 bytes), and the first one's DEF.
        model.materialVariantBytes = [](const Primitive&) { return 140.0; };
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
        // The writer stores a primitive's geometry once for every material (gltfWriter): one more material costs
        // a mesh whose primitive names the same accessors, each attribute named again in Draco's extension.
        model.materialVariantBytes = [draco = write.draco](const Primitive& part) {
            std::size_t attributes = 1 + !part.normals.empty() + !part.texcoords.empty() + !part.colors.empty(),
                        names = 8 + (part.normals.empty() ? 0 : 6) + (part.texcoords.empty() ? 0 : 10) +
                                (part.colors.empty() ? 0 : 7);
            for (const VertexAttribute& attribute : part.attributes) ++attributes, names += attribute.name.size();
            // {"primitives":[{"attributes":{..},"material":N,"indices":N}]}, and Draco's {"bufferView":N,..}
            return 56.0 + double(names + 6 * attributes) * (draco ? 2 : 1) + (draco ? 64 : 12);
        };
    }
    return model;
}

}  // namespace symcompress
