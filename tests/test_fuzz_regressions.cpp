// Inputs that crashed, hung, allocated without bound or ran into undefined behaviour in the readers, found
// by the fuzz targets of fuzz/ and by reading the readers with them in mind (issue 19). Each is now a clear
// FileError naming the file and what is wrong, or read as the format says. The small ones are files in
// tests/fuzz_regressions/; the deep ones are written here, as they are large.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

fs::path regressionInput(const std::string& name) {
    return fs::path(SYMCOMPRESS_SOURCE_DIR) / "tests" / "fuzz_regressions" / name;
}

// The message of the FileError that reading `file` gives; any other exception fails the test.
std::string readError(const fs::path& file) {
    try {
        readScene(file);
    } catch (const FileError& error) {
        return error.what();
    }
    FAIL("read without an error: " << file);
    return "";
}

// A gzip file of about 1032 * `zeroBytes` zero bytes in about `zeroBytes` bytes: deflate's densest coding, one
// dynamic Huffman block in which length 258 and distance 1 have one-bit codes, so that each 258 bytes take two
// zero bits. Built by hand, as zlib takes seconds per gigabyte to compress.
std::string gzipBomb(std::size_t zeroBytes) {
    std::string out("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03", 10);
    unsigned pending = 0, count = 0;
    const auto bits = [&](unsigned value, unsigned length) {  // fields go least significant bit first
        for (unsigned bit = 0; bit < length; ++bit) {
            pending |= ((value >> bit) & 1u) << count;
            if (++count == 8) {
                out += static_cast<char>(pending);
                pending = count = 0;
            }
        }
    };
    const auto code = [&](unsigned value, unsigned length) {  // Huffman codes most significant bit first
        for (unsigned bit = length; bit-- > 0;) bits((value >> bit) & 1u, 1);
    };
    bits(1, 1);  // the last block
    bits(2, 2);  // dynamic Huffman codes
    bits(286 - 257, 5);
    bits(1 - 1, 5);
    bits(19 - 4, 4);
    // The code length code's lengths, in deflate's order 16 17 18 0 8 7 9 6 10 5 11 4 12 3 13 2 14 1 15: 18 (a
    // run of zero lengths, 7 bits for 11 to 138 of them) gets '0', lengths 1 and 2 get '10' and '11'.
    for (unsigned length : {0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0}) bits(length, 3);
    const auto zeroLengths = [&](unsigned run) {
        code(0, 1);
        bits(run - 11, 7);
    };
    // Literal 0 and end of block get 2 bits ('10', '11'), length 258 (285) gets 1 ('0'), distance 1 gets 1 ('0').
    code(3, 2);        // literal 0: 2
    zeroLengths(138);  // literals 1 to 138: none
    zeroLengths(117);  // 139 to 255: none
    code(3, 2);        // end of block: 2
    zeroLengths(28);   // lengths 3 to 257: none
    code(2, 2);        // length 258: 1
    code(2, 2);        // distance 1: 1
    code(2, 2);        // the data: literal 0
    std::uint64_t copies = 4 * std::uint64_t(zeroBytes);
    for (; count != 0; ++copies) bits(0, 2);  // until the bits fill whole bytes: the header has an even count
    out.append(zeroBytes, '\0');
    code(3, 2);  // end of block
    if (count != 0) bits(0, 8 - count);
    const std::uint64_t size = 1 + 258 * copies;
    std::vector<unsigned char> zeros(1 << 20, 0);
    uLong crc = crc32(0, zeros.data(), 1);
    const uLong chunk = crc32(0, zeros.data(), static_cast<uInt>(zeros.size()));
    for (std::uint64_t left = size - 1; left > 0;) {
        const std::uint64_t piece = std::min<std::uint64_t>(left, zeros.size());
        crc = crc32_combine(crc, piece == zeros.size() ? chunk : crc32(0, zeros.data(), uInt(piece)), z_off_t(piece));
        left -= piece;
    }
    for (const std::uint64_t field : {std::uint64_t(crc), size})
        for (int byte = 0; byte < 4; ++byte) out += static_cast<char>((field >> (8 * byte)) & 0xff);
    return out;
}

