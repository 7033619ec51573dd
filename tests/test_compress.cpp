// symcompress IN -o OUT and symdecompress --verify: round trips that must rebuild the original surface,
// the report's keys, instancing where it pays, the Khronos validator on the output.
#include "common/color_space.hpp"
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/compression_plan.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/tiles.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <tuple>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

const std::string kSymcompress = SYMCOMPRESS_CLI;
const std::string kSymdecompress = SYMDECOMPRESS_CLI;

// Compressed by the library (compressFile) to NAME.EXTENSION, rebuilt and verified (decompressFile) against
// the original and against the digest stored in the file; the report's JSON.
nlohmann::json compressAndVerify(const std::filesystem::path& input, const TemporaryFolder& folder, const std::string& name,
                                 const CompressOptions& options = {}, const std::string& extension = ".glb") {
    const auto output = folder / (name + extension), flat = folder / (name + "-flat.glb");
    const CompressionReport report = compressFile(input, output, options);
    const RebuildReport verified = decompressFile(output, flat, input);
    CHECK(verified.verified);
    CHECK(verified.areaRatio == Approx(1).epsilon(1e-3));
    // Without the original, the digest stored in the file.
    const RebuildReport fromDigest = decompressFile(output, flat);
    CHECK(fromDigest.against == RebuildReport::Against::Digest);
    CHECK(fromDigest.verified);
    if (extension == ".glb" && interopAvailable()) CHECK(validatorErrors(output).empty());
    return nlohmann::json::parse(report.json());
}

// The scene as an uncompressed GLB in the folder: the input a user would start from.
std::filesystem::path writePlainGlb(const Scene& scene, const TemporaryFolder& folder, const std::string& name) {
    WriteOptions plain;
    plain.draco = false;
    const auto file = folder / (name + ".glb");
    writeScene(scene, file, plain);
    return file;
}

// A texture whose image is a PNG signature and a few bytes: carried as it is, never decoded.
Texture pngSignatureTexture() {
    Texture image;
    image.bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1, 2, 3};
    image.mimeType = "image/png";
    return image;
}

// Open edges (used by one triangle) after welding at `weld` of the diagonal (by default far below a 14-bit step).
std::ptrdiff_t openEdges(const TriangleMesh& mesh, double weld = 1e-6) {
    Eigen::AlignedBox3d box;
    for (const auto& p : mesh.positions) box.extend(p);
    const auto representative = weldPositions(mesh.positions, weld * box.diagonal().norm());
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (const Triangle& t : mesh.triangles)
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = representative[t[i]], b = representative[t[(i + 1) % 3]];
            if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
        }
    return std::count_if(uses.begin(), uses.end(), [](const auto& entry) { return entry.second == 1; });
}

// The scene (one symmetric part) compressed as its fundamental region: no open edge after quantization.
void checkRegionSeamsClosed(const Scene& scene, const std::string& name) {
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, name);
    const nlohmann::json report = compressAndVerify(input, folder, name + "-small");
    REQUIRE(report["region_classes"] == 1);
    REQUIRE(openEdges(worldMesh(scene)) == 0);
    CHECK(openEdges(worldMesh(readScene(folder / (name + "-small.glb")))) == 0);
}

}  // namespace

TEST_CASE("Every shared model, compressed, rebuilds its original surface", "[compress][models]") {
    TemporaryFolder folder;
    for (const std::string& model : sharedModels()) {
        INFO(model);
        // The sanitizer build (scripts/test.sh sets SYMCOMPRESS_QUICK) runs ten times slower: the models
        // above 20k triangles are left to the Release build there.
        if (std::getenv("SYMCOMPRESS_QUICK") && sceneStatistics(readScene(modelPath(model))).trianglesDrawn > 20000) continue;
        const nlohmann::json report = compressAndVerify(modelPath(model), folder, "model");
        for (const char* key : {"input_bytes", "output_bytes", "ratio", "triangles_in", "triangles_stored", "tiles", "classes",
                                "instances", "symmetric_classes", "max_deviation", "seconds", "ablation"})
            CHECK(report.contains(key));
        CHECK(report["ratio"].get<double>() > 0);
        CHECK(report["max_deviation"].get<double>() <= 1e-5);
    }
}

TEST_CASE("Baked copies are stored once and drawn by instances, mirrors included", "[compress]") {
    // 12 copies of the torus knot (2880 triangles), turned, moved, a third of them mirrored, baked into one
    // mesh. (Parts of a few hundred triangles do not pay for a node each: Draco stores the rock's 180
    // triangles in about 250 bytes, twice what a node costs.)
    const TriangleMesh rock = worldMesh(readScene(modelPath("vulkan_torusknot/torusknot.gltf")));
    Scene scene;
    scene.meshes.emplace_back();
    Primitive baked;
    std::mt19937_64 random(5);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 12; ++k) {
        Eigen::Matrix3d linear =
            samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
        if (k % 3 == 1) linear.col(0) *= -1;
        const Eigen::Vector3d shift = samples::drawnVector([&] { return normal(random); }) * 300;
        const auto offset = std::uint32_t(baked.positions.size());
        for (const auto& p : rock.positions) baked.positions.push_back((linear * p + shift).cast<float>().cast<double>());
        for (auto t : rock.triangles) {
            if (linear.determinant() < 0) std::swap(t[1], t[2]);
            baked.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        }
    }
    scene.meshes[0].primitives.push_back(baked);
    scene.nodes.emplace_back();
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "knots");

    const nlohmann::json report = compressAndVerify(input, folder, "knots-compressed");
    CHECK(report["tiles"] == 12);
    CHECK(report["classes"] == 1);
    // Each copy drawn by a node, or by a node per copy of the knot's fundamental region where the GPU-instanced
    // batches make that pay.
    CHECK(report["instances"].get<int>() % 12 == 0);
    CHECK(report["triangles_stored"] <= 2880);
    // Instancing beats Draco alone by far here (measured: 7.9 KB against 31.6 KB).
    CHECK(report["ablation"]["instancing"].get<double>() * 3 < report["ablation"]["draco_alone"].get<double>());
}

TEST_CASE(
    "Baked copies with tangents are stored once, mirrors included, and a copy of the other handedness stays apart",
    "[compress]") {
    // 7 copies of the torus knot with tangents (a field along the knot's local positions, w = 1), turned and moved,
    // two of them mirrored (tangents turned with them, their handedness kept, as a viewer draws a mirrored
    // instance), and one whose tangents have w = -1: its normal maps would shade otherwise.
    const TriangleMesh knot = worldMesh(readScene(modelPath("vulkan_torusknot/torusknot.gltf")));
    Primitive baked;
    baked.attributes = {{"TANGENT", 4, {}}};
    std::vector<double>& tangents = baked.attributes[0].values;
    std::mt19937_64 random(8);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 7; ++k) {
        Eigen::Matrix3d linear =
            samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
        if (k % 3 == 1) linear.col(0) *= -1;
        const Eigen::Vector3d shift = samples::drawnVector([&] { return normal(random); }) * 300;
        const auto offset = std::uint32_t(baked.positions.size());
        for (const auto& p : knot.positions) {
            baked.positions.push_back((linear * p + shift).cast<float>().cast<double>());
            const Eigen::Vector3d direction = (linear * (p + Eigen::Vector3d(0.1, 0.2, 0.3))).normalized();
            tangents.insert(tangents.end(), {direction.x(), direction.y(), direction.z(), k == 6 ? -1.0 : 1.0});
            baked.texcoords.push_back(Eigen::Vector2d(p.x(), p.y()) * 0.1);
        }
        for (auto t : knot.triangles) {
            if (linear.determinant() < 0) std::swap(t[1], t[2]);
            baked.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        }
    }
    // Read by a normal map (tangents nothing reads are dropped); its image bytes are carried, not decoded.
    baked.material = 0;
    Scene scene = sceneOfOneMesh("knots", baked);
    scene.textures = {pngSignatureTexture()};
    scene.materials.emplace_back().normalTexture.texture = 0;
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "knots");

    const nlohmann::json report = compressAndVerify(input, folder, "knots-compressed");
    CHECK(report["tiles"] == 7);
    CHECK(report["classes"] == 1);
    CHECK(report["attribute_mismatches"] == 1);
    CHECK(report["triangles_stored"] <= 2 * 2880);
    CHECK(report["ablation"]["instancing"].get<double>() * 2 < report["ablation"]["draco_alone"].get<double>());
    // Rebuilt, every vertex has the tangent of the input's vertex at its place, within the quantization.
    const TriangleMesh rebuiltMesh = worldMesh(readScene(folder / "knots-compressed-flat.glb"));
    const Scene rebuilt = expandInstances(readScene(folder / "knots-compressed.glb"));
    std::vector<Eigen::Vector3d> both = baked.positions;
    std::vector<Eigen::Vector4d> tangentOf;
    for (std::size_t v = 0; v < baked.positions.size(); ++v)
        tangentOf.push_back(Eigen::Map<const Eigen::Vector4d>(baked.attributes[0].vertex(v)));
    for (const Mesh& mesh : rebuilt.meshes)
        for (const Primitive& p : mesh.primitives) {
            REQUIRE(attributeSignature(p) == "TANGENT:4;");
            REQUIRE(p.texcoords.size() == p.positions.size());
            both.insert(both.end(), p.positions.begin(), p.positions.end());
            for (std::size_t v = 0; v < p.positions.size(); ++v)
                tangentOf.push_back(Eigen::Map<const Eigen::Vector4d>(p.attributes[0].vertex(v)));
        }
    REQUIRE(both.size() > baked.positions.size());
    double shortestEdge = std::numeric_limits<double>::infinity();
    for (const Triangle& t : knot.triangles)
        for (int i = 0; i < 3; ++i)
            shortestEdge = std::min(shortestEdge, (knot.positions[t[i]] - knot.positions[t[(i + 1) % 3]]).norm());
    const std::vector<std::uint32_t> place = weldPositions(both, 0.3 * shortestEdge);
    std::multimap<std::uint32_t, Eigen::Vector4d> inputAt;
    for (std::size_t v = 0; v < baked.positions.size(); ++v) inputAt.emplace(place[v], tangentOf[v]);
    std::size_t matched = 0;
    for (std::size_t v = baked.positions.size(); v < both.size(); ++v) {
        const auto [first, last] = inputAt.equal_range(place[v]);
        matched += std::any_of(first, last, [&](const std::pair<const std::uint32_t, Eigen::Vector4d>& entry) {
            const Eigen::Vector4d& expected = entry.second;
            return expected.w() == tangentOf[v].w() && expected.head(3).dot(tangentOf[v].head(3)) > 0.999;
        });
    }
    CHECK(matched == both.size() - baked.positions.size());
    CHECK(rebuiltMesh.triangles.size() == baked.triangles.size());
}

