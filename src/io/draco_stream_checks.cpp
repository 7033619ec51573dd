#include "draco_stream_checks.hpp"

#include <draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_portable_decoder.h>
#include <draco/compression/attributes/prediction_schemes/prediction_scheme_wrap_decoding_transform.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/varint_decoding.h>
#include <draco/mesh/corner_table.h>
#include <draco/mesh/mesh_attribute_corner_table.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

#include <cstdint>
#include <optional>

namespace symcompress {
namespace {

// What a Draco mesh stream says it holds, from the counts at the head of its connectivity (10^8 triangles
// claimed by 263 bytes cost libdraco 10 s and 2.3 GB before these checks).
struct DracoCounts {
    bool edgebreaker = false;
    bool standardTraversal = false;  // edgebreaker's plain symbol coding: at least one bit per symbol
    std::uint32_t faces = 0;
    std::uint32_t vertices = 0;  // sequential: points; edgebreaker: the connectivity's vertices
    std::uint32_t symbols = 0;   // edgebreaker: one per triangle but the first of each part
    std::uint32_t splitSymbols = 0;
    std::size_t bytesAfterCounts = 0;
};

// The counts of a Draco 2.2 mesh stream (what libdraco 1.5 and the encoders in use write; older streams are
// left to libdraco), or nothing when the stream is something else or too short to hold them.
std::optional<DracoCounts> dracoCounts(const char* data, std::size_t size) {
    draco::DecoderBuffer buffer;
    buffer.Init(data, size);
    draco::DracoHeader header;
    if (!draco::PointCloudDecoder::DecodeHeader(&buffer, &header).ok()) return std::nullopt;
    if (header.encoder_type != draco::TRIANGULAR_MESH || header.version_major != 2 || header.version_minor != 2)
        return std::nullopt;
    buffer.set_bitstream_version(DRACO_BITSTREAM_VERSION(2, 2));
    if (header.flags & METADATA_FLAG_MASK) {
        draco::GeometryMetadata metadata;
        if (!draco::MetadataDecoder().DecodeGeometryMetadata(&buffer, &metadata)) return std::nullopt;
    }
    DracoCounts counts;
    if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
        if (!draco::DecodeVarint(&counts.faces, &buffer) || !draco::DecodeVarint(&counts.vertices, &buffer))
            return std::nullopt;
    } else if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) {
        counts.edgebreaker = true;
        std::uint8_t traversal = 0, attributeData = 0;
        if (!buffer.Decode(&traversal) || !draco::DecodeVarint(&counts.vertices, &buffer) ||
            !draco::DecodeVarint(&counts.faces, &buffer) || !buffer.Decode(&attributeData) ||
            !draco::DecodeVarint(&counts.symbols, &buffer) || !draco::DecodeVarint(&counts.splitSymbols, &buffer))
            return std::nullopt;
        counts.standardTraversal = traversal == draco::MESH_EDGEBREAKER_STANDARD_ENCODING;
    } else {
        return std::nullopt;
    }
    counts.bytesAfterCounts = static_cast<std::size_t>(buffer.remaining_size());
    return counts;
}

// Triangles per vertex an edgebreaker stream may claim: a closed surface has 2V - 4 + 4g, and the genus of
// real models stays far below the number of their vertices, so 8 is generous.
constexpr std::uint64_t kMaxDracoFacesPerVertex = 8;

// libdraco's DecodePredictionData of the portable texture-coordinate predictor, with one check added: the
// orientation count, an int32 read from the stream, at most the number of values the scheme predicts (each
// prediction takes at most one orientation). libdraco 1.5.5 loops over any count, one bit decoder step each
// past the end of its data: four corrupt bytes made it run 1.9e9 steps (11 s). The rest is libdraco's code as
// it is (draco/compression/attributes/prediction_schemes/mesh_prediction_scheme_tex_coords_portable_decoder.h,
// Apache 2.0, Copyright 2017 The Draco Authors). libdraco calls it through its virtual table, whose entry the
// dynamic linker binds to this explicit specialization, a strong definition, over libdraco's weak one.
template <class MeshDataT>
bool decodeOrientationsBounded(const MeshDataT& meshData,
                               draco::MeshPredictionSchemeTexCoordsPortablePredictor<int, MeshDataT>& predictor,
                               draco::DecoderBuffer* buffer) {
    std::int32_t orientations = 0;
    if (!buffer->Decode(&orientations) || orientations < 0) return false;
    if (!meshData.data_to_corner_map() ||
        static_cast<std::size_t>(orientations) > meshData.data_to_corner_map()->size())
        return false;
    predictor.ResizeOrientations(orientations);
    bool lastOrientation = true;
    draco::RAnsBitDecoder decoder;
    if (!decoder.StartDecoding(buffer)) return false;
    for (int i = 0; i < orientations; ++i) {
        if (!decoder.DecodeNextBit()) lastOrientation = !lastOrientation;
        predictor.set_orientation(i, lastOrientation);
    }
    decoder.EndDecoding();
    return true;
}

}  // namespace

std::string dracoStreamProblem(const char* stream, std::size_t size, std::size_t declaredPoints) {
    const std::optional<DracoCounts> counts = dracoCounts(stream, size);
    if (!counts) return {};
    const char* kind = counts->edgebreaker ? " vertices" : " points";
    if (counts->vertices > declaredPoints)
        return "the Draco stream claims " + std::to_string(counts->vertices) + kind + ", more than the " +
               std::to_string(declaredPoints) + " its POSITION accessor declares";
    const std::uint64_t vertices = std::uint64_t(counts->vertices) + counts->splitSymbols;
    if (counts->edgebreaker && counts->faces > kMaxDracoFacesPerVertex * vertices + kMaxDracoFacesPerVertex)
        return "the Draco stream claims " + std::to_string(counts->faces) + " triangles on " +
               std::to_string(vertices) + " vertices, more than " + std::to_string(kMaxDracoFacesPerVertex) +
               " per vertex (a broken stream)";
    if (counts->standardTraversal && counts->symbols / 8 > counts->bytesAfterCounts)
        return "the Draco stream claims " + std::to_string(counts->symbols) + " edgebreaker symbols, more than its " +
               std::to_string(counts->bytesAfterCounts) + " remaining bytes can code at one bit each";
    return {};
}

}  // namespace symcompress

// The two instantiations libdraco 1.5.5 has (edgebreaker's corner table, and the attribute corner table of
// attributes with seams).
namespace draco {

using WrapTransform = PredictionSchemeWrapDecodingTransform<int, int>;

template <>
bool MeshPredictionSchemeTexCoordsPortableDecoder<int, WrapTransform, MeshPredictionSchemeData<CornerTable>>::
    DecodePredictionData(DecoderBuffer* buffer) {
    return symcompress::decodeOrientationsBounded(this->mesh_data(), predictor_, buffer) &&
           MeshPredictionSchemeDecoder<int, WrapTransform, MeshPredictionSchemeData<CornerTable>>::
               DecodePredictionData(buffer);
}

template <>
bool MeshPredictionSchemeTexCoordsPortableDecoder<int, WrapTransform,
                                                  MeshPredictionSchemeData<MeshAttributeCornerTable>>::
    DecodePredictionData(DecoderBuffer* buffer) {
    return symcompress::decodeOrientationsBounded(this->mesh_data(), predictor_, buffer) &&
           MeshPredictionSchemeDecoder<int, WrapTransform, MeshPredictionSchemeData<MeshAttributeCornerTable>>::
               DecodePredictionData(buffer);
}

}  // namespace draco