bool hasWarning(const Scene& scene, const std::string& text) {
    for (const std::string& warning : scene.warnings)
        if (warning.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("glTF: an EXT_meshopt_compression fallback that is a number is no fallback, not an exception", "[io][fuzz]") {
    // fuzz_gltf: nlohmann's type_error escaped the reader and aborted the process.
    const std::string error = readError(regressionInput("gltf_meshopt_fallback_number.gltf"));
    CHECK_THAT(error, Catch::Contains("gltf_meshopt_fallback_number.gltf"));
}

TEST_CASE("glTF: a required extension symcompress cannot read is named, before its data upsets the layout",
          "[io][fuzz]") {
    // As gltfpack -cz wrote KHR_meshopt_compression before symcompress read it: a fallback buffer that claims
    // bytes the file does not have; tinygltf said "Invalid `byteLength'".
    TemporaryFolder folder;
    writeTextFile(folder / "unknown.gltf",
                  R"({"asset": {"version": "2.0"}, "extensionsUsed": ["EXT_unknown_compression"],
                      "extensionsRequired": ["EXT_unknown_compression"],
                      "buffers": [{"byteLength": 40716, "extensions": {"EXT_unknown_compression": {"fallback": true}}}]})");
    CHECK_THAT(readError(folder / "unknown.gltf"),
               Catch::Contains("unknown.gltf: requires the extension EXT_unknown_compression, which symcompress "
                               "cannot read"));
}

TEST_CASE("glTF: a buffer view whose byteOffset + byteLength wraps around is refused", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_view_range_wraps.gltf"));
    CHECK_THAT(error, Catch::Contains("gltf_view_range_wraps.gltf: POSITION (accessor 0): buffer view runs past the end"));
}

TEST_CASE("glTF: an accessor count whose count * components and (count - 1) * stride wrap is refused", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_accessor_count_wraps.gltf"));
    CHECK_THAT(error, Catch::Contains("POSITION (accessor 0): 6148914691236517206 elements run past the end of its buffer view"));
}

TEST_CASE("glTF: a huge count without a buffer view is refused before anything is allocated", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_count_without_view.gltf"));
    CHECK_THAT(error, Catch::Contains("NORMAL (accessor 1): a count of 2305843009213693952 without a buffer view"));
}

TEST_CASE("glTF: indices without a buffer view are zeros, as the specification says, and not too many of them",
          "[io][fuzz]") {
    // How symcompress writes triangles of zero area; tinygltf alone refuses such indices.
    auto file = [](std::size_t count, int componentType) {
        return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
            "buffers":[{"byteLength":12,"uri":"data:application/octet-stream;base64,AACAPwAAAEAAAEBA"}],
            "bufferViews":[{"buffer":0,"byteLength":12}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":1,"type":"VEC3","min":[1,2,3],"max":[1,2,3]},
                         {"componentType":)" +
               std::to_string(componentType) + R"(,"count":)" + std::to_string(count) + R"(,"type":"SCALAR"}]})";
    };
    TemporaryFolder folder;
    writeTextFile(folder / "zeros.gltf", file(3000, 5121));
    const Scene scene = readScene(folder / "zeros.gltf");
    const std::vector<Triangle>& triangles = scene.meshes.at(0).primitives.at(0).triangles;
    CHECK(triangles.size() == 1000);
    CHECK(std::all_of(triangles.begin(), triangles.end(), [](const Triangle& t) { return t == Triangle{0, 0, 0}; }));
    writeTextFile(folder / "huge.gltf", file(std::size_t(1) << 30, 5125));
    CHECK_THAT(readError(folder / "huge.gltf"),
               Catch::Contains("huge.gltf: accessor 1: 1073741824 indices without a buffer view, more than"));
    // A component type that is no number is tinygltf's to refuse, not a JSON exception.
    std::string typeless = file(3, 5121);
    typeless.replace(typeless.rfind("5121"), 4, "\"byte\"");
    writeTextFile(folder / "typeless.gltf", typeless);
    CHECK_THAT(readError(folder / "typeless.gltf"), Catch::Contains("typeless.gltf"));
}

TEST_CASE("glTF: a COLOR_0 accessor that does not exist is a clear error and not std::out_of_range", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_color_accessor_missing.gltf"));
    CHECK_THAT(error, Catch::Contains("gltf_color_accessor_missing.gltf: mesh 0 primitive 0 refers to accessor 7 for "
                                      "its COLOR_0, but the file has 1 accessor"));
}

TEST_CASE("glTF: sparse indices stored as floats are refused before any is converted", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_sparse_float_indices.gltf"));
    CHECK_THAT(error, Catch::Contains("POSITION (accessor 0): sparse indices must be unsigned integers"));
}

TEST_CASE("glTF: an EXT_mesh_gpu_instancing accessor index beyond int is not cast", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_instancing_index_real.gltf"));
    CHECK_THAT(error, Catch::Contains("TRANSLATION: accessor -1 does not exist"));
}

TEST_CASE("glTF: an EXT_meshopt_compression byteStride beyond int is refused before it is cast", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_meshopt_stride_huge.gltf"));
    CHECK_THAT(error, Catch::Contains("buffer view 0 (EXT_meshopt_compression): buffer, byteOffset, byteLength, byteStride or count"));
}

TEST_CASE("glTF: without scenes the GPU instances and a channel naming an instance's index stay inside the node list",
          "[io][fuzz]") {
    const Scene scene = readScene(regressionInput("gltf_instances_without_scenes.gltf"));
    CHECK(scene.roots == std::vector<int>{0});
    REQUIRE(scene.nodes.size() == 3);
    CHECK(scene.nodes[0].children == std::vector<int>{1, 2});
    CHECK(scene.animations.empty());
    CHECK(hasWarning(scene, "animation 0 channel 0 refers to node 1 for its target, but the file has 1 node"));
}

TEST_CASE("glTF: a node index beyond int is refused and not cut down to another index", "[io][fuzz]") {
    const std::string error = readError(regressionInput("gltf_mesh_index_beyond_int.gltf"));
    CHECK_THAT(error, Catch::Contains("gltf_mesh_index_beyond_int.gltf: \"mesh\": 4294967296 does not fit a 32-bit integer"));
}

TEST_CASE("glTF: a chain of 100000 nodes is refused before anything recurses over it", "[io][fuzz]") {
    TemporaryFolder folder;
    std::string nodes;
    for (int n = 0; n < 100000; ++n) nodes += "{\"children\":[" + std::to_string(n + 1) + "]},";
    nodes += "{}";
    writeTextFile(folder / "chain.gltf", "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[" + nodes + "],\"scenes\":[{\"nodes\":[0]}]}");
    CHECK_THAT(readError(folder / "chain.gltf"), Catch::Contains("chain.gltf: nodes nested deeper than 256 levels"));
}

TEST_CASE("glTF: extras nested 100000 levels deep do not exhaust the stack", "[io][fuzz]") {
    TemporaryFolder folder;
    const std::string extras = std::string(100000, '[') + std::string(100000, ']');
    writeTextFile(folder / "deep.gltf", "{\"asset\":{\"version\":\"2.0\",\"extras\":" + extras + "}}");
    CHECK_THAT(readError(folder / "deep.gltf"), Catch::Contains("deep.gltf: JSON nested deeper than 512 levels"));
}

TEST_CASE("X3D: a Background nesting 200000 elements does not exhaust the stack", "[io][fuzz]") {
    TemporaryFolder folder;
    std::string nested;
    for (int level = 0; level < 200000; ++level) nested += "<Group>";
    for (int level = 0; level < 200000; ++level) nested += "</Group>";
    writeTextFile(folder / "deep.x3d", "<X3D><Scene><Background>" + nested + "</Background></Scene></X3D>");
    CHECK_THAT(readError(folder / "deep.x3d"), Catch::Contains("deep.x3d: XML elements nested deeper than 300 levels"));
}

TEST_CASE("X3D: a gzip bomb is refused once it inflates past 2 GiB, and a genuine .x3dz still reads", "[io][fuzz]") {
    TemporaryFolder folder;
    // 2.1 MB that inflate to 2.17 GB (2^31 bytes and a little more).
    writeTextFile(folder / "bomb.x3dz", gzipBomb(std::size_t(2100) << 10));
    CHECK_THAT(readError(folder / "bomb.x3dz"),
               Catch::Contains("bomb.x3dz: the gzip data inflates to more than 2 GiB of XML"));
    // The same coding, 1 MB of it: valid gzip (zeros, which are no X3D) under the limit.
    writeTextFile(folder / "small.x3dz", gzipBomb(1000));
    CHECK_THAT(readError(folder / "small.x3dz"), !Catch::Contains("gzip"));
    const Scene scene = readScene(fs::path(SYMCOMPRESS_SOURCE_DIR) / "fuzz" / "corpus" / "x3d" / "faces.x3dz");
    CHECK(!scene.meshes.empty());
}

TEST_CASE("X3D: a coordIndex value beyond 32 bits is refused before it is converted", "[io][fuzz]") {
    const std::string error = readError(regressionInput("x3d_coord_index_huge.x3d"));
    CHECK_THAT(error, Catch::Contains("x3d_coord_index_huge.x3d: <IndexedFaceSet>: coordIndex holds 1000000000000000019884624838656"));
}

TEST_CASE("X3D: a whichChoice beyond 32 bits is refused before it is converted", "[io][fuzz]") {
    const std::string error = readError(regressionInput("x3d_which_choice_huge.x3d"));
    CHECK_THAT(error, Catch::Contains("<Switch>: whichChoice holds"));
}

TEST_CASE("X3D: key times that do not fit a float are left out and not cast", "[io][fuzz]") {
    const Scene scene = readScene(regressionInput("x3d_cycle_interval_huge.x3d"));
    CHECK(scene.animations.empty());
    CHECK(hasWarning(scene, "1 animation ROUTEs left out"));
}

TEST_CASE("X3D: a key before the cycle's start is left out, as glTF's times start at 0", "[io][fuzz]") {
    const Scene scene = readScene(regressionInput("x3d_animation_key_negative.x3d"));
    CHECK(scene.animations.empty());
    CHECK(hasWarning(scene, "1 animation ROUTEs left out"));
}

// Found by fuzz_gltf on the first day vertex attributes came through: an attribute named "NOfalseRMAL" (no glTF
// attribute), holding -1, which the Draco writer cast to a joint index's unsigned short (undefined) whatever its
// name. Unknown names are now left out by the reader (the file written would be invalid with them); an
// application's own attribute and a second UV set with negative values go through Draco as floats.
TEST_CASE("glTF: an attribute glTF does not name is left out, and negative attribute values go through Draco",
          "[io][fuzz]") {
    const Scene read = readScene(regressionInput("gltf_attribute_name_unknown.gltf"));
    CHECK(hasWarning(read, "attribute NOfalseRMAL not carried through: glTF has no such attribute"));
    TemporaryFolder folder;
    writeScene(read, folder / "read.glb");
    CHECK_NOTHROW(readScene(folder / "read.glb"));

    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.triangles = {{0, 1, 2}};
    triangle.attributes = {{"TEXCOORD_1", 2, {-1, -2, 0.5, -0.25, 3, 4}}, {"_TEMPERATURE", 1, {-1, 0, 2.5}}};
    writeScene(sceneOfOneMesh("hot", triangle), folder / "hot.glb");
    const Scene back = readScene(folder / "hot.glb");
    REQUIRE(back.meshes.size() == 1);
    const Primitive& out = back.meshes[0].primitives.at(0);
    REQUIRE(out.attributes.size() == 2);
    // Draco may reorder the vertices: each vertex's values, found by its position.
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
        const auto source = std::size_t(std::find(triangle.positions.begin(), triangle.positions.end(), out.positions[v]) -
                                        triangle.positions.begin());
        REQUIRE(source < 3);
        CHECK(out.attributes[0].name == "TEXCOORD_1");
        // The UV set quantized as the first (12 bits over its span of 6: steps of 0.0015), the other as it is.
        CHECK(out.attributes[0].values[2 * v] == Approx(triangle.attributes[0].values[2 * source]).margin(1.5e-3));
        CHECK(out.attributes[0].values[2 * v + 1] == Approx(triangle.attributes[0].values[2 * source + 1]).margin(1.5e-3));
        CHECK(out.attributes[1].name == "_TEMPERATURE");
        CHECK(out.attributes[1].values[v] == triangle.attributes[1].values[source]);
    }
}

TEST_CASE("glTF: negative key times are left out with a warning, where X3D output made keys of -inf", "[io][fuzz]") {
    const fs::path input = regressionInput("gltf_animation_times_negative.gltf");
    const Scene scene = readScene(input);
    CHECK(scene.animations.empty());
    CHECK(hasWarning(scene, "animation 0 channel 0 ignored: negative key times"));
    TemporaryFolder folder;
    writeScene(scene, folder / "written.x3d");
    CHECK(readScene(folder / "written.x3d").meshes.size() == 1);
}

TEST_CASE("PLY: an element count that the rest of the file cannot hold is refused before it is read", "[io][fuzz]") {
    const std::string error = readError(regressionInput("ply_count_beyond_bytes.ply"));
    CHECK_THAT(error, Catch::Contains("ply_count_beyond_bytes.ply: element 'vertex' has a count of 100000000000000, more than"));
}

TEST_CASE("PLY: an element of 10^14 items without properties holds nothing and is passed at once", "[io][fuzz]") {
    const Scene scene = readScene(regressionInput("ply_element_of_nothing.ply"));
    REQUIRE(scene.meshes.size() == 1);
    CHECK(scene.meshes[0].primitives[0].triangles.size() == 1);
    CHECK(hasWarning(scene, "1 elements other than vertex and face ignored"));
}

TEST_CASE("Writers: names read from X3D that are not UTF-8 are written to glTF and read back", "[io][fuzz]") {
    const Scene scene = readScene(regressionInput("x3d_names_not_utf8.x3d"));
    TemporaryFolder folder;
    for (const char* name : {"names.glb", "names.gltf", "names.x3d"}) {
        writeScene(scene, folder / name);
        CHECK(readScene(folder / name).meshes.size() == scene.meshes.size());
    }
}

TEST_CASE("X3D meta tags that are not UTF-8 are read, written to every format and reported", "[io][fuzz]") {
    // Found by fuzz_x3d: a meta tag's name with a byte that is no UTF-8 threw from the JSON the tags are kept in.
    const Scene scene = readScene(regressionInput("x3d_meta_not_utf8.x3d"));
    CHECK(!scene.extrasJson.empty());
    TemporaryFolder folder;
    for (const char* name : {"meta.glb", "meta.gltf", "meta.x3d"}) {
        writeScene(scene, folder / name);
        CHECK(readScene(folder / name).meshes.size() == scene.meshes.size());
    }
    const CompressionReport report = compressFile(regressionInput("x3d_meta_not_utf8.x3d"), folder / "out.glb");
    CHECK(nlohmann::json::parse(report.json()).contains("output"));
}

TEST_CASE("Writers: an OBJ texture name with control bytes is written to X3D that reads back", "[io][fuzz]") {
    // Found by fuzz_obj: a map_Kd name holding a NUL and a BEL made the X3D writer's url malformed XML.
    TemporaryFolder folder;
    writeTextFile(folder / "part.obj", "mtllib part.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                       "usemtl m\nf 1/1 2/2 3/3\n");
    writeTextFile(folder / "part.mtl", std::string("newmtl m\nmap_Kd a") + '\0' + "b\x07c.png\n");
    const Scene scene = readScene(folder / "part.obj");
    REQUIRE(scene.textures.size() == 1);
    writeScene(scene, folder / "part.x3d");
    const Scene back = readScene(folder / "part.x3d");
    CHECK(back.meshes.size() == scene.meshes.size());
    REQUIRE(back.textures.size() == 1);
    CHECK(back.textures[0].uri.find('\0') == std::string::npos);
}

TEST_CASE("GLB: an image whose buffer view runs past its buffer is refused before its bytes are copied", "[io][fuzz]") {
    const std::string error = readError(regressionInput("glb_image_view_past_buffer.glb"));
    CHECK_THAT(error, Catch::Contains("glb_image_view_past_buffer.glb: invalid glTF: image 0: its buffer view runs past the end"));
}

TEST_CASE("GLB: a BIN chunk that runs past the end of the file is refused before tinygltf copies it", "[io][fuzz]") {
    const std::string error = readError(regressionInput("glb_bin_chunk_past_end.glb"));
    CHECK_THAT(error, Catch::Contains("glb_bin_chunk_past_end.glb: the BIN chunk (40 bytes) runs past the end of the file"));
}

// A Draco stream's counts (its triangles, vertices and edgebreaker symbols) raised in a valid GLB: libdraco
// sized its tables and ran its traversal by them (10^8 triangles in 263 bytes: 10 s and 2.3 GB before it gave
// up). The counts are checked against the POSITION accessor and the stream's bytes first.
TEST_CASE("GLB: a Draco stream claiming 10^8 triangles on 4 vertices is refused before libdraco decodes it",
          "[io][fuzz]") {
    CHECK_THAT(readError(regressionInput("glb_draco_faces_huge.glb")),
               Catch::Contains("glb_draco_faces_huge.glb: mesh 0 primitive 0: the Draco stream claims 100000000 "
                               "triangles on 4 vertices, more than 8 per vertex"));
    CHECK_THAT(readError(regressionInput("glb_draco_vertices_undeclared.glb")),
               Catch::Contains("the Draco stream claims 100000000 vertices, more than the 4 its POSITION accessor "
                               "declares"));
    // A sequential stream (no edgebreaker) names its points.
    CHECK_THAT(readError(regressionInput("glb_draco_sequential_points.glb")),
               Catch::Contains("the Draco stream claims 100000000 points, more than the 4 its POSITION accessor "
                               "declares"));
    // With the accessors' counts raised to match, the symbols still cannot fit the stream's bytes.
    CHECK_THAT(readError(regressionInput("glb_draco_symbols_past_bytes.glb")),
               Catch::Contains("the Draco stream claims 100000000 edgebreaker symbols, more than its"));
}

// The count of texture-coordinate orientations in a Draco stream (four bytes of draco_primitives.glb's first
// stream changed), found by fuzz_glb as a slow unit: libdraco 1.5.5 looped over any count past the end of its data
// (2^31 - 1: 10.5 s in the Release build, 19 s in the fuzz build) and then read the file. The count is now bounded
// by the values the scheme predicts (559 here), inside libdraco's decoder (src/io/draco_stream_checks.cpp); one
// more than that was read before too.
TEST_CASE("GLB: a Draco texture-coordinate orientation count beyond the values it predicts is refused",
          "[io][fuzz]") {
    for (const char* name : {"glb_draco_orientations_huge.glb", "glb_draco_orientations_past_values.glb"})
        CHECK_THAT(readError(regressionInput(name)),
                   Catch::Contains(std::string(name) + ": mesh 0 primitive 0: Draco cannot decode the mesh"));
    CHECK_NOTHROW(readScene(fs::path(SYMCOMPRESS_SOURCE_DIR) / "fuzz" / "corpus" / "glb" / "draco_primitives.glb"));
}

TEST_CASE("GLB: an EXT_meshopt_compression TRIANGLES view of 17 indices is refused before meshoptimizer asserts",
          "[io][fuzz]") {
    // Found by fuzz_glb: the packaged meshoptimizer aborts on a count that is not a multiple of 3.
    CHECK_THAT(readError(regressionInput("glb_meshopt_triangles_count.glb")),
               Catch::Contains("buffer view 3 (EXT_meshopt_compression): mode TRIANGLES with a count of 17, which is "
                               "not a multiple of 3"));
}

TEST_CASE("Writers: values near float32's limit are refused by the Draco writer, where its quantization overflowed",
          "[io][fuzz]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    // Found by fuzz_ply: s = 2.5e38 and -2.5e38 span beyond float32; Draco's entropy coder then wrote through a
    // null pointer. Found by fuzz_stl: a z of -3.4e38 (float32's lowest) decoded as infinite.
    for (const std::string name : {"ply_texcoords_beyond_float.ply", "stl_position_float_lowest.stl"}) {
        const Scene scene = readScene(regressionInput(name));
        const std::string attribute = name[0] == 'p' ? "TEXCOORD_0" : "POSITION";
        CHECK_THROWS_WITH(writeScene(scene, folder / "out.glb"),
                          Catch::Contains("out.glb: " + attribute + " holds values beyond 8.5e37 in magnitude") &&
                              Catch::Contains("write with --no-draco"));
        writeScene(scene, folder / "plain.glb", plain);
        CHECK(readScene(folder / "plain.glb").meshes.size() == scene.meshes.size());
    }
    // Beyond float32 itself glTF cannot hold the value at all, with or without Draco (it was written as inf).
    writeTextFile(folder / "huge.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                  "property double z\nelement face 1\nproperty list uchar int vertex_indices\n"
                  "end_header\n0 0 0\n1e300 0 0\n0 1 0\n3 0 1 2\n");
    const Scene huge = readScene(folder / "huge.ply");
    for (const WriteOptions& options : {WriteOptions{}, plain})
        CHECK_THROWS_WITH(writeScene(huge, folder / "huge.glb", options),
                          Catch::Contains("huge.glb: POSITION holds values beyond float32's range (3.4e38)"));
}

TEST_CASE(
    "Writers: a further attribute near float32's limit goes through Draco unquantized, where quantizing it crashed",
    "[io][fuzz]") {
    // Found by fuzz_glb: a TEXCOORD_1 spanning -3e38 to 3e38 overflowed Draco's quantization, whose entropy
    // coder then read far out of bounds (SEGV). Such an attribute is now stored as read, exactly.
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.triangles = {{0, 1, 2}};
    triangle.attributes = {{"TEXCOORD_1", 2, {3e38, 0, -3e38, 1, 0.25, 0.5}}};
    TemporaryFolder folder;
    writeScene(sceneOfOneMesh("far", triangle), folder / "far.glb");
    const Scene back = readScene(folder / "far.glb");
    REQUIRE(back.meshes.size() == 1);
    const Primitive& out = back.meshes[0].primitives.at(0);
    REQUIRE(out.attributes.size() == 1);
    for (std::size_t v = 0; v < out.positions.size(); ++v) {
        const auto source =
            std::size_t(std::find(triangle.positions.begin(), triangle.positions.end(), out.positions[v]) -
                        triangle.positions.begin());
        REQUIRE(source < 3);
        for (int c = 0; c < 2; ++c)
            CHECK(out.attributes[0].values[2 * v + c] == double(float(triangle.attributes[0].values[2 * source + c])));
    }
}

TEST_CASE("glTF: an image or buffer URI naming a folder is not a file, where tinygltf asked for 2^63 bytes", "[io][fuzz]") {
    // Found by fuzz_obj: an OBJ texture name cut short by a NUL, its reference kept in the GLB written.
    TemporaryFolder folder;
    std::filesystem::create_directories(folder / "images");
    const std::string triangle = R"("buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}])";
    writeTextFile(folder / "image_folder.gltf", R"({"asset": {"version": "2.0"}, "images": [{"uri": "images"}], "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}], )" + triangle + "}");
    const Scene scene = readScene(folder / "image_folder.gltf");
    CHECK(hasWarning(scene, "('images') could not be read; its reference is kept"));
    writeTextFile(folder / "buffer_folder.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36, "uri": "images"}]})");
    CHECK_THAT(readError(folder / "buffer_folder.gltf"), Catch::Contains("buffer_folder.gltf"));
}