TEST_CASE("A part baked in several materials is stored once: a mesh per material names the same Draco geometry",
          "[compress]") {
    // 6 copies of the torus knot, turned and moved, each in a material of its own: 0-2 of a colour alone (their
    // texture coordinates, read by nothing, are dropped), 3-5 textured; copy 5's texture coordinates differ, so
    // that it must stay apart.
    const Scene knotScene = readScene(modelPath("vulkan_torusknot/torusknot.gltf"));
    const TriangleMesh knot = worldMesh(knotScene);
    Scene scene;
    scene.textures = {pngSignatureTexture()};
    std::mt19937_64 random(12);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 6; ++k) {
        Material& material = scene.materials.emplace_back();
        material.baseColorFactor = Eigen::Vector4d(0.1 * k + 0.2, 0.5, 0.3, 1);
        if (k >= 3) material.baseColorTexture.texture = 0;
        const Eigen::Matrix3d linear =
            samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
        const Eigen::Vector3d shift = samples::drawnVector([&] { return normal(random); }) * 300;
        Primitive copy;
        copy.material = k;
        for (const auto& p : knot.positions) {
            copy.positions.push_back((linear * p + shift).cast<float>().cast<double>());
            copy.texcoords.push_back(Eigen::Vector2d(p.x(), p.y()) * (k == 5 ? 0.2 : 0.1));
        }
        copy.triangles = knot.triangles;
        Mesh& mesh = scene.meshes.emplace_back();
        mesh.primitives.push_back(std::move(copy));
        Node& node = scene.nodes.emplace_back();
        node.mesh = k;
        scene.roots.push_back(k);
    }
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "knots");

    const nlohmann::json report = compressAndVerify(input, folder, "knots-compressed");
    CHECK(report["classes"] == 6);
    CHECK(report["material_variants"] == 4);
    CHECK(report["attribute_mismatches"] == 1);
    CHECK(report["triangles_stored"] == 2 * knot.triangles.size());
    // (Draco alone draws the three untextured copies as one primitive by their base colour, and the textured ones,
    // each quantized in a box 300 times a knot's: 23328 bytes, 35344 apart.)
    CHECK(report["ablation"]["instancing"].get<double>() * 1.25 < report["ablation"]["draco_alone"].get<double>());
    // Two Draco geometries (the knot, and copy 5 apart), named by primitives of all 6 materials.
    const nlohmann::json json = glbJson(folder / "knots-compressed.glb");
    std::set<int> views, materials;
    for (const auto& mesh : json["meshes"])
        for (const auto& primitive : mesh["primitives"]) {
            views.insert(primitive["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<int>());
            materials.insert(primitive["material"].get<int>());
        }
    CHECK(views.size() == 2);
    CHECK(materials == std::set<int>{0, 1, 2, 3, 4, 5});
    // Rebuilt, each material draws one knot, the textured ones with their texture coordinates.
    const Scene rebuilt = expandInstances(readScene(folder / "knots-compressed.glb"));
    std::map<int, std::size_t> trianglesOf;
    for (const Mesh& mesh : rebuilt.meshes)
        for (const Primitive& p : mesh.primitives) {
            trianglesOf[p.material] += p.triangles.size();
            if (p.material >= 3) CHECK(p.texcoords.size() == p.positions.size());
        }
    for (int k = 0; k < 6; ++k) CHECK(trianglesOf[k] == knot.triangles.size());

    // X3D: one geometry node, USEd by a Shape in each other material.
    const nlohmann::json x3d = compressAndVerify(input, folder, "knots-x3d", {}, ".x3d");
    CHECK(x3d["material_variants"] == 4);
    CHECK(x3d["ablation"]["instancing"].get<double>() * 2 < x3d["ablation"]["draco_alone"].get<double>());
    const std::string text = readTextFile(folder / "knots-x3d.x3d");
    std::size_t uses = 0;
    for (std::size_t at = text.find("Set USE='"); at != std::string::npos; at = text.find("Set USE='", at + 1)) ++uses;
    CHECK(uses == 4);
}

TEST_CASE("Copies each alone in a material are shared: storing them as they are would open a primitive for each",
          "[compress]") {
    TemporaryFolder folder;
    // The unlit test: one mesh in an orange and in a blue material, nothing else in either. (By default the two
    // materials, which differ only in base colour, are drawn as one primitive: smaller still, below.)
    const auto unlit = modelPath("pbr/unlit/UnlitTest.gltf");
    CompressOptions unjoined;
    unjoined.optimize.joinByBaseColor = false;
    const nlohmann::json report = compressAndVerify(unlit, folder, "unlit", unjoined);
    CHECK(report["instances"] == 2);
    CHECK(report["material_variants"] == 1);
    CHECK(report["ablation"]["final"].get<double>() < report["ablation"]["draco_alone"].get<double>());
    const nlohmann::json json = glbJson(folder / "unlit.glb");
    // The instance nodes keep the input's names, and its translations (+-1.2, 0, 0) print as they were, not with the
    // rounding of the centroids they came from (1.9e-18) in float32's digits.
    std::set<std::string> names;
    for (const auto& node : json["nodes"]) {
        if (node.contains("name")) names.insert(node["name"].get<std::string>());
        CHECK(node["translation"].dump() == (node["name"] == "Orange Object" ? "[-1.2,0,0]" : "[1.2,0,0]"));
    }
    CHECK(names == std::set<std::string>{"Orange Object", "Blue Object"});
    const nlohmann::json joined = compressAndVerify(unlit, folder, "unlit-joined");
    CHECK(joined["optimizations"]["joined_primitives"] == 1);
    CHECK(joined["output_bytes"].get<double>() < report["output_bytes"].get<double>());

    // Three materials, each drawing a large part and a small one, both the same in every material. The large parts
    // are shared; the small ones, judged beside them, would join primitives written anyway, but once the large
    // parts are shared nothing else is stored in those materials: a second look shares them too.
    std::mt19937_64 random(5);
    const TriangleMesh large =
        samples::transformed(samples::unevenEllipsoid(48, 3), Eigen::Matrix3d::Identity() * 4, {0, 0, 0});
    const TriangleMesh small = samples::randomConvexPart(random);
    samples::OneMeshBuilder three("large and small parts in three materials");
    for (int k = 0; k < 3; ++k) {
        const int material = three.addMaterial("m" + std::to_string(k), Eigen::Vector4d(0.2 * k + 0.1, 0.5, 0.3, 1));
        three.add(material,
                  samples::transformed(large, samples::randomRotation(random), Eigen::Vector3d(10.0 * k, 0, 0)));
        three.add(material,
                  samples::transformed(small, samples::randomRotation(random), Eigen::Vector3d(10.0 * k, 8, 0)));
    }
    // (Without the join by base colour, by which the small parts stored as they are share one primitive.)
    const auto threeInput = writePlainGlb(std::move(three).build(), folder, "three");
    const nlohmann::json both = compressAndVerify(threeInput, folder, "three-out", unjoined);
    CHECK(both["classes"] == 6);
    CHECK(both["instanced_classes"] == 2);
    CHECK(both["instances"] == 6);
    CHECK(both["not_worth_instancing"] == 0);
    CHECK(compressAndVerify(threeInput, folder, "three-joined")["output_bytes"] <= both["output_bytes"]);

    // Must not act: two copies of the small part in a material whose large part is stored as it is.
    samples::OneMeshBuilder one("small parts beside a large one");
    const int material = one.addMaterial("m", Eigen::Vector4d(0.5, 0.5, 0.3, 1));
    one.add(material, large);
    for (int k = 0; k < 2; ++k)
        one.add(material,
                samples::transformed(small, samples::randomRotation(random), Eigen::Vector3d(10.0 * k, 8, 0)));
    const nlohmann::json apart =
        compressAndVerify(writePlainGlb(std::move(one).build(), folder, "one"), folder, "one-out");
    CHECK(apart["instances"] == 0);
    CHECK(apart["not_worth_instancing"] == 2);
}

TEST_CASE("Parts in materials that differ only in base colour are drawn as one primitive, each vertex given its colour",
          "[compress][join]") {
    TemporaryFolder folder;
    // Four parts of different shapes (nothing to share) in four materials: three differ only in their base colour
    // (one dark, where COLOR_0's default 8 bits would lighten it by several steps of sRGB output), the fourth in
    // its roughness too.
    const Eigen::Vector4d colours[] = {
        {0.00041231798, 6.37466e-05, 3.74733e-05, 1}, {0.8, 0.8, 0.8, 1}, {0.1, 0.6, 0.2, 1}, {0.3, 0.2, 0.9, 1}};
    samples::OneMeshBuilder builder("parts in four colours");
    for (int k = 0; k < 4; ++k) {
        const int material = builder.addMaterial("m" + std::to_string(k), colours[k]);
        builder.add(material, samples::transformed(samples::unevenEllipsoid(24 + 4 * k, std::uint64_t(k + 1)),
                                                   Eigen::Matrix3d::Identity(), Eigen::Vector3d(10.0 * k, 0, 0)));
    }
    Scene scene = std::move(builder).build();
    scene.materials[3].roughnessFactor = 0.3;
    const auto input = writePlainGlb(scene, folder, "colours");

    const nlohmann::json report = compressAndVerify(input, folder, "joined");
    CHECK(report["optimizations"]["primitives_joined_by_base_color"] == 3);
    CHECK(report["optimizations"]["joined_primitives"] == 1);
    // The three materials' names are lost, with a warning.
    CHECK(std::any_of(report["warnings"].begin(), report["warnings"].end(), [](const nlohmann::json& warning) {
        return warning.get<std::string>().rfind("3 material names (e.g. 'm0') not kept", 0) == 0;
    }));
    const Scene joined = readGltf(folder / "joined.glb");
    REQUIRE(joined.materials.size() == 2);
    std::size_t coloured = 0;
    for (const Mesh& mesh : joined.meshes)
        for (const Primitive& primitive : mesh.primitives) {
            const Material& material = joined.materials[std::size_t(primitive.material)];
            if (primitive.colors.empty()) {  // the part that differs in roughness too, as it was
                CHECK(material.roughnessFactor == Approx(0.3));
                CHECK(material.baseColorFactor.isApprox(colours[3], 1e-6));
                continue;
            }
            ++coloured;
            CHECK(material.baseColorFactor == Eigen::Vector4d(1, 1, 1, 1));
            CHECK(material.roughnessFactor == Approx(0.6));
            CHECK(material.name.empty());
            // Each vertex carries its part's colour (the parts lie 10 apart along x) within a quarter of a step of
            // 8-bit sRGB output.
            for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
                const auto k = std::size_t(std::lround(primitive.positions[v].x() / 10));
                REQUIRE(k < 3);
                for (int c = 0; c < 3; ++c)
                    CHECK(std::abs(linearToSrgb(primitive.colors[v][c]) - linearToSrgb(colours[k][c])) * 255 <
                          0.25 + 1e-3);
                CHECK(primitive.colors[v][3] == Approx(1));
            }
        }
    CHECK(coloured == 1);
    if (renderAvailable()) checkRendersSame(input, folder / "joined.glb");

    // --no-color-join: four primitives, no colours, and a larger file.
    CompressOptions apart;
    apart.optimize.joinByBaseColor = false;
    const nlohmann::json kept = compressAndVerify(input, folder, "apart", apart);
    CHECK(kept["optimizations"]["primitives_joined_by_base_color"] == 0);
    const Scene four = readGltf(folder / "apart.glb");
    CHECK(four.materials.size() == 4);
    for (const Mesh& mesh : four.meshes)
        for (const Primitive& primitive : mesh.primitives) CHECK(primitive.colors.empty());
    CHECK(report["output_bytes"].get<double>() < kept["output_bytes"].get<double>());

    // X3D output holds no such join.
    const nlohmann::json x3d = compressAndVerify(input, folder, "x3d", {}, ".x3d");
    CHECK(x3d["optimizations"]["primitives_joined_by_base_color"] == 0);
}

