// Pruning and deduplication before tiling: each acts where it must and not where it must not; what a
// viewer draws (every material's fields but names, every primitive's texture) stays the same.
#include "plan/primitives_by_kind.hpp"
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// One triangle per material index, side by side.
Scene sceneOfMaterials(const std::vector<Material>& materials, const std::vector<int>& drawn) {
    Scene scene;
    scene.materials = materials;
    Mesh mesh;
    for (std::size_t i = 0; i < drawn.size(); ++i) {
        Primitive triangle;
        triangle.positions = {{double(i), 0, 0}, {double(i) + 1, 0, 0}, {double(i), 1, 0}};
        triangle.triangles = {{0, 1, 2}};
        triangle.material = drawn[i];
        mesh.primitives.push_back(triangle);
    }
    scene.meshes.push_back(mesh);
    scene.nodes.push_back({});
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    return scene;
}

Material named(const std::string& name, double red) {
    Material material;
    material.name = name;
    material.baseColorFactor = {red, 0.5, 0.5, 1};
    return material;
}

}  // namespace

TEST_CASE("Materials equal but for their names are merged into the first (its name kept) and one factor apart stay two",
          "[optimize]") {
    Scene scene = sceneOfMaterials({named("a", 0.2), named("b", 0.2), named("c", 0.3)}, {0, 1, 2});
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.materialsMerged == 1);
    CHECK(report.materialsRemoved == 1);
    REQUIRE(scene.materials.size() == 2);
    CHECK(scene.materials[0].name == "a");
    CHECK(scene.materials[1].name == "c");  // baseColorFactor 0.3 against 0.2: not merged
    const auto& primitives = scene.meshes[0].primitives;
    CHECK(primitives[0].material == 0);
    CHECK(primitives[1].material == 0);
    CHECK(primitives[2].material == 1);
    validateScene(scene);

    Scene kept = sceneOfMaterials({named("a", 0.2), named("b", 0.2)}, {0, 1});
    OptimizeOptions noDedup;
    noDedup.dedup = false;
    CHECK(optimizeScene(kept, noDedup).materialsMerged == 0);
    CHECK(kept.materials.size() == 2);
}