TEST_CASE("Writers: a whole-number bound beyond a 32-bit int reads back, where written as an integer it was refused",
          "[io][fuzz]") {
    // Found by fuzz_obj, fuzz_ply and fuzz_stl: a vertex at z = 12147483648, its accessor's "max" printed as an
    // integer, which the reader takes for an index out of int's range.
    const Scene scene = readScene(regressionInput("obj_coordinate_beyond_int.obj"));
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    for (const WriteOptions& options : {WriteOptions{}, plain}) {
        writeScene(scene, folder / "big.glb", options);
        CHECK(readScene(folder / "big.glb").meshes.size() == scene.meshes.size());
    }
}

TEST_CASE("Writers: a texture coordinate beyond float32's range is written to X3D as a number that reads back",
          "[io][fuzz]") {
    // Found by fuzz_obj: vt 1.3e117, printed through float32 as "inf", which the X3D reader refuses.
    TemporaryFolder folder;
    writeTextFile(folder / "part.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1.3e117 0.5\nf 1/1 2/2 3/3\n");
    const Scene scene = readScene(folder / "part.obj");
    REQUIRE(scene.meshes.at(0).primitives.at(0).texcoords.size() == 3);
    writeScene(scene, folder / "part.x3d");
    const Scene back = readScene(folder / "part.x3d");
    REQUIRE(back.meshes.size() == 1);
    const auto& texcoords = back.meshes[0].primitives.at(0).texcoords;
    CHECK(std::any_of(texcoords.begin(), texcoords.end(), [](const Eigen::Vector2d& t) { return t.x() == 1.3e117; }));
}