TEST_CASE("Copies turned over face the way they do: flat cards, and a rebuild turned inside out is not verified",
          "[compress]") {
    // A flat card (a 30 x 30 grid of one-sided quads, its inner vertices moved in the plane so that only the
    // mirror in its own plane is a symmetry) is the same point set turned over: a placement that matches
    // positions only may draw a copy facing away. Every other copy is turned over.
    Primitive card;
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    const int n = 30;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const bool inner = i > 0 && i < n && j > 0 && j < n;
            card.positions.push_back({0.1 * (i + (inner ? jitter(random) : 0)), 0.05 * (j + (inner ? jitter(random) : 0)), 0});
        }
    for (std::uint32_t i = 0; i < std::uint32_t(n); ++i)
        for (std::uint32_t j = 0; j < std::uint32_t(n); ++j) {
            const std::uint32_t a = i * (n + 1) + j;
            card.triangles.push_back({a, a + n + 1, a + n + 2});
            card.triangles.push_back({a, a + n + 2, a + 1});
        }
    Primitive cards;
    for (int k = 0; k < 12; ++k) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                     (k % 2 ? Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix()
                                            : Eigen::Matrix3d::Identity());
        TriangleMesh placed = samples::transformed(TriangleMesh{card.positions, card.triangles}, turn, Eigen::Vector3d(4.0 * k, 0, 0));
        samples::appendMesh(cards, placed);
    }
    const Scene scene = sceneOfOneMesh("cards", cards);
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "cards");
    const nlohmann::json report = compressAndVerify(input, folder, "cards-small");  // verified, orientation included
    CHECK(report["instances"].get<int>() % 12 == 0);  // a node per card, or per copy of its region in each
    CHECK(report["instances"] >= 12);

    // The same rebuild against an original whose cards 1, 3, 5... are wound the other way: not verified.
    Scene insideOut = scene;
    auto& triangles = insideOut.meshes[0].primitives[0].triangles;
    for (std::size_t t = 0; t < triangles.size(); ++t)
        if ((t / card.triangles.size()) % 2) std::swap(triangles[t][1], triangles[t][2]);
    const auto wrong = writePlainGlb(insideOut, folder, "cards-inside-out");
    const CommandResult check = runCommand(kSymdecompress + " " + quoted(folder / "cards-small.glb") + " -o " +
                                           quoted(folder / "flat.glb") + " --json --verify " + quoted(wrong));
    INFO(check.output);
    CHECK(check.status == 1);
    const auto result = nlohmann::json::parse(check.output.substr(check.output.find('{')));
    CHECK(result["flipped_area"].get<double>() == Approx(0.5).margin(0.01));
    CHECK(result["verified"] == false);
}

TEST_CASE("The plans measured beside the output leave no file behind, in every output format", "[compress]") {
    // The bolts: instancing and its ablation plans are measured, each written beside the output and removed.
    const Scene scene = samples::makeBoltsScene();
    const std::vector<std::pair<std::string, std::set<std::string>>> cases = {
        {"out.glb", {"out.glb"}}, {"out.gltf", {"out.gltf", "out.bin"}},
        {"out.x3d", {"out.x3d"}}, {"out.obj", {"out.obj", "out.mtl"}},
        {"out.ply", {"out.ply"}},
    };
    for (const auto& [name, expected] : cases) {
        INFO(name);
        TemporaryFolder folder;
        compressToFile(scene, folder / name);
        std::set<std::string> left;
        for (const auto& entry : std::filesystem::directory_iterator(folder.path()))
            left.insert(entry.path().filename().string());
        CHECK(left == expected);
    }
}

TEST_CASE("A plan that takes another plan's assemblies and scene symmetry is the plan that seeks them itself",
          "[compress]") {
    // The room (scene symmetry: a mirror) and the room with a box that breaks it (repeated assemblies).
    Scene broken = samples::makeRoomScene();
    samples::appendMesh(broken.meshes[0].primitives[0], samples::boxMesh({1.3, 0.7, 0.9}, {0.2, 0.3, 0.1}));
    for (const Scene& scene : {samples::makeRoomScene(), broken}) {
        const SceneAnalysis analysis = analyzeScene(scene);
        PlanOptions options;
        CompressionPlan full;
        compressAnalyzed(scene, analysis, options, &full);
        REQUIRE(std::any_of(full.shared.begin(), full.shared.end(),
                            [](const SharedPart& part) { return part.mechanism != SharedPart::Mechanism::Class; }));
        options.regions = false;
        const CompressedScene sought = compressAnalyzed(scene, analysis, options);
        options.sharedPartsFrom = &full;
        const CompressedScene taken = compressAnalyzed(scene, analysis, options);
        TemporaryFolder folder;
        writeScene(sought.scene, folder / "sought.glb");
        writeScene(taken.scene, folder / "taken.glb");
        CHECK(readFileBytes(folder / "sought.glb") == readFileBytes(folder / "taken.glb"));
    }
}

TEST_CASE("The analysis that takes the input's geometry is the one that copies it, and leaves the kept meshes whole",
          "[compress]") {
    // The room (one mesh, one node), and four boxes: drawn by two nodes, by an animated node, with tangents under a
    // node that scales unevenly (which tiles do not carry), and by two nodes one of which scales it (the author's
    // instancing).
    Scene scene = samples::makeRoomScene();
    Primitive box;
    samples::appendMesh(box, samples::boxMesh({5, 0, 0}, {0.4, 0.5, 0.6}));
    auto addNode = [&](int mesh, const Eigen::Vector3d& at, double scale) {
        Node node;
        node.mesh = mesh;
        node.transform.topLeftCorner<3, 3>() *= scale;
        node.transform.topRightCorner<3, 1>() = at;
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
        return int(scene.nodes.size()) - 1;
    };
    for (int m = 0; m < 4; ++m) scene.meshes.push_back({"box" + std::to_string(m), {box}, "", {}});
    const int twice = int(scene.meshes.size()) - 4, animated = twice + 1, tangents = twice + 2, scaled = twice + 3;
    addNode(twice, {0, 3, 0}, 1);
    addNode(twice, {0, 6, 0}, 1);
    AnimationChannel slide;
    slide.node = addNode(animated, {0, 9, 0}, 1);
    slide.times = {0, 1};
    slide.values = {0, 9, 0, 1, 9, 0};
    scene.animations.push_back({"slide", {slide}});
    scene.meshes[std::size_t(tangents)].primitives[0].attributes.push_back(
        {"TANGENT", 4, std::vector<double>(box.positions.size() * 4, 0.5)});
    scene.nodes[std::size_t(addNode(tangents, {0, 12, 0}, 1))].transform(0, 0) = 2;
    addNode(scaled, {0, 15, 0}, 1);
    addNode(scaled, {0, 18, 0}, 0.5);
    validateScene(scene);

    const SceneAnalysis copied = analyzeScene(scene);
    Scene taken = scene;
    const SceneAnalysis analysis = analyzeSceneTakingGeometry(taken);
    REQUIRE(analysis.soup.size() == copied.soup.size());
    for (std::size_t p = 0; p < copied.soup.size(); ++p) {
        CHECK(analysis.soup[p].primitive.positions == copied.soup[p].primitive.positions);
        CHECK(analysis.soup[p].primitive.normals == copied.soup[p].primitive.normals);
        CHECK(analysis.soup[p].primitive.triangles == copied.soup[p].primitive.triangles);
        CHECK(analysis.soup[p].node == copied.soup[p].node);
    }
    CHECK(analysis.tiles.size() == copied.tiles.size());
    CHECK(analysis.digest.json() == copied.digest.json());
    CHECK(analysis.keptInstances.size() == 3);
    // The meshes only tiles draw keep their materials and nothing else; the others are as they were.
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        INFO(scene.meshes[m].name);
        const bool kept = int(m) == animated || int(m) == tangents || int(m) == scaled;
        for (std::size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
            const Primitive& before = scene.meshes[m].primitives[p];
            const Primitive& after = taken.meshes[m].primitives[p];
            CHECK(after.material == before.material);
            CHECK(after.positions.size() == (kept ? before.positions.size() : 0));
            CHECK(after.triangles.size() == (kept ? before.triangles.size() : 0));
            CHECK(after.attributes == before.attributes);
        }
    }
    // The same output, byte for byte.
    TemporaryFolder folder;
    writeScene(compressAnalyzed(scene, copied, {}).scene, folder / "copied.glb");
    writeScene(compressAnalyzed(taken, analysis, {}).scene, folder / "taken.glb");
    CHECK(readFileBytes(folder / "copied.glb") == readFileBytes(folder / "taken.glb"));
}