TEST_CASE(
    "Primitives joined by base colour: where the measure finds it smaller, colours multiplied into their own, and "
    "not across materials that differ otherwise, variants, morph targets or lines",
    "[optimize][join]") {
    // Triangles in materials 0 to 2 (base colours only apart), 3 (its roughness apart too); material 4 unused.
    Scene scene = sceneOfMaterials({named("a", 0.2), named("b", 0.4), named("c", 0.6), named("d", 0.8), named("e", 1)},
                                   {0, 1, 2, 3});
    scene.materials[3].roughnessFactor = 0.5;
    // Each primitive's bytes: a header per primitive, and colours at 4 bytes a vertex.
    auto measure = [](double perColour) {
        return [perColour](const Primitive& p) {
            return 400 + 10 * double(p.positions.size() + perColour * p.colors.size());
        };
    };
    SECTION("joined where smaller: the members' materials left unused removed, the input's unused one kept") {
        scene.meshes[0].primitives[2].colors.assign(3, Eigen::Vector4d(0.5, 1, 1, 0.25));  // multiplied by its base
        const BaseColorJoins joins = joinByBaseColor(scene, measure(1), 80);
        CHECK(joins.primitivesJoined == 3);
        CHECK(joins.joinedPrimitives == 1);
        CHECK(joins.materialsRemoved == 3);
        validateScene(scene);
        REQUIRE(scene.materials.size() == 3);  // d, e, and the joined one
        CHECK(scene.materials[0].name == "d");
        CHECK(scene.materials[1].name == "e");
        CHECK(scene.materials[2].baseColorFactor == Eigen::Vector4d(1, 1, 1, 1));
        const auto& primitives = scene.meshes[0].primitives;
        REQUIRE(primitives.size() == 2);
        const Primitive& joined = primitives[0];  // in its first member's place
        CHECK(joined.material == 2);
        CHECK(primitives[1].material == 0);
        REQUIRE(joined.colors.size() == 9);
        CHECK(joined.colors[0] == Eigen::Vector4d(0.2, 0.5, 0.5, 1));
        CHECK(joined.colors[3] == Eigen::Vector4d(0.4, 0.5, 0.5, 1));
        CHECK(joined.colors[6] == Eigen::Vector4d(0.3, 0.5, 0.5, 0.25));
        CHECK(joined.colorBits > 0);
        CHECK(joined.triangles[2] == Triangle{6, 7, 8});
    }
    SECTION(
        "a part far smaller than the others is joined only with parts of its size: it would hold them to its "
        "precision") {
        for (Eigen::Vector3d& p : scene.meshes[0].primitives[2].positions) p *= 0.05;
        const BaseColorJoins joins = joinByBaseColor(scene, measure(1), 80);
        CHECK(joins.primitivesJoined == 2);
        REQUIRE(scene.meshes[0].primitives.size() == 3);
        CHECK(scene.meshes[0].primitives[0].colors.size() == 6);  // materials 0 and 1
        CHECK(scene.meshes[0].primitives[1].colors.empty());      // material 2's, small
    }
    SECTION("not where the measure finds the joined one larger") {
        const Scene before = scene;
        CHECK(joinByBaseColor(scene, measure(100), 80).primitivesJoined == 0);
        CHECK(scene.meshes[0].primitives.size() == 4);
        CHECK(scene.materials.size() == before.materials.size());
    }
    SECTION(
        "not a material a variant swaps, primitives with morph targets, lines, of one material, specular-glossiness "
        "or the default material") {
        // Two triangles in materials 0 and 1, which differ only in base colour, each case keeping them apart.
        auto joinsIn = [&](const std::function<void(Scene&)>& change) {
            Scene two = sceneOfMaterials({named("a", 0.2), named("b", 0.4)}, {0, 1});
            change(two);
            validateScene(two);
            return joinByBaseColor(two, measure(1), 80).primitivesJoined;
        };
        CHECK(joinsIn([](Scene&) {}) == 2);
        CHECK(joinsIn([](Scene& two) {
                  two.materials[0].variants = {1};
                  two.materialVariants = {MaterialVariant{"other", ""}};
              }) == 0);
        CHECK(joinsIn([](Scene& two) {
                  for (Primitive& p : two.meshes[0].primitives)
                      p.targets.push_back({{"POSITION", 3, std::vector<double>(9, 0.1)}});
              }) == 0);
        CHECK(joinsIn([](Scene& two) {
                  Primitive& lines = two.meshes[0].primitives[1];
                  lines.topology = Topology::Lines;
                  lines.triangles.clear();
                  lines.lines = {{0, 1}};
              }) == 0);
        CHECK(joinsIn([](Scene& two) { two.meshes[0].primitives[1].material = 0; }) == 0);  // one material
        CHECK(joinsIn([](Scene& two) {
                  for (Material& m : two.materials)
                      m.extensions.push_back({"KHR_materials_pbrSpecularGlossiness", R"({"diffuseFactor":[1,0,0,1]})"});
              }) == 0);
        // named() leaves metallic and roughness at 1, as the default material has them.
        CHECK(joinsIn([](Scene& two) { two.meshes[0].primitives[1].material = -1; }) == 0);
    }
}

TEST_CASE("Textures of the same image are merged and different images stay apart", "[optimize]") {
    Scene scene =
        sceneOfMaterials({named("a", 1), named("b", 1), named("c", 1), named("d", 1), named("e", 1)}, {0, 1, 2, 3, 4});
    scene.textures.resize(5);
    scene.textures[0].bytes = scene.textures[1].bytes = {1, 2, 3};  // the same image twice
    scene.textures[2].bytes = {1, 2, 4};
    scene.textures[3].uri = scene.textures[4].uri = "missing.png";  // not read, the same reference
    for (int m = 0; m < 5; ++m) scene.materials[std::size_t(m)].baseColorTexture.texture = m;
    scene.textures[0].mimeType = scene.textures[1].mimeType = scene.textures[2].mimeType = "image/png";
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.texturesMerged == 2);
    // Materials b and e become equal to a and d (the same image now): merged too.
    CHECK(report.materialsMerged == 2);
    CHECK(scene.textures.size() == 3);
    CHECK(scene.materials.size() == 3);
    validateScene(scene);
}