TEST_CASE("Readers: a NaN or infinite number in an OBJ file or its material library is refused, naming the file",
          "[io][fuzz]") {
    // Found by fuzz_obj: "Ks nan 0 0" became an X3D specularColor the X3D reader refuses.
    TemporaryFolder folder;
    const std::string triangle = "mtllib part.mtl\nusemtl shiny\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n";
    for (const std::string statement : {"Ks nan 0 0", "Kd 1 inf 0", "Ke 0 0 -inf", "Ns nan", "d nan", "Tr inf"}) {
        writeTextFile(folder / "part.obj", triangle);
        writeTextFile(folder / "part.mtl", "newmtl shiny\n" + statement + "\n");
        const std::string message = readError(folder / "part.obj");
        CHECK(message.find("part.mtl") != std::string::npos);
        CHECK(message.find("NaN or infinite") != std::string::npos);
    }
    for (const std::string line : {"v 0 0 0 nan 1 1", "vt nan 0", "vt 0 inf"}) {
        writeTextFile(folder / "part.obj", triangle + line + "\n");
        writeTextFile(folder / "part.mtl", "newmtl shiny\n");
        const std::string message = readError(folder / "part.obj");
        CHECK(message.find("part.obj") != std::string::npos);
        CHECK(message.find("NaN or infinite") != std::string::npos);
    }
}