TEST_CASE("Tiles that recur together are stored once per group: the room's bookshelves", "[compress]") {
    // The room with a box on one table: its mirror symmetry is broken, so the scene's symmetry does not
    // apply, and the repeated assemblies do.
    Scene scene = samples::makeRoomScene();
    samples::appendMesh(scene.meshes[0].primitives[0], samples::boxMesh({1.3, 0.7, 0.9}, {0.2, 0.3, 0.1}));
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "room");
    const nlohmann::json report = compressAndVerify(input, folder, "room-compressed");
    CHECK(report["scene_group"] == "C1");
    // The 4 bookshelves of 188 boxes each pay for a mesh and 4 nodes; tables and chairs of 12-triangle
    // boxes cost less stored as they are than a node per copy.
    CHECK(report["assemblies"] == 1);
    CHECK(report["assembly_copies"] == 4);
    CHECK(report["tiles_in_assemblies"] == 4 * 188);
    CHECK(report["triangles_stored"] == report["triangles_in"].get<std::size_t>() - 3 * 188 * 12);
    CHECK(report["bytes_per_instance"].get<double>() < 100);  // a mirror, a translation and the name "room"
    CHECK(report["output_bytes"].get<double>() < 0.8 * report["ablation"]["draco_alone"].get<double>());
}

TEST_CASE("Tiles that recur together leave out the parts their class draws for less: five groups of three vases",
          "[compress]") {
    // Each group: three lathes of 96 sectors (2880 triangles, C96v) stacked, in a ring of twelve random convex
    // parts of some 28 triangles that touch them; five groups at random placements, baked into one mesh. The
    // parts cost less stored once for the five groups than apart; the vases less drawn by their class's mesh,
    // a node each, than three times in the group's mesh. Before, with the vases the group cost more as one mesh
    // than its tiles apart, and no group was stored once.
    std::mt19937_64 random(17);
    std::vector<TriangleMesh> parts;
    for (int k = 0; k < 12; ++k) parts.push_back(samples::randomConvexPart(random));
    std::vector<Eigen::Vector2d> profile;  // (radius, z): a vase of height 2 and radius up to 1
    for (int k = 0; k <= 16; ++k) {
        const double z = -1 + k / 8.0;
        profile.push_back({k == 0 || k == 16 ? 0 : 0.7 + 0.3 * std::sin(3 * z), z});
    }
    const TriangleMesh vase = samples::latheMesh(profile, 96, Eigen::Vector3d::Zero());
    samples::OneMeshBuilder builder("groups");
    const int material = builder.addMaterial("grey", {0.6, 0.6, 0.6, 1});
    for (int copy = 0; copy < 5; ++copy) {
        const Eigen::Matrix3d turn = samples::randomRotation(random);
        const Eigen::Vector3d at(12.0 * copy, 3.0 * copy, 0);
        for (double z : {-2.1, 0.0, 2.1})
            builder.add(material, samples::transformed(vase, turn, turn * Eigen::Vector3d(0, 0, z) + at));
        for (int k = 0; k < 12; ++k) {
            const double angle = k * M_PI / 6;
            builder.add(material,
                        samples::transformed(parts[k], turn,
                                             turn * Eigen::Vector3d(2 * std::cos(angle), 2 * std::sin(angle), 0) + at));
        }
    }
    TemporaryFolder folder;
    const auto input = writePlainGlb(std::move(builder).build(), folder, "groups");
    const nlohmann::json report = compressAndVerify(input, folder, "groups-compressed");
    CHECK(report["tiles"] == 5 * 15);
    CHECK(report["assemblies"] == 1);
    CHECK(report["assembly_copies"] == 5);
    CHECK(report["tiles_in_assemblies"] == 5 * 12);
    CHECK(report["instanced_classes"] == 1);  // the vases, by their class's mesh
    CHECK(report["triangles_stored"].get<std::size_t>() <= 2880 + 12 * 28 + 12 * 4);
}

TEST_CASE("A repeated assembly symmetric in itself stores one part of one copy: three rooms of mirrored quadrants",
          "[compress]") {
    // The room (C2v as a whole) baked three times at random placements: the scene has no symmetry, each room is
    // a copy of a repeated assembly, and each copy is C2v about its own centre. Before, the assembly stored a
    // whole room, three times what the room alone stores.
    const Scene room = samples::makeRoomScene();
    Scene rooms = room;
    std::mt19937_64 random(5);
    std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> placements;
    for (int copy = 0; copy < 3; ++copy)
        placements.push_back({samples::randomRotation(random), Eigen::Vector3d(20.0 * copy, 7.0 * copy, 0)});
    for (std::size_t k = 0; k < room.meshes[0].primitives.size(); ++k) {
        const Primitive& one = room.meshes[0].primitives[k];
        Primitive& all = rooms.meshes[0].primitives[k];
        all.positions.clear();
        all.triangles.clear();
        for (const auto& [turn, at] : placements)
            samples::appendMesh(all, samples::transformed(TriangleMesh{one.positions, one.triangles}, turn, at));
    }
    TemporaryFolder folder;
    const nlohmann::json alone = compressAndVerify(writePlainGlb(room, folder, "room"), folder, "room-compressed");

    const nlohmann::json report = compressAndVerify(writePlainGlb(rooms, folder, "rooms"), folder, "rooms-compressed");
    CHECK(report["scene_group"] == "C1");
    // One part of the room drawn 3 x 4 times, and the tiles on its mirror planes (the floor, two walls, what
    // stands across a plane) drawn 3 times.
    CHECK(report["assemblies"] == 2);
    CHECK(report["assembly_copies"] == 2 * 3);
    CHECK(report["tiles_in_assemblies"] == 3 * samples::kRoomTiles);
    CHECK(report["triangles_stored"].get<std::size_t>() <= alone["triangles_stored"].get<std::size_t>());
    CHECK(report["output_bytes"].get<double>() < 1.5 * alone["output_bytes"].get<double>());
}

TEST_CASE("A scene symmetric as a whole is stored as one part of it, drawn once per symmetry: room and chess board",
          "[compress]") {
    TemporaryFolder folder;
    struct Case {
        const char* name;
        Scene scene;
        const char* group;
        std::size_t tilesOnPlanes;  // tiles that the group maps onto themselves, stored apart
    };
    for (const Case& c : {Case{"room", samples::makeRoomScene(), "C2v", 5}, Case{"chess", samples::makeChessScene(), "C2", 0}}) {
        INFO(c.name);
        const auto input = writePlainGlb(c.scene, folder, c.name);
        const nlohmann::json report = compressAndVerify(input, folder, std::string(c.name) + "-compressed");
        CHECK(report["scene_group"] == c.group);
        const std::size_t order = std::string(c.group) == "C2v" ? 4 : 2;
        CHECK(report["tiles_in_scene_symmetry"] == report["tiles"].get<std::size_t>() - c.tilesOnPlanes);
        CHECK(report["instances"] == order);
        // The part holds 1/order of the tiles in symmetric orbits (the tiles are equal in size per orbit).
        CHECK(report["triangles_stored"].get<std::size_t>() < report["triangles_in"].get<std::size_t>() / order + 100);
        CHECK(report["output_bytes"].get<double>() < 0.9 * report["ablation"]["draco_alone"].get<double>());
    }
}

TEST_CASE("symcompress prints the size report, and no progress line when stderr is not a terminal", "[compress][cli]") {
    TemporaryFolder folder;
    const auto input = writePlainGlb(samples::makeLampScene(), folder, "lamp");
    const CommandResult run = runCommand(kSymcompress + " " + quoted(input) + " -o " + quoted(folder / "lamp-small.glb"));
    REQUIRE(run.status == 0);
    CHECK(run.output.find("ratio") != std::string::npos);
    CHECK(run.output.find("ablation") != std::string::npos);
    CHECK(run.output.find('\r') == std::string::npos);
    CHECK(run.output.find("symcompress: classifying") == std::string::npos);
}

TEST_CASE("A symmetric single part is stored as its fundamental region (GLB): the coffee cup", "[compress]") {
    // Its mirror halves the triangles; the cut must not leave zero-area slivers, which would push Draco
    // from edgebreaker to its sequential method (the region was once 3 times Draco alone).
    TemporaryFolder folder;
    const nlohmann::json report = compressAndVerify(modelPath("xj3d_coffee_cup/coffeeCup.x3d"), folder, "cup");
    CHECK(report["plan"] == "final");
    CHECK(report["region_classes"] == 1);
    CHECK(report["triangles_stored"] == report["triangles_in"].get<std::size_t>() / 2);
    // 0.82 at the default budget (0.75 at 14 bits: the whole cup then takes more bits than its region's grid).
    CHECK(report["output_bytes"].get<double>() < 0.85 * report["ablation"]["draco_alone"].get<double>());
}

TEST_CASE("Seams of a fundamental region stay closed after quantization: the cup turned so its mirror is oblique",
          "[compress]") {
    // In the tile's own frame, Draco's grid moves the seam vertices of the two halves apart by up to a
    // step (282 open edges); in the region's aligned frame the mirror is a coordinate plane on the grid.
    Scene cup = readScene(modelPath("xj3d_coffee_cup/coffeeCup.x3d"));
    Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
    turn.topLeftCorner<3, 3>() = Eigen::Quaterniond(0.3, -0.5, 0.7, 0.2).normalized().toRotationMatrix();
    for (int root : cup.roots) cup.nodes[root].transform = turn * cup.nodes[root].transform;
    Scene turned = sceneOfOneMesh("cup", flattenScene(cup)[0].primitive);
    turned.materials = cup.materials;
    checkRegionSeamsClosed(turned, "cup");
}

TEST_CASE("Seams of a fundamental region stay closed after quantization: a square ring, D4h, whose region is off its axis",
          "[compress]") {
    // A square ring: its region (1/16) lies between the planes y = 0 and x = y, away from the axis. On Draco's default grid (the region's box) x and y have different
    // origins, and the copies across x = y come apart by up to a step; on a power-of-two grid through the
    // centre, signed permutations (every element of D4h in its axis frame) map grid points onto grid points.
    // A torus of 4 straight sides around z, each cut into 24 steps, and 32 segments around its tube: large
    // enough (6144 triangles) for its region to pay for 16 nodes.
    TriangleMesh ring;
    const int around = 4, steps = 24, tube = 32;
    auto corner = [&](int s, int i) {
        const double a = 2 * M_PI * s / around, b = 2 * M_PI * (i + 0.5) / tube, radius = 1 + 0.37 * std::cos(b);
        return Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), 0.37 * std::sin(b));
    };
    for (int s = 0; s < around; ++s)
        for (int k = 0; k < steps; ++k)
            for (int i = 0; i < tube; ++i)
                ring.positions.push_back(corner(s, i) + (corner(s + 1, i) - corner(s, i)) * double(k) / steps);
    const int columns = around * steps;
    auto at = [&](int c, int i) { return std::uint32_t((c % columns) * tube + i % tube); };
    for (int c = 0; c < columns; ++c)
        for (int i = 0; i < tube; ++i) {
            ring.triangles.push_back({at(c, i), at(c + 1, i), at(c + 1, i + 1)});
            ring.triangles.push_back({at(c, i), at(c + 1, i + 1), at(c, i + 1)});
        }
    // Turned and moved, so that nothing is on the coordinate planes by accident.
    const Eigen::Matrix3d turn = Eigen::Quaterniond(0.8, 0.1, -0.4, 0.3).normalized().toRotationMatrix();
    ring = samples::transformed(ring, turn, Eigen::Vector3d(3.1, -0.7, 2.3));
    Primitive part;
    part.positions = ring.positions;
    part.triangles = ring.triangles;
    const Scene scene = sceneOfOneMesh("ring", part);
    checkRegionSeamsClosed(scene, "ring");
}