TEST_CASE("Materials no primitive uses and textures no material uses are removed and every index remapped",
          "[optimize]") {
    Scene scene = sceneOfMaterials({named("unused", 0.1), named("used", 0.2), named("also unused", 0.3)}, {1, -1});
    scene.textures.resize(2);
    scene.textures[1].bytes = {7};
    scene.materials[1].baseColorTexture.texture = 1;
    scene.materials[2].baseColorTexture.texture = 0;
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.materialsRemoved == 2);
    CHECK(report.texturesRemoved == 1);
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].name == "used");
    CHECK(scene.materials[0].baseColorTexture.texture == 0);
    CHECK(scene.textures[0].bytes == std::vector<std::uint8_t>{7});
    CHECK(scene.meshes[0].primitives[0].material == 0);
    CHECK(scene.meshes[0].primitives[1].material == -1);
    validateScene(scene);

    Scene kept = sceneOfMaterials({named("unused", 0.1), named("used", 0.2)}, {1});
    OptimizeOptions noPrune;
    noPrune.prune = false;
    CHECK(optimizeScene(kept, noPrune).materialsRemoved == 0);
    CHECK(kept.materials.size() == 2);
}

TEST_CASE(
    "symcompress merges duplicate materials before tiling: one primitive where there were two, and the report says so",
    "[optimize][compress]") {
    // Two boxes apart, each of its own material; the materials differ only by their names.
    TemporaryFolder folder;
    Primitive boxes;
    samples::appendMesh(boxes, samples::boxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3)));
    Primitive second = boxes;
    for (auto& p : second.positions) p += Eigen::Vector3d(5, 0, 0);
    Scene scene = samples::singleMeshScene("boxes", boxes, {0.5, 0.5, 0.5, 1});
    scene.materials.push_back(scene.materials[0]);
    scene.materials[1].name = "copy of the first";
    second.material = 1;
    scene.meshes[0].primitives.push_back(second);
    WriteOptions plain;
    plain.draco = false;
    const auto input = folder / "boxes.glb";
    writeScene(scene, input, plain);

    const CompressionReport merged = compressFile(input, folder / "merged.glb");
    CHECK(merged.optimizations.materialsMerged == 1);
    const Scene out = readScene(folder / "merged.glb");
    REQUIRE(out.materials.size() == 1);
    Material expected = scene.materials[0];
    CHECK(out.materials[0].baseColorFactor.isApprox(expected.baseColorFactor, 1e-6));
    CHECK(nlohmann::json::parse(merged.json())["optimizations"]["materials_merged"] == 1);

    CompressOptions noDedup;
    noDedup.optimize.dedup = false;
    noDedup.optimize.joinByBaseColor = false;  // which would draw them as one primitive too
    const CompressionReport apart = compressFile(input, folder / "apart.glb", noDedup);
    CHECK(apart.optimizations.materialsMerged == 0);
    CHECK(readScene(folder / "apart.glb").materials.size() == 2);
    CHECK(merged.outputBytes < apart.outputBytes);
}