TEST_CASE("Readers: OBJ colours beyond [0, 1] are clamped with a warning, not converted to infinite linear values",
          "[io][fuzz]") {
    // Found by fuzz_obj: "Kd 1 0.5 5.1e307", whose linear value overflowed, written as an X3D Color that does not
    // read back.
    TemporaryFolder folder;
    writeTextFile(folder / "part.obj", "mtllib part.mtl\nusemtl bright\nv 0 0 0 1 300 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeTextFile(folder / "part.mtl", "newmtl bright\nKd 1 0.5 5.1e307\nKs -2 0 1\n");
    const Scene scene = readScene(folder / "part.obj");
    const Material& material = scene.materials.at(0);
    CHECK(material.phong->diffuseColor == Eigen::Vector3d(1, 0.5, 1));
    CHECK(material.phong->specularColor == Eigen::Vector3d(0, 0, 1));
    CHECK(material.baseColorFactor.allFinite());
    const auto& colors = scene.meshes.at(0).primitives.at(0).colors;
    REQUIRE(colors.size() == 3);
    CHECK(colors[0].head<3>() == Eigen::Vector3d(1, 1, 0));
    auto warned = [&](const std::string& text) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                           [&](const std::string& warning) { return warning.find(text) != std::string::npos; });
    };
    CHECK(warned("part.mtl: colour components outside [0, 1] clamped"));
    CHECK(warned("part.obj: vertex colour components outside [0, 1] clamped"));
    for (const char* extension : {".x3d", ".glb"}) {
        writeScene(scene, folder / (std::string("part") + extension));
        CHECK(readScene(folder / (std::string("part") + extension)).meshes.size() == 1);
    }
}