TEST_CASE("Every sample, compressed to GLB and X3D, rebuilds its original surface, the bolts using both mechanisms",
          "[compress]") {
    TemporaryFolder folder;
    const std::vector<std::pair<const char*, Scene>> scenes{
        {"bolts", samples::makeBoltsScene()},         {"three_spheres", samples::makeThreeSpheresScene()},
        {"lamp", samples::makeLampScene()},           {"pliers", samples::makePliersScene()},
        {"chess", samples::makeChessScene()},         {"icosahedral", samples::makeIcosahedralScene()},
        {"room", samples::makeRoomScene()}};
    for (const auto& [name, scene] : scenes) {
        INFO(name);
        const auto input = writePlainGlb(scene, folder, name);
        compressAndVerify(input, folder, std::string(name) + "-small");
        const nlohmann::json r = compressAndVerify(input, folder, std::string(name) + "-small", {}, ".x3d");
        if (std::string(name) == "bolts") {
            // As X3D text a bolt's region copies pay: every one of the 12 placements times the elements of a
            // subgroup of C6 (its mirrors hold only within the tolerance) that keeps the triangles whole.
            CHECK(r["region_classes"] == 1);
            const int instances = r["instances"];
            CHECK(instances % 12 == 0);
            CHECK(instances > 12);
            CHECK(instances <= 72);
        }
    }
}

TEST_CASE("An image that several materials use is embedded once: the Chevy Tahoe's 8 ImageTextures", "[compress]") {
    // Its X3D names one 76 KB JPEG from 7 ImageTextures; embedded 7 times the GLB was 622 KB.
    TemporaryFolder folder;
    const nlohmann::json report = compressAndVerify(modelPath("savage_chevy_tahoe/ChevyTahoe.x3d"), folder, "chevy");
    CHECK(readScene(folder / "chevy.glb").textures.size() == 2);
    CHECK(report["output_bytes"].get<double>() < 200000);
}

TEST_CASE("The input's own shared meshes stay shared: the subpass scene", "[compress]") {
    // 6 of its 12 meshes are drawn by 64 nodes, many scaled non-uniformly (not congruent): flattened and
    // tiled they cost 152 KB, kept as the author shared them about 60 KB. Its 4168 drawn triangles with two
    // corners at one point draw nothing but are counted by viewers: they stay, at one point (kept as they are,
    // a sequential Draco primitive, they cost 36.8 KB in all against 25.2 KB).
    TemporaryFolder folder;
    const nlohmann::json report =
        compressAndVerify(modelPath("vulkan_subpass_scene/subpass_scene_opaque.gltf"), folder, "subpass");
    CHECK(report["input_instances_kept"].get<int>() >= 50);
    CHECK(report["output_bytes"].get<double>() < 30000);
    CHECK(readScene(folder / "subpass.glb").meshes.size() >= 6);
    const TriangleMesh drawn = worldMesh(readScene(folder / "subpass.glb"));
    CHECK(drawn.triangles.size() == 23388);
    CHECK(std::count_if(drawn.triangles.begin(), drawn.triangles.end(), [&](const Triangle& t) {
              return (drawn.positions[t[1]] - drawn.positions[t[0]])
                         .cross(drawn.positions[t[2]] - drawn.positions[t[0]])
                         .norm() == 0;
          }) == 4168);
}

TEST_CASE("A triangle strip keeps its joints of zero area, as viewers draw and count them, in GLB and X3D",
          "[compress]") {
    // Three quads in one strip, the last two joined by a repeated index: 8 triangles, 4 of them of zero area at the
    // joint (three.js turns a strip into n - 2 triangles and counts them all).
    TemporaryFolder folder;
    writeTextFile(folder / "strip.gltf", R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":5}]}],
        "buffers":[{"byteLength":116,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAAAAAAAAAAACAPwAAgD8AAAAAAAAAQAAAAAAAAAAAAAAAQAAAgD8AAAAAAABAQAAAAAAAAAAAAABAQAAAgD8AAAAAAAABAAIAAwADAAQABAAFAAYABwA="}],
        "bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":20}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[3,1,0]},
                     {"bufferView":1,"componentType":5123,"count":10,"type":"SCALAR"}]})");
    auto zeroArea = [](const TriangleMesh& mesh) {
        return std::count_if(mesh.triangles.begin(), mesh.triangles.end(), [&](const Triangle& t) {
            const auto& p = mesh.positions;
            return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm() == 0;
        });
    };
    const TriangleMesh input = worldMesh(readScene(folder / "strip.gltf"));
    CHECK(input.triangles.size() == 8);
    CHECK(zeroArea(input) == 4);
    for (const char* extension : {".glb", ".x3d"}) {
        INFO(extension);
        compressAndVerify(folder / "strip.gltf", folder, "small", {}, extension);
        const TriangleMesh drawn = worldMesh(readScene(folder / (std::string("small") + extension)));
        CHECK(drawn.triangles.size() == 8);
        CHECK(zeroArea(drawn) == 4);
    }
}

TEST_CASE("Tiles stored as they are keep their attributes, whatever the other tiles of their material carry",
          "[compress]") {
    // Two different parts of one material, one with normals and one without: merged into one primitive the
    // normals would have to go (a glTF primitive has them for every vertex or for none). The small part without
    // (flat) joins the other with its faces' normals, shaded as before.
    Primitive withNormals, without;
    for (Primitive* part : {&withNormals, &without}) {
        part->material = 0;
        const double size = part == &without ? 2.0 : 1.0;
        part->positions = {{0, 0, 0}, {size, 0, 0}, {0, size, 0}, {0, 0, size}};
        part->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        for (auto& p : part->positions) p += Eigen::Vector3d(size * 5, 0, 0);
    }
    withNormals.normals.assign(4, Eigen::Vector3d::UnitZ());
    Scene scene = sceneOfOneMesh("parts", withNormals);
    scene.meshes[0].primitives.push_back(without);
    scene.materials.emplace_back();
    const CompressedScene compressed = compressInMemory(scene);
    std::size_t trianglesWithNormals = 0, flatShaded = 0;
    for (const Mesh& mesh : compressed.scene.meshes)
        for (const Primitive& p : mesh.primitives) {
            trianglesWithNormals += p.normals.empty() ? 0 : p.triangles.size();
            for (const Triangle& t : p.triangles) {
                if (p.normals.empty()) continue;
                const Eigen::Vector3d face =
                    (p.positions[t[1]] - p.positions[t[0]]).cross(p.positions[t[2]] - p.positions[t[0]]).normalized();
                flatShaded +=
                    std::all_of(t.begin(), t.end(), [&](std::uint32_t v) { return p.normals[v].dot(face) > 0.9999; });
            }
        }
    CHECK(trianglesWithNormals == 8);
    CHECK(flatShaded == 4);  // the other part's normals (all +z) are no face's
}

TEST_CASE("Compressing to .gltf leaves the .gltf and its .bin, and nothing of the ablation's trial files", "[compress][cli]") {
    TemporaryFolder folder;
    const auto input = writePlainGlb(samples::makeBoltsScene(), folder, "bolts");
    REQUIRE(runCommand(kSymcompress + " -q " + quoted(input) + " -o " + quoted(folder / "small.gltf")).status == 0);
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder.path())) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    CHECK(names == std::vector<std::string>{"bolts.glb", "small.bin", "small.gltf"});
}

TEST_CASE("Where nothing pays, the output is the Draco-alone file: the spider", "[compress]") {
    // Its repeated legs are under 100 triangles: nodes cost more than Draco's bytes for them.
    TemporaryFolder folder;
    const nlohmann::json report = compressAndVerify(modelPath("assimp_spider/spider.obj"), folder, "spider");
    CHECK(report["output_bytes"].get<double>() <= report["ablation"]["draco_alone"].get<double>());
    CHECK(report["output_bytes"] == report["ablation"]["final"]);
}

TEST_CASE("Tiles stored as they are keep the frame of a node that turns them off the axes, not one that keeps them",
          "[compress]") {
    // The three spheres' rings each share a coordinate in their mesh's frame and none once turned off the axes:
    // Draco codes them smaller in the frame (the file 1912 -> 1752 bytes). A quarter turn keeps the axes: the
    // world's frame is as good, and no node is spent. Stored as they are (by default the spheres, alone in their
    // material, are one mesh drawn three times).
    TemporaryFolder folder;
    CompressOptions asTheyAre;
    asTheyAre.instancing = false;
    const nlohmann::json upright = compressAndVerify(writePlainGlb(samples::makeThreeSpheresScene(), folder, "upright"),
                                                     folder, "upright-small", asTheyAre);
    CHECK(upright["node_frames"] == 0);
    const Eigen::Matrix3d oblique = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::Matrix3d quarter = Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (const auto& [name, turn, framed] :
         {std::tuple{"oblique", oblique, true}, std::tuple{"quarter", quarter, false}}) {
        Scene scene = samples::makeThreeSpheresScene();
        REQUIRE(scene.nodes.size() == 1);
        scene.nodes[0].transform.topLeftCorner<3, 3>() = turn;
        const nlohmann::json report =
            compressAndVerify(writePlainGlb(scene, folder, name), folder, std::string(name) + "-small", asTheyAre);
        CHECK(report["node_frames"] == (framed ? 1 : 0));
        CHECK(report["tiles_in_node_frames"] == (framed ? 3 : 0));
        const Scene out = readScene(folder / (std::string(name) + "-small.glb"));
        const auto drawing =
            std::find_if(out.nodes.begin(), out.nodes.end(), [](const Node& n) { return n.mesh >= 0; });
        REQUIRE(drawing != out.nodes.end());
        if (framed) {
            // The node's name and placement, and Draco's bytes of the upright scene's but for the node's.
            CHECK(drawing->name == "three-spheres");
            CHECK((drawing->transform.topLeftCorner<3, 3>() - oblique).norm() < 1e-6);
            CHECK(report["output_bytes"].get<double>() < upright["output_bytes"].get<double>() + 150);
        } else {
            CHECK(drawing->transform.isIdentity());
        }
    }
    // At glTF-Transform's deviation on the oblique spheres (which it stores in the node's frame at 14 bits), the
    // frame takes the bits the world's does: the close-up bound is the world box's, not the turned one's, whose
    // diagonal is 4% shorter and asked for a bit more (1920 bytes in world space, 1760 in the frame). The upright
    // scene's spheres take a coarser grid of their bits (coarserPositionGrid) that the turned ones' bound leaves no
    // room for: 22 bytes more than the node's.
    Scene scene = samples::makeThreeSpheresScene();
    scene.nodes[0].transform.topLeftCorner<3, 3>() = oblique;
    CompressOptions atPeer = asTheyAre;
    atPeer.maxError = 3.1825e-5;
    const nlohmann::json report = compressAndVerify(writePlainGlb(scene, folder, "peer"), folder, "peer-small", atPeer);
    CHECK(report["node_frames"] == 1);
    CHECK(report["output_bytes"].get<double>() < upright["output_bytes"].get<double>() + 200);
}