namespace {

// A unit box split by face (24 vertices), each face's vertices with the face's normal, and a second
// primitive: the same box with every normal turned `tilt` radians about x (no longer its faces' own).
Scene boxesWithFaceNormals(double tilt, int material = -1) {
    const TriangleMesh box = samples::boxMesh({0, 0, 0}, {1, 1, 1});
    Primitive split;
    for (const Triangle& t : box.triangles) {
        const auto first = std::uint32_t(split.positions.size());
        const Eigen::Vector3d normal =
            (box.positions[t[1]] - box.positions[t[0]]).cross(box.positions[t[2]] - box.positions[t[0]]).normalized();
        for (std::uint32_t v : t) {
            split.positions.push_back(box.positions[v]);
            split.normals.push_back(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()) * normal);
        }
        split.triangles.push_back({first, first + 1, first + 2});
    }
    split.material = material;
    Scene scene;
    scene.meshes.push_back({});
    scene.meshes[0].primitives.push_back(split);
    scene.nodes.push_back({});
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    return scene;
}

}  // namespace

TEST_CASE("Normals that are their triangles' own are dropped and the vertices they split merged", "[optimize]") {
    Scene flat = boxesWithFaceNormals(0);
    REQUIRE(flat.meshes[0].primitives[0].positions.size() == 36);
    CHECK(dropFlatNormals(flat) == 1);
    const Primitive& box = flat.meshes[0].primitives[0];
    CHECK(box.normals.empty());
    CHECK(box.positions.size() == 8);
    CHECK(box.triangles.size() == 12);
    CHECK_NOTHROW(validateScene(flat));
    // The surface is the same, triangle by triangle.
    const TriangleMesh before = worldMesh(boxesWithFaceNormals(0)), after = worldMesh(flat);
    for (std::size_t t = 0; t < 12; ++t)
        for (int k = 0; k < 3; ++k)
            CHECK(before.positions[before.triangles[t][k]] == after.positions[after.triangles[t][k]]);

    SECTION("normals a degree off their faces shade otherwise: kept") {
        Scene tilted = boxesWithFaceNormals(M_PI / 180);
        CHECK(dropFlatNormals(tilted) == 0);
        CHECK(tilted.meshes[0].primitives[0].normals.size() == 36);
    }
    SECTION("a sliver far out, whose normal float32 cannot tell, asks nothing; more than 1% of them keep the normals") {
        // A triangle 0.07 long and 6e-5 wide in a plane turned off the axes, 350 units out: float32's rounding
        // of its corners turns its normal by more than the angle, while its stored normal is the plane's.
        const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 3).normalized(), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
        const Eigen::Vector3d origin(350, 200, 100);
        auto addSliver = [&](Primitive& primitive, double along) {
            const auto first = std::uint32_t(primitive.positions.size());
            const Eigen::Vector3d start = origin + along * e2;
            for (const Eigen::Vector3d& p :
                 std::vector<Eigen::Vector3d>{start, start + 0.07 * e1, start + 0.035 * e1 + 6e-5 * e2}) {
                primitive.positions.push_back(p.cast<float>().cast<double>());
                primitive.normals.push_back(n);
            }
            primitive.triangles.push_back({first, first + 1, first + 2});
            const Eigen::Vector3d* p = &primitive.positions[first];
            REQUIRE((p[1] - p[0]).cross(p[2] - p[0]).normalized().dot(n) < 0.9999);  // it would fail the test
        };
        Scene scene = boxesWithFaceNormals(0);
        Primitive& boxes = scene.meshes[0].primitives[0];
        const Primitive box = boxes;
        for (int k = 1; k < 9; ++k) {  // 108 triangles in all
            Primitive moved = box;
            for (Eigen::Vector3d& p : moved.positions) p.x() += 2 * k;
            for (Triangle& t : moved.triangles)
                for (std::uint32_t& v : t) v += std::uint32_t(boxes.positions.size());
            boxes.positions.insert(boxes.positions.end(), moved.positions.begin(), moved.positions.end());
            boxes.normals.insert(boxes.normals.end(), moved.normals.begin(), moved.normals.end());
            boxes.triangles.insert(boxes.triangles.end(), moved.triangles.begin(), moved.triangles.end());
        }
        Scene many = scene;
        addSliver(boxes, 0);
        CHECK(dropFlatNormals(scene) == 1);
        addSliver(many.meshes[0].primitives[0], 0);
        addSliver(many.meshes[0].primitives[0], 0.01);
        CHECK(dropFlatNormals(many) == 0);
    }
    SECTION("a normal map reads the normals: kept") {
        Scene mapped = boxesWithFaceNormals(0, 0);
        mapped.materials.push_back({});
        mapped.textures.push_back({});
        mapped.textures[0].uri = "normal.png";
        mapped.materials[0].normalTexture.texture = 0;
        CHECK(dropFlatNormals(mapped) == 0);
    }
    SECTION("through symcompress: no NORMAL in the GLB, the report counts it, the surface verified") {
        TemporaryFolder folder;
        WriteOptions plain;
        plain.draco = false;
        writeScene(boxesWithFaceNormals(0), folder / "box.glb", plain);
        const CompressionReport report = compressFile(folder / "box.glb", folder / "small.glb");
        CHECK(report.optimizations.flatNormalsDropped == 1);
        const nlohmann::json json = glbJson(folder / "small.glb");
        for (const auto& mesh : json["meshes"])
            for (const auto& primitive : mesh["primitives"]) CHECK_FALSE(primitive["attributes"].contains("NORMAL"));
        CHECK(decompressFile(folder / "small.glb", folder / "flat.glb", folder / "box.glb").verified);
        CompressOptions keep;
        keep.optimize.dropFlatNormals = false;
        CHECK(compressFile(folder / "box.glb", folder / "kept.glb", keep).optimizations.flatNormalsDropped == 0);
        CHECK(std::filesystem::file_size(folder / "small.glb") < std::filesystem::file_size(folder / "kept.glb"));
    }
}