TEST_CASE("glTF: a zero-area point written as zeros reads back from a file whose buffers are smaller than it",
          "[io][fuzz]") {
    // Found by fuzz_stl and fuzz_obj: triangles of zero area at the origin and hardly anything else. Their point's
    // position is an accessor without a buffer view (12 bytes of zeros) in a file of a 6-byte buffer, which the reader
    // refused as more zeros than the file's buffers could hold.
    TemporaryFolder folder;
    for (const std::string name : {"stl_zero_area_only.stl", "obj_zero_area_point.obj"}) {
        INFO(name);
        const Scene scene = readScene(regressionInput(name));
        writeScene(scene, folder / "out.glb");
        CHECK(worldMesh(readScene(folder / "out.glb")).triangles.size() == worldMesh(scene).triangles.size());
    }
}

TEST_CASE("X3D: a prototype's IS connect to a field whose name is no name is left out, and the output reads back",
          "[io][fuzz]") {
    // Found by fuzz_x3d: nodeField='>height' became an attribute the X3D writer wrote as it was, which no XML
    // reader reads.
    const Scene scene = readScene(regressionInput("x3d_prototype_field_not_a_name.x3d"));
    CHECK(std::any_of(scene.warnings.begin(), scene.warnings.end(), [](const std::string& warning) {
        return warning.find("an IS connect to the field '>height', which is no field's name, left out") !=
               std::string::npos;
    }));
    TemporaryFolder folder;
    writeScene(scene, folder / "written.x3d");
    CHECK(readScene(folder / "written.x3d").meshes.size() == scene.meshes.size());
}

TEST_CASE("X3D output: a mesh that draws nothing, drawn by several nodes, is neither DEF'd nor USEd", "[io][fuzz]") {
    // fuzz_glb, fuzz_gltf, fuzz_x3d: such a mesh had no DEF (its Shapes, none, not grouped), and the second
    // node's USE of it threw std::out_of_range from the writer.
    TemporaryFolder folder;
    for (const char* name : {"glb_x3d_use_of_mesh_drawing_nothing.glb", "x3d_use_of_mesh_drawing_nothing.x3d"}) {
        INFO(name);
        const Scene scene = readScene(regressionInput(name));
        CHECK_NOTHROW(writeScene(scene, folder / "out.x3d"));
        CHECK_NOTHROW(readScene(folder / "out.x3d"));
    }
}