TEST_CASE("Tiles of several nodes under one turned root share one mesh in that turn's frame", "[compress]") {
    // The three spheres and the lamp (its base stored as it is) as two nodes under a root turned by 0.7 rad:
    // one mesh in the root's frame, drawn by a node with the turn alone (their names merged away, as in world
    // space), not a mesh and a node for each.
    Scene scene = samples::makeThreeSpheresScene();
    const Scene lamp = samples::makeLampScene();
    const int firstMaterial = int(scene.materials.size());
    scene.materials.insert(scene.materials.end(), lamp.materials.begin(), lamp.materials.end());
    Mesh lampMesh = lamp.meshes.at(0);
    for (Primitive& primitive : lampMesh.primitives)
        if (primitive.material >= 0) primitive.material += firstMaterial;
    scene.meshes.push_back(lampMesh);
    Node lampNode;
    lampNode.name = "lamp";
    lampNode.mesh = int(scene.meshes.size()) - 1;
    lampNode.transform.topRightCorner<3, 1>() = Eigen::Vector3d(10, 0, 0);
    scene.nodes.push_back(lampNode);
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    Node root;
    root.transform.topLeftCorner<3, 3>() = turn;
    root.children = {0, 1};
    scene.roots = {int(scene.nodes.size())};
    scene.nodes.push_back(root);
    TemporaryFolder folder;
    // Without the join by base colour, which draws the spheres' three materials as one primitive in world space,
    // smaller there than apart in the turn's frame.
    CompressOptions options;
    options.optimize.joinByBaseColor = false;
    const nlohmann::json report = compressAndVerify(writePlainGlb(scene, folder, "two"), folder, "two-small", options);
    REQUIRE(report["node_frames"].get<int>() >= 1);
    const Scene out = readScene(folder / "two-small.glb");
    CHECK(std::any_of(out.nodes.begin(), out.nodes.end(), [&](const Node& node) {
        return node.mesh >= 0 && node.name.empty() && (node.transform.topLeftCorner<3, 3>() - turn).norm() < 1e-6;
    }));
}

TEST_CASE(
    "Shared meshes are written in the frame their tiles' nodes share where it turns them off the axes: the chess "
    "board turned",
    "[compress]") {
    // Its squares, pawns and rooks are drawn from shared meshes; under a root turned by 0.7 rad they were stored
    // in world orientation (4380 bytes against 4040 upright). In the frame the turned root gives them all, with
    // each instance node turned back, they take what they take upright.
    TemporaryFolder folder;
    const nlohmann::json upright =
        compressAndVerify(writePlainGlb(samples::makeChessScene(), folder, "upright"), folder, "upright-small");
    CHECK(upright["node_frames"] == 0);
    Scene scene = samples::makeChessScene();
    Node root;
    root.transform.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    root.children = scene.roots;
    scene.roots = {int(scene.nodes.size())};
    scene.nodes.push_back(root);
    const nlohmann::json turned = compressAndVerify(writePlainGlb(scene, folder, "turned"), folder, "turned-small");
    CHECK(turned["node_frames"].get<int>() >= 1);
    // (Its nodes' turned rotations, translations and the digest's bounds print in more digits: 128 bytes of 2892.)
    CHECK(turned["output_bytes"].get<double>() < upright["output_bytes"].get<double>() + 200);
}

TEST_CASE("A scene far from the origin is stored about its centre, its node's translation to the budget, verified",
          "[compress]") {
    // 10 km out, float32's spacing is a millimetre, 1e-4 of the lamp's size: merged in world space and with
    // its node's translation printed as float32, it missed its budget (NOT VERIFIED, 6.5e-5 of the diagonal).
    TemporaryFolder folder;
    for (const auto& [name, scene] :
         {std::pair{"lamp", samples::makeLampScene()}, std::pair{"spheres", samples::makeThreeSpheresScene()}}) {
        Scene far = scene;
        REQUIRE(far.nodes.size() == 1);
        far.nodes[0].transform.topRightCorner<3, 1>() = Eigen::Vector3d(1e4, -2e3, 5e3);
        const std::string small = std::string(name) + "-far-small";
        compressAndVerify(writePlainGlb(far, folder, std::string(name) + "-far"), folder, small);
        for (const Mesh& mesh : readScene(folder / (small + ".glb")).meshes)
            for (const Primitive& primitive : mesh.primitives)
                for (const Eigen::Vector3d& p : primitive.positions) CHECK(p.norm() < 10);
    }
}

TEST_CASE("A mesh with tangents drawn once under a scale alike on every axis is merged as a rigid one is: the lantern",
          "[compress]") {
    // Its parts carry tangents, which the tiles do not: each is kept, and merged in world space where one node
    // draws it. Under a root scaling the lantern by 1000 they were kept apart instead, each with its node
    // (31472 bytes against 27052): a uniform scale turns tangents as the normal matrix does.
    TemporaryFolder folder;
    const auto input = modelPath("khronos_lantern/Lantern.gltf");
    const nlohmann::json own = compressAndVerify(input, folder, "own");
    Scene scaled = readScene(input);
    Node root;
    root.transform.topLeftCorner<3, 3>() *= 1000;
    root.children = scaled.roots;
    scaled.roots = {int(scaled.nodes.size())};
    scaled.nodes.push_back(root);
    const nlohmann::json big = compressAndVerify(writePlainGlb(scaled, folder, "big"), folder, "big-small");
    CHECK(big["output_bytes"].get<double>() < 1.02 * own["output_bytes"].get<double>());
}

TEST_CASE("symcompress refuses to overwrite its input and reports bad input with status 2", "[compress][cli]") {
    TemporaryFolder folder;
    const auto copy = folder / "rock.gltf";
    std::filesystem::copy_file(modelPath("vulkan_rock/rock.gltf"), copy);
    CHECK(runCommand(kSymcompress + " " + quoted(copy) + " -o " + quoted(copy)).status != 0);
    CHECK(runCommand(kSymcompress + " " + quoted(folder / "missing.glb") + " -o " + quoted(folder / "out.glb")).status == 2);
    CHECK_FALSE(std::filesystem::exists(folder / "out.glb"));
    // symdecompress: a file that is not what its original says is not verified (exit status 1).
    const auto output = folder / "rock.glb";
    REQUIRE(runCommand(kSymcompress + " -q " + quoted(copy) + " -o " + quoted(output)).status == 0);
    const CommandResult wrong = runCommand(kSymdecompress + " " + quoted(output) + " -o " + quoted(folder / "flat.glb") +
                                           " --verify " + quoted(modelPath("vulkan_torusknot/torusknot.gltf")));
    CHECK(wrong.status == 1);
}

TEST_CASE("Texture coordinates no texture reads are dropped by default, and said so: the torus knot", "[compress]") {
    // Its material has no texture. Without texture coordinates it is symmetric in all it stores (C3).
    TemporaryFolder folder;
    const auto input = modelPath("vulkan_torusknot/torusknot.gltf");
    CompressOptions keepAttributes;
    keepAttributes.optimize.pruneAttributes = false;
    const nlohmann::json kept = compressAndVerify(input, folder, "kept", keepAttributes);
    CHECK(kept["region_classes"] == 0);
    CHECK(kept["optimizations"]["unread_attributes_dropped"] == 0);
    CHECK_FALSE(readScene(folder / "kept.glb").meshes.at(0).primitives.at(0).texcoords.empty());
    const nlohmann::json dropped = compressAndVerify(input, folder, "dropped");
    CHECK(dropped["optimizations"]["unread_attributes_dropped"] == 1);
    for (const Mesh& mesh : readScene(folder / "dropped.glb").meshes)
        for (const Primitive& primitive : mesh.primitives) CHECK(primitive.texcoords.empty());
    CHECK(dropped["region_classes"] == 1);
    CHECK(dropped["output_bytes"].get<double>() < 0.6 * kept["output_bytes"].get<double>());
}

TEST_CASE("A subgroup's region is stored where a node per element of the whole group costs more", "[compress]") {
    // One closed surface of revolution, 48 sectors (C48v, 96 elements), drawn once: 96 nodes cost more
    // than the part, a region of a subgroup does not. C48v's mirrors through the sectors' middles halve
    // quads split along a diagonal: the region keeps whole triangles, of the rotations or of a few mirror
    // planes through the meridians. The copies meet vertex for vertex; quantization moves a seam's two
    // sides apart by less than the budget where the rotations are not signed permutations.
    std::vector<Eigen::Vector2d> profile;
    for (int k = 0; k <= 24; ++k) {
        const double angle = 3.14159265358979323846 * k / 24;
        profile.push_back({std::sin(angle) * (1 + 0.2 * std::cos(3 * angle)), -std::cos(angle)});
    }
    Primitive part;
    samples::appendMesh(part, samples::latheMesh(profile, 48, Eigen::Vector3d::Zero()));
    const Scene scene = samples::singleMeshScene("vase", part, {0.5, 0.5, 0.9, 1});
    TemporaryFolder folder;
    const nlohmann::json report = compressAndVerify(writePlainGlb(scene, folder, "vase"), folder, "vase-small");
    CHECK(report["symmetric_classes"] == 1);
    CHECK(report["region_classes"] == 1);
    const int copies = report["instances"];
    CHECK(copies > 1);
    CHECK(copies < 96);
    CHECK(96 % copies == 0);
    CHECK(report["output_bytes"].get<double>() < report["ablation"]["instancing"].get<double>());
    CHECK(sceneStatistics(readScene(folder / "vase-small.glb")).trianglesDrawn == report["triangles_in"]);
    CHECK(openEdges(worldMesh(readScene(folder / "vase-small.glb")), 1e-4) == 0);  // twice the budget
}