TEST_CASE("A small flat part is drawn by its material's smooth part, each corner given its triangle's normal",
          "[optimize][plan]") {
    // A smooth sphere and a flat box of one material, stored as they are.
    std::vector<Eigen::Vector2d> profile;
    for (int k = 0; k <= 12; ++k) profile.emplace_back(std::sin(M_PI * k / 12), -std::cos(M_PI * k / 12));
    Primitive sphere;
    samples::appendMesh(sphere, samples::latheMesh(profile, 16, Eigen::Vector3d::Zero()));
    for (const Eigen::Vector3d& p : sphere.positions) sphere.normals.push_back(p.normalized());
    Primitive box;
    samples::appendMesh(box, samples::boxMesh({5, 0, 0}, {1, 1, 1}));
    sphere.material = box.material = 0;
    PrimitivesByKind parts;
    parts.add(sphere);
    parts.add(box);
    Mesh mesh;
    parts.moveInto(mesh);
    REQUIRE(mesh.primitives.size() == 1);
    const Primitive& joined = mesh.primitives[0];
    CHECK(joined.triangles.size() == sphere.triangles.size() + 12);
    CHECK(joined.positions.size() == sphere.positions.size() + 36);
    for (std::size_t t = sphere.triangles.size(); t < joined.triangles.size(); ++t) {
        const Triangle& c = joined.triangles[t];
        const Eigen::Vector3d face =
            (joined.positions[c[1]] - joined.positions[c[0]]).cross(joined.positions[c[2]] - joined.positions[c[0]]);
        for (std::uint32_t v : c) CHECK(joined.normals[v].dot(face.normalized()) == Approx(1));
    }

    SECTION("another material's, or a larger flat part, stays a primitive of its own") {
        Primitive other = box;
        other.material = 1;
        Primitive large;
        for (int k = 0; k < 3; ++k) samples::appendMesh(large, samples::boxMesh({0, 5.0 * k, 0}, {1, 1, 1}));
        large.material = 0;
        PrimitivesByKind apart;
        apart.add(sphere);
        apart.add(other);
        apart.add(large);
        Mesh separate;
        apart.moveInto(separate);
        CHECK(separate.primitives.size() == 3);
    }
    SECTION("through symcompress: one primitive, verified") {
        Scene scene = samples::singleMeshScene("parts", sphere, {0.8, 0.2, 0.2, 1});
        scene.meshes[0].primitives.push_back(box);
        TemporaryFolder folder;
        WriteOptions plain;
        plain.draco = false;
        writeScene(scene, folder / "parts.glb", plain);
        compressFile(folder / "parts.glb", folder / "small.glb");
        const nlohmann::json json = glbJson(folder / "small.glb");
        std::size_t primitives = 0;
        for (const auto& m : json["meshes"]) primitives += m["primitives"].size();
        CHECK(primitives == 1);
        CHECK(decompressFile(folder / "small.glb", folder / "flat.glb", folder / "parts.glb").verified);
    }
}

TEST_CASE(
    "Animation channels that hold their node where it rests are removed, and one that moves it, or that another "
    "animation keys too, or that gives the animation its length, stays",
    "[optimize]") {
    // A triangle on node 0, rotated 30 degrees about z and 2 along x at rest, scaled by 1.5.
    Scene scene = sceneOfMaterials({}, {-1});
    const Eigen::Quaterniond rest(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()));
    scene.nodes[0].transform.topLeftCorner<3, 3>() = rest.toRotationMatrix() * 1.5;
    scene.nodes[0].transform.topRightCorner<3, 1>() = Eigen::Vector3d(2, 0, 0);
    auto channel = [](AnimationChannel::Path path, std::vector<double> times, std::vector<double> values) {
        AnimationChannel out;
        out.node = 0;
        out.path = path;
        out.times = std::move(times);
        out.values = std::move(values);
        return out;
    };
    const double x = rest.x(), y = rest.y(), z = rest.z(), w = rest.w();
    using Path = AnimationChannel::Path;
    // Still: the rest translation (float32's rounding of it), the rest rotation as its opposite quaternion too.
    const AnimationChannel stillTranslation = channel(Path::Translation, {0, 1}, {2, 0, 0, double(float(2)), 0, 0}),
                           stillRotation = channel(Path::Rotation, {0, 1}, {x, y, z, w, -x, -y, -z, -w}),
                           // Moving: the scale goes from 1.5 to 2.
        movingScale = channel(Path::Scale, {0, 1}, {1.5, 1.5, 1.5, 2, 2, 2});
    scene.animations.push_back({"still and moving", {stillTranslation, stillRotation, movingScale}});
    validateScene(scene);

    SECTION("the still ones removed, the moving one kept") {
        CHECK(removeStillChannels(scene) == 2);
        REQUIRE(scene.animations[0].channels.size() == 1);
        CHECK(scene.animations[0].channels[0].path == Path::Scale);
    }
    SECTION("a rotation a little off its rest stays") {
        scene.animations[0].channels[1].values[2] += 1e-4;
        CHECK(removeStillChannels(scene) == 1);
        CHECK(scene.animations[0].channels.size() == 2);
    }
    SECTION("a still channel that another animation keys too stays: played together, the two blend") {
        scene.animations.push_back({"turning", {channel(Path::Rotation, {0, 1}, {x, y, z, w, 0, 0, 0, 1})}});
        CHECK(removeStillChannels(scene) == 1);
        CHECK(scene.animations[0].channels.size() == 2);
        CHECK(scene.animations[0].channels[0].path == Path::Rotation);
    }
    SECTION("a still channel whose last key is the animation's last stays: it gives the animation its length") {
        scene.animations[0].channels[0].times = {0, 3};
        CHECK(removeStillChannels(scene) == 1);
        CHECK(scene.animations[0].channels[0].path == Path::Translation);
    }
    SECTION("an animation of still channels only keeps one") {
        scene.animations[0].channels.pop_back();
        CHECK(removeStillChannels(scene) == 1);
        CHECK(scene.animations[0].channels.size() == 1);
    }
    SECTION("--no-prune keeps them all") {
        OptimizeOptions keep;
        keep.prune = false;
        CHECK(optimizeScene(scene, keep).stillChannelsRemoved == 0);
        CHECK(scene.animations[0].channels.size() == 3);
        CHECK(optimizeScene(scene).stillChannelsRemoved == 2);
    }
}