TEST_CASE("Animated nodes are kept as they are with their animations: the milk truck's turning wheels", "[compress]") {
    TemporaryFolder folder;
    const auto input = modelPath("cesium_milk_truck/CesiumMilkTruck.gltf");
    const nlohmann::json report = compressAndVerify(input, folder, "truck");
    CHECK(report["animated_nodes_kept"] == 2);
    CHECK(report["warnings"].dump().find("animation") == std::string::npos);
    const Scene original = readScene(input), compressed = readScene(folder / "truck.glb");
    REQUIRE(compressed.animations.size() == 1);
    REQUIRE(compressed.animations[0].channels.size() == 2);
    const std::vector<Eigen::Matrix4d> before = worldTransforms(original), after = worldTransforms(compressed);
    for (std::size_t c = 0; c < 2; ++c) {
        const AnimationChannel &from = original.animations[0].channels[c], &to = compressed.animations[0].channels[c];
        // The channel drives a node drawing the same wheel, placed where it was, keyed over the same time: the
        // wheels turn steadily, so that three keys of the 31 give the rest back (dropRedundantKeys).
        REQUIRE(compressed.nodes[std::size_t(to.node)].mesh >= 0);
        CHECK(compressed.meshes[std::size_t(compressed.nodes[std::size_t(to.node)].mesh)].primitives.size() ==
              original.meshes[std::size_t(original.nodes[std::size_t(from.node)].mesh)].primitives.size());
        CHECK((after[std::size_t(to.node)] - before[std::size_t(from.node)]).cwiseAbs().maxCoeff() < 1e-6);
        CHECK(to.path == from.path);
        CHECK(to.times == std::vector<double>{0, 0.625, 1.25});
    }
    CHECK(report["optimizations"]["animation_keys_dropped"] == 2 * (31 - 3));
    // Their keys dropped and rotations rounded within the animation keys' share of the budget: the original scene
    // drawn with the file's keys moves no vertex farther from where the original's put it, at any key of the original.
    Animation rounded = original.animations[0];
    for (std::size_t c = 0; c < 2; ++c) {
        rounded.channels[c].times = compressed.animations[0].channels[c].times;
        rounded.channels[c].values = compressed.animations[0].channels[c].values;
    }
    const double allowed =
        report["animation_key_share"].get<double>() * digestOf(worldMesh(original), 0).bounds.diagonal().norm();
    double farthest = 0;
    for (double time : keyTimes(original.animations[0])) {
        const TriangleMesh moved = posedMesh(original, rounded, time),
                           reference = posedMesh(original, original.animations[0], time);
        REQUIRE(moved.positions.size() == reference.positions.size());
        for (std::size_t v = 0; v < moved.positions.size(); ++v)
            farthest = std::max(farthest, (moved.positions[v] - reference.positions[v]).norm());
    }
    CHECK(farthest > 0);
    CHECK(farthest <= allowed);
    // As X3D: a TimeSensor and an interpolator for each wheel (X_ITE loads it: test_interop).
    const CommandResult x3d = runCommand(kSymcompress + " -q " + quoted(input) + " -o " + quoted(folder / "truck.x3d"));
    CHECK(x3d.status == 0);
    const std::string text = readTextFile(folder / "truck.x3d");
    CHECK(text.find("<TimeSensor") != std::string::npos);
    CHECK(text.find("<OrientationInterpolator", text.find("<OrientationInterpolator") + 1) != std::string::npos);
    // OBJ keeps none: said, not silent.
    const CommandResult obj = runCommand(kSymcompress + " convert " + quoted(input) + " -o " + quoted(folder / "truck.obj"));
    CHECK(obj.status == 0);
    CHECK(obj.output.find("1 animations not written: .obj output is drawn at rest") != std::string::npos);
}

TEST_CASE("Cameras and lights stay where they were: the sterile room's, the Chevy's viewpoints", "[compress]") {
    TemporaryFolder folder;
    const auto input = modelPath("cge_sterile_room/sterile_room.gltf");
    const nlohmann::json report = compressAndVerify(input, folder, "room");
    CHECK(report["cameras_and_lights_kept"] == 3);
    const Scene original = readScene(input), compressed = readScene(folder / "room.glb");
    REQUIRE(compressed.cameras.size() == 1);
    REQUIRE(compressed.lights.size() == 2);
    const std::vector<Eigen::Matrix4d> before = worldTransforms(original), after = worldTransforms(compressed);
    std::size_t matched = 0;
    for (std::size_t from = 0; from < original.nodes.size(); ++from) {
        if (original.nodes[from].camera < 0 && original.nodes[from].light < 0) continue;
        for (std::size_t to = 0; to < compressed.nodes.size(); ++to)
            if (compressed.nodes[to].name == original.nodes[from].name) {
                ++matched;
                CHECK(compressed.nodes[to].camera == original.nodes[from].camera);
                CHECK(compressed.nodes[to].light == original.nodes[from].light);
                CHECK((after[to] - before[from]).cwiseAbs().maxCoeff() < 1e-6);
            }
    }
    CHECK(matched == 3);
    // The Chevy's four X3D viewpoints, as X3D again.
    const CommandResult chevy = runCommand(kSymcompress + " " + quoted(modelPath("savage_chevy_tahoe/ChevyTahoe.x3d")) + " -o " +
                                           quoted(folder / "chevy.x3d"));
    CHECK(chevy.status == 0);
    CHECK(chevy.output.find("cameras, lights 4 nodes kept where they were (4 cameras, 0 lights)") != std::string::npos);
    const Scene chevyAgain = readScene(folder / "chevy.x3d");
    REQUIRE(chevyAgain.cameras.size() == 4);
    CHECK(chevyAgain.cameras[0].name == "Chevy Side View");
}

TEST_CASE("Hundreds of small copies the author shared with a scale: one meshopt batch, stored merged where nodes cost more",
          "[compress]") {
    // One box drawn by 400 nodes that scale it by 0.5, as gltfpack -mi writes a quantized mesh's instances.
    Primitive box;
    samples::appendMesh(box, samples::boxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3)));
    Scene scene = samples::singleMeshScene("box", box, {0.5, 0.5, 0.5, 1});
    scene.nodes.clear();
    scene.roots.clear();
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-50, 50);
    for (int n = 0; n < 400; ++n) {
        Node node;
        node.mesh = 0;
        node.transform.topLeftCorner<3, 3>() *= 0.5;
        node.transform.topRightCorner<3, 1>() = samples::drawnVector([&] { return coordinate(random); });
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    }
    TemporaryFolder folder;
    const auto input = writePlainGlb(scene, folder, "shared");
    // One batch, its translations through meshopt's exponential filter and its scale, the same for all, next
    // to nothing: smaller than the boxes merged, so kept as the author shared them.
    const nlohmann::json batched = compressAndVerify(input, folder, "batched");
    CHECK(batched["plan"] == "final");
    CHECK(batched["triangles_stored"] == 12);
    CHECK(batched["gpu_instancing"]["instances"] == 400);
    CHECK(batched["output_bytes"].get<double>() < batched["ablation"]["draco_alone"].get<double>());
    // As nodes, 400 nodes cost far more JSON than the boxes cost in Draco: merged.
    CompressOptions asNodes;
    asNodes.write.gpuInstancing = false;
    const nlohmann::json report = compressAndVerify(input, folder, "small", asNodes);
    CHECK(report["plan"] == "draco_alone");
    CHECK(report["triangles_stored"] == 400 * 12);
    CHECK(report["output_bytes"].get<double>() < report["ablation"]["instancing_and_regions"].get<double>());
}

TEST_CASE("Animation channels of nodes the scene does not draw are left out, and said so", "[compress]") {
    Primitive box;
    samples::appendMesh(box, samples::boxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3)));
    Scene scene = samples::singleMeshScene("box", box, {0.5, 0.5, 0.5, 1});
    scene.nodes.push_back(scene.nodes[0]);  // a second node drawing the box, which no root reaches
    AnimationChannel slide;
    slide.node = int(scene.nodes.size()) - 1;
    slide.times = {0, 1};
    slide.values = {0, 0, 0, 1, 0, 0};
    scene.animations.push_back({"slide", {slide}});
    validateScene(scene);
    const CompressedScene compressed = compressInMemory(scene);
    CHECK(compressed.scene.animations.empty());
    CHECK(compressed.stats.animatedNodesKept == 0);
    CHECK(compressed.scene.warnings.back() == "1 animation channels of nodes the scene does not draw left out");
    CHECK(compressed.stats.trianglesStored == 12);
}

TEST_CASE("Symmetric parts are stored as their fundamental regions where that pays (X3D)", "[compress]") {
    // The menger sponge (Oh, 48 elements) as X3D text: its region and a USE per copy cost far less than
    // its 2112 triangles; the rebuilt surface must be the original.
    TemporaryFolder folder;
    const auto input = modelPath("menger_sponge/Menger_sponge-Binary.stl");
    const auto output = folder / "menger.x3d", report = folder / "menger.json", flat = folder / "flat.glb";
    REQUIRE(runCommand(kSymcompress + " -q " + quoted(input) + " -o " + quoted(output) + " --report " + quoted(report)).status == 0);
    const nlohmann::json r = nlohmann::json::parse(readTextFile(report));
    CHECK(r["region_classes"] == 1);
    // The region of Oh or of a subgroup, whichever costs less: a Transform per copy.
    const int copies = r["instances"];
    CHECK(copies > 1);
    CHECK(48 % copies == 0);
    CHECK(r["ablation"]["instancing_and_regions"].get<double>() * 2 < r["ablation"]["instancing"].get<double>());
    const nlohmann::json verified =
        runJson(kSymdecompress + " " + quoted(output) + " -o " + quoted(flat) + " --json --verify " + quoted(input));
    CHECK(verified["verified"] == true);
    const nlohmann::json fromDigest = runJson(kSymdecompress + " " + quoted(output) + " -o " + quoted(flat) + " --json");
    CHECK(fromDigest["against"] == "digest");  // read back from the X3D head's meta
    CHECK(fromDigest["verified"] == true);
    if (x3dInteropAvailable()) {
        // X_ITE draws 48 shapes enclosing the volume of the original (converted to X3D as it is), within what
        // the positions' rounding to the error budget changes (a copy drawn inside out would take 2/48 of it).
        const auto plain = folder / "plain.x3d";
        REQUIRE(runCommand(kSymcompress + " convert -q " + quoted(input) + " -o " + quoted(plain)).status == 0);
        auto count = [&](const std::filesystem::path& file) {
            return runJson("node " + quoted(sharedDir() / "bench/x3d_count.js") + " " + quoted(file) + " --json");
        };
        const nlohmann::json loaded = count(output), reference = count(plain);
        CHECK(loaded["shapes"] == copies);
        CHECK(loaded["volume"].get<double>() == Approx(reference["volume"].get<double>()).epsilon(1e-3));
    }
}

TEST_CASE("The plan weighs parts by the writer's measure: the forest's trees, with normals and texture coordinates, "
          "are stored once per tree", "[compress]") {
    // Its tiles of 18 to 56 triangles cost Draco about 8 bytes a triangle with their attributes; a constant
    // cost per triangle (1.5, right for bare positions) found no copy worth a node.
    TemporaryFolder folder;
    const nlohmann::json report = compressAndVerify(modelPath("kenney_racing_forest/decoration-forest.glb"), folder, "forest");
    // The full plan's decisions, its meshes in the frames the plan chose or all in the world's.
    CHECK((report["plan"] == "final" || report["plan"] == "world_frame"));
    CHECK(report["assemblies"].get<std::size_t>() >= 2);
    CHECK(report["tiles_in_assemblies"].get<std::size_t>() >= 20);
    CHECK(report["output_bytes"].get<double>() < 0.8 * report["ablation"]["draco_alone"].get<double>());
}

TEST_CASE("The report's bytes_per_instance counts the nodes that draw a shared mesh, by the writer's measure",
          "[compress]") {
    // A part with no symmetry and no copy: stored as it is, drawn by one node that is no instance.
    TemporaryFolder folder;
    Primitive lone;
    lone.positions = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
    lone.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const nlohmann::json alone = compressAndVerify(writePlainGlb(sceneOfOneMesh("lone", lone), folder, "lone"), folder, "lone-small");
    CHECK(alone["instances"] == 0);
    CHECK(alone["bytes_per_instance"] == 0);

    // The bolts sample (12 copies of one bolt) with that part beside them: the bolts' 12 nodes, measured as
    // the file holds them (their JSON, a comma and their index in the scene), not the merged part's node.
    Scene scene = samples::makeBoltsScene();
    Primitive placed = lone;
    for (auto& p : placed.positions) p += Eigen::Vector3d(40, 0, 0);
    placed.material = scene.meshes[0].primitives[0].material;
    scene.meshes[0].primitives.push_back(placed);
    const auto output = folder / "bolts-small.glb";
    CompressOptions asNodes;
    asNodes.write.gpuInstancing = false;
    const auto input = writePlainGlb(scene, folder, "bolts");
    const CompressionReport report = compressFile(input, output, asNodes);
    REQUIRE(report.stats.instances == 12);
    const nlohmann::json gltf = glbJson(output);
    double total = 0;
    std::size_t drawing = 0;
    for (const auto& node : gltf["nodes"])
        if (node.contains("mesh") && node["mesh"] == gltf["nodes"][0]["mesh"]) total += double(node.dump().size() + 1 + 3), ++drawing;
    REQUIRE(drawing == 12);
    CHECK(report.bytesPerInstance == Approx(total / 12));

    // GPU-instanced (the default), the 12 bolts are 2 batches (the mirrored ones apart), measured as batches;
    // a batch's instances cheap enough that each bolt may be drawn as copies of its fundamental region.
    const CompressionReport batched = compressFile(input, output);
    CHECK(batched.gpuInstancing.batches == 2);
    CHECK(batched.gpuInstancing.instances % 12 == 0);
    CHECK(batched.bytesPerInstance < report.bytesPerInstance);
}

namespace {

// The GLB bytes of the full plan on an analysis made with or without the cost model's question of which
// groups can be used, and the analysis's count of groups not detected.
std::pair<std::string, std::size_t> glbWithGroupsAsked(const Scene& scene, bool ask, const std::filesystem::path& file) {
    const CompressOptions options;
    WriteOptions write;
    AnalysisOptions analysisOptions = analysisOptionsOf(options);
    if (ask) analysisOptions.groupCosts = costModelFor(FileFormat::Glb, write);
    const SceneAnalysis analysis = analyzeScene(scene, analysisOptions);
    PlanOptions planOptions = planOptionsOf(options);
    planOptions.costs = costModelFor(FileFormat::Glb, write);
    const CompressedScene compressed = compressAnalyzed(scene, analysis, planOptions);
    writeScene(compressed.scene, file, write);
    std::ifstream in(file, std::ios::binary);
    return {std::string(std::istreambuf_iterator<char>(in), {}), analysis.classification.groupsSkipped};
}

}  // namespace

TEST_CASE("Small parts alone get no symmetry group, and the output is the same byte for byte", "[compress]") {
    // Two bolts (a class of copies) and 24 distinct small parts, one of them a cube: no region of a part of
    // a few dozen triangles pays for its mesh and nodes.
    Primitive baked;
    const Primitive bolt = samples::makeBolt();
    for (int k = 0; k < 2; ++k) {
        Primitive placed = bolt;
        for (auto& p : placed.positions) p = Eigen::AngleAxisd(0.7 * k, Eigen::Vector3d::UnitX()) * p + Eigen::Vector3d(6.0 * k, 0, 0);
        for (auto& n : placed.normals) n = Eigen::AngleAxisd(0.7 * k, Eigen::Vector3d::UnitX()) * n;
        samples::appendMesh(baked, {placed.positions, placed.triangles});
    }
    std::mt19937_64 random(5);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 24; ++k) {
        std::vector<Eigen::Vector3d> points;
        while (points.size() < 16) points.push_back(samples::drawnVector([&] { return normal(random); }).normalized());
        const TriangleMesh part = k == 7 ? samples::boxMesh({0, 0, 0}, {1, 1, 1}) : triangulateFaces(makeConvexPolyhedron(points));
        samples::appendMesh(baked, samples::transformed(part, Eigen::Matrix3d::Identity(), {3.0 * k, 6, 0}));
    }
    const Scene scene = samples::singleMeshScene("parts", std::move(baked), {0.7, 0.7, 0.7, 1});
    TemporaryFolder folder;
    const auto [all, none] = glbWithGroupsAsked(scene, false, folder.path() / "all.glb");
    const auto [asked, skipped] = glbWithGroupsAsked(scene, true, folder.path() / "asked.glb");
    CHECK(none == 0);
    CHECK(skipped > 0);
    CHECK(asked == all);
}

TEST_CASE("Groups the scene's symmetry needs are detected, small or not: the room keeps its mirrored quadrants",
          "[compress]") {
    const Scene scene = samples::makeRoomScene();
    TemporaryFolder folder;
    const auto [all, none] = glbWithGroupsAsked(scene, false, folder.path() / "all.glb");
    const auto [asked, skipped] = glbWithGroupsAsked(scene, true, folder.path() / "asked.glb");
    CHECK(skipped == 0);
    CHECK(asked == all);
}

namespace {

// `count` root nodes drawing mesh 0, each turned at random, `spacing` apart along x.
void addTurnedNodes(Scene& scene, int count, double spacing, std::mt19937_64& random) {
    for (int k = 0; k < count; ++k) {
        Node node;
        node.mesh = 0;
        node.transform.topLeftCorner<3, 3>() = samples::randomRotation(random);
        node.transform.topRightCorner<3, 1>() = Eigen::Vector3d(spacing * k, 0, 0);
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    }
}

}  // namespace

TEST_CASE("What a file names and notes comes out with it: the root's extras, a part's mesh name and extras",
          "[compress]") {
    // A part drawn by three nodes, turned: too small for a node per copy to pay (stored as it is, merged), or
    // large enough (one stored copy).
    const bool large = GENERATE(false, true);
    INFO((large ? "large" : "small"));
    std::mt19937_64 random(11);
    Scene scene;
    scene.meshes.push_back({});
    scene.meshes[0].name = "bracket";
    scene.meshes[0].extrasJson = R"({"part":7})";
    scene.meshes[0].primitives.emplace_back();
    samples::appendMesh(scene.meshes[0].primitives[0],
                        large ? samples::unevenEllipsoid(48, 3) : samples::randomConvexPart(random));
    addTurnedNodes(scene, 3, 5, random);
    scene.rootExtrasJson = R"({"project":"mill"})";
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "in.glb", plain);
    const CompressionReport report = compressFile(folder / "in.glb", folder / "out.glb", CompressOptions{});
    CHECK(report.stats.instances == (large ? 3 : 0));
    const nlohmann::json out = glbJson(folder / "out.glb");
    CHECK(out["extras"]["project"] == "mill");
    REQUIRE(out["meshes"].size() == 1);
    CHECK(out["meshes"][0]["name"] == "bracket");
    CHECK(out["meshes"][0]["extras"]["part"] == 7);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "in.glb").verified);
}

TEST_CASE("A scene of nothing writes no empty node list, which glTF does not allow", "[io]") {
    TemporaryFolder folder;
    writeScene(Scene{}, folder / "empty.glb", WriteOptions{});
    const nlohmann::json empty = glbJson(folder / "empty.glb");
    REQUIRE(empty["scenes"].size() == 1);
    CHECK(!empty["scenes"][0].contains("nodes"));
    if (interopAvailable()) CHECK(validatorErrors(folder / "empty.glb").empty());
}

TEST_CASE("Copies each turned its own way are stored in the frame of the node of one of them, where that is smaller",
          "[compress]") {
    // A stair of boxes that three nodes draw, each turned otherwise: stored as turned in the world, its corners
    // share no coordinates, and Draco codes it larger (50 wingnuts: 15 bits where their own frame takes 14).
    std::mt19937_64 random(5);
    Scene scene;
    scene.meshes.push_back({});
    scene.meshes[0].primitives.emplace_back();
    for (int step = 0; step < 24; ++step)
        samples::appendMesh(scene.meshes[0].primitives[0], samples::boxMesh(Eigen::Vector3d(0.5 * step, 0, 0.25 * step),
                                                                            Eigen::Vector3d(0.5, 3, 0.25)));
    auto boxSizes = [](const std::vector<Eigen::Vector3d>& positions) {
        Eigen::AlignedBox3d box;
        for (const Eigen::Vector3d& p : positions) box.extend(p);
        return Eigen::Vector3d(box.sizes());
    };
    const Eigen::Vector3d modelled = boxSizes(scene.meshes[0].primitives[0].positions);
    addTurnedNodes(scene, 3, 30, random);
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "in.glb", plain);
    const CompressionReport report = compressFile(folder / "in.glb", folder / "out.glb", CompressOptions{});
    REQUIRE(report.stats.instances == 3);
    const Scene out = readScene(folder / "out.glb");
    REQUIRE(out.meshes.size() == 1);
    const Eigen::Vector3d stored = boxSizes(out.meshes[0].primitives[0].positions);
    INFO("stored " << stored.transpose() << ", modelled " << modelled.transpose());
    CHECK((stored - modelled).cwiseAbs().maxCoeff() < 1e-3 * modelled.maxCoeff());
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "in.glb").verified);
}
