// The glTF writer's numbers: each as short as what a reader keeps of it (float32 for positions and
// translations, 1e-7 for rotations), and defaults left out; the file reads back to the same scene. And its
// measure of a mesh, which the compression plan weighs its choices with.
#include "common/number_text.hpp"
#include "geometry/bounds.hpp"
#include "io/gltf_instance_encoding.hpp"
#include "io/primitive_encodings.hpp"
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstring>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

TEST_CASE("Rounding helpers: float32 text reads back to the same float, rotation noise prints as 0", "[io]") {
    for (double value : {0.1, 1.0 / 3.0, -123456.789, 0.03323778510093689, 6.4000000953674316, 1e-30}) {
        const double shortened = asFloat32(value);
        CHECK(static_cast<float>(shortened) == static_cast<float>(value));
        CHECK(nlohmann::json(shortened).dump().size() <= 16);  // at most 9 digits, sign, point and exponent
    }
    CHECK(nlohmann::json(asFloat32(0.800000011920929)).dump() == "0.8");
    CHECK(roundedDecimals(-3.047421e-10, 7) == 0.0);
    CHECK(nlohmann::json(roundedDecimals(-3.047421e-10, 7)).dump() == "0.0");  // not "-0.0"
    CHECK(roundedDecimals(0.70710678118, 7) == 0.7071068);
}

TEST_CASE("meshopt's exponential filter: zeros lifted leave a vector its own exponent and still decode as 0", "[io]") {
    const std::vector<float> values = {0, 0.0189325f, 0, /**/ 0, 0, 0, /**/ -0.5f, 0.25f, 0.125f};
    for (const int bits : {8, 12, 16, 23}) {
        INFO(bits << " bits");
        const std::vector<float> plain = exponentialDecoded(exponentialFiltered(values, 3, bits, false), 3);
        const std::vector<float> lifted = exponentialDecoded(exponentialFiltered(values, 3, bits, true), 3);
        for (const std::size_t zero : {0, 2, 3, 4, 5}) CHECK(lifted[zero] == 0.0f);
        // 0.0189 steps by 2^-5 of a unit of its own at most (its exponent -5): alone, not where its zeros set 0.
        CHECK(std::abs(lifted[1] - values[1]) <= std::ldexp(1.0, -5 - bits + 1));
        if (bits < 23) CHECK(std::abs(plain[1] - values[1]) > std::ldexp(1.0, -5 - bits + 1));
        for (std::size_t c = 6; c < 9; ++c) CHECK(lifted[c] == plain[c]);  // no zeros: the same
    }
}

TEST_CASE("Written glTF nodes and materials carry no needless digits and no defaults", "[io]") {
    Scene scene;
    scene.materials.emplace_back();
    scene.materials[0].baseColorFactor = {0.8f, 0.8f, 0.8f, 1};
    scene.meshes.emplace_back();
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1.0 / 3.0, 0, 0}, {0, 0.1, 0}};
    triangle.triangles = {{0, 1, 2}};
    triangle.material = 0;
    scene.meshes[0].primitives.push_back(triangle);
    // A node turned by 1e-9 rad (noise from a rotation solve) and moved by float32-rounded values and by noise far
    // below float32's precision at the largest of them (a placement's rounding); a mirror turned by 90 degrees.
    Node noisy, mirror;
    noisy.mesh = mirror.mesh = 0;
    noisy.transform.topLeftCorner<3, 3>() = Eigen::AngleAxisd(1e-9, Eigen::Vector3d::UnitY()).toRotationMatrix();
    noisy.transform.topRightCorner<3, 1>() = Eigen::Vector3d(double(0.1f), double(9.44278356f), 1.9e-15);
    mirror.transform.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() * Eigen::Vector3d(-1, 1, 1).asDiagonal();
    // Scales at float32's noise about 1 (Cesium Man's joints: 0.9999999, 0.9999998, 0.99999994) are none; a
    // thousandth is kept.
    Node nearOne = noisy, scaled = noisy;
    nearOne.transform.topLeftCorner<3, 3>() = Eigen::Vector3d(0.9999998, 1.0000001, 0.99999994).asDiagonal();
    scaled.transform.topLeftCorner<3, 3>() = Eigen::Vector3d(1.001, 1, 1).asDiagonal();
    scene.nodes = {noisy, mirror, nearOne, scaled};
    scene.roots = {0, 1, 2, 3};

    TemporaryFolder folder;
    for (bool draco : {true, false}) {
        WriteOptions options;
        options.draco = draco;
        const auto file = folder / (draco ? "draco.glb" : "plain.glb");
        writeScene(scene, file, options);
        const nlohmann::json root = glbJson(file);
        INFO(root.dump());
        CHECK_FALSE(root["nodes"][0].contains("rotation"));
        // Whole numbers as integers (0 for 0.0 and for the noise).
        CHECK(root["nodes"][0]["translation"].dump() == "[0.1,9.442783,0]");
        CHECK(root["nodes"][1]["rotation"].dump() == "[0,0,0.7071068,0.7071068]");
        CHECK(root["nodes"][1]["scale"].dump() == "[-1,1,1]");
        CHECK_FALSE(root["nodes"][2].contains("scale"));
        CHECK(root["nodes"][3]["scale"].dump() == "[1.001,1,1]");
        CHECK(root["materials"][0].dump() == R"({"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1]}})");
        // Draco's bounds are those of the quantized positions it decodes to.
        if (!draco) CHECK(root["accessors"][0]["max"].dump() == "[0.33333334,0.1,0]");
        for (const auto& bound : root["accessors"][0]["max"]) CHECK(bound.dump().size() <= 10);
        CHECK_FALSE(root["meshes"][0]["primitives"][0].contains("mode"));
        CHECK_FALSE(root["bufferViews"][0].contains("byteOffset"));

        const Scene back = readScene(file);
        REQUIRE(back.nodes.size() == 4);
        CHECK(back.nodes[0].transform.isApprox(scene.nodes[0].transform, 1e-7));
        CHECK(back.nodes[1].transform.isApprox(scene.nodes[1].transform, 1e-7));
        CHECK(back.materials[0].baseColorFactor.isApprox(scene.materials[0].baseColorFactor, 1e-7));
        CHECK(back.materials[0].metallicFactor == 1);
    }
}

TEST_CASE("The asset names symcompress once: in the digest where there is one, else as the generator", "[io]") {
    TemporaryFolder folder;
    const Scene scene = samples::makeThreeSpheresScene();
    writeScene(scene, folder / "plain.glb");
    CHECK(glbJson(folder / "plain.glb")["asset"]["generator"] == "symcompress");
    WriteOptions withDigest;
    withDigest.extrasJson = SurfaceDigest{}.json();
    writeScene(scene, folder / "digest.glb", withDigest);
    const nlohmann::json asset = glbJson(folder / "digest.glb")["asset"];
    CHECK(asset["extras"].contains("symcompress_digest"));
    CHECK_FALSE(asset.contains("generator"));
    WriteOptions otherExtras;
    otherExtras.extrasJson = R"({"author":"someone"})";
    writeScene(scene, folder / "other.glb", otherExtras);
    CHECK(glbJson(folder / "other.glb")["asset"]["generator"] == "symcompress");
}

TEST_CASE("A node that shears is written as TRS nodes, as glTF requires, and draws the same", "[io]") {
    // X3D's scaleOrientation gives such transforms (the Chevy Tahoe's parts); glTF requires node matrices to
    // decompose into translation, rotation and scale, and glTF Transform reads one that does not wrongly.
    Scene scene;
    scene.meshes.emplace_back();
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
    triangle.triangles = {{0, 1, 2}};
    scene.meshes[0].primitives.push_back(triangle);
    Node shear, child, stretched;
    shear.name = "shear";
    shear.transform.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() *
                                            Eigen::Vector3d(0.5, -2, 3).asDiagonal() *
                                            Eigen::AngleAxisd(-1.1, Eigen::Vector3d(3, -1, 2).normalized()).toRotationMatrix();
    shear.transform.topRightCorner<3, 1>() = Eigen::Vector3d(1, 2, 3);
    shear.mesh = 0;
    shear.children = {1};
    child.mesh = 0;
    child.transform.topRightCorner<3, 1>() = Eigen::Vector3d(0, 5, 0);
    // Non-uniform scale along turned axes, mirrored: TRS holds it in one node.
    stretched.mesh = 0;
    stretched.transform.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix() * Eigen::Vector3d(1, -2, 4).asDiagonal();
    scene.nodes = {shear, child, stretched};
    scene.roots = {0, 2};

    TemporaryFolder folder;
    const auto file = folder / "shear.glb";
    writeScene(scene, file, WriteOptions{});
    const nlohmann::json root = glbJson(file);
    INFO(root["nodes"].dump());
    CHECK(root["nodes"].size() == 4);  // the shearing node split in two
    for (const auto& node : root["nodes"]) CHECK_FALSE(node.contains("matrix"));
    CHECK(root["nodes"][0]["name"] == "shear");
    CHECK_FALSE(root["nodes"][0].contains("mesh"));
    CHECK(root["nodes"][2]["scale"].size() == 3);
    const Scene back = readScene(file);
    const std::vector<Eigen::Matrix4d> before = worldTransforms(scene), after = worldTransforms(back);
    std::vector<Eigen::Matrix4d> drawingBefore, drawingAfter;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
        if (scene.nodes[n].mesh >= 0) drawingBefore.push_back(before[n]);
    for (std::size_t n = 0; n < back.nodes.size(); ++n)
        if (back.nodes[n].mesh >= 0) drawingAfter.push_back(after[n]);
    REQUIRE(drawingAfter.size() == drawingBefore.size());
    for (const Eigen::Matrix4d& m : drawingBefore)  // the split node's mesh moves to its new child, last
        CHECK(std::any_of(drawingAfter.begin(), drawingAfter.end(), [&](const Eigen::Matrix4d& a) { return a.isApprox(m, 1e-6); }));
}

TEST_CASE("gltfMeshBytes measures a part far from the origin about its centre, as the plan's scene stores it", "[io]") {
    // Found by a sweep of variants: a chess set placed 4e5 units away took 10 s to plan (0.03 at home), Draco
    // measuring each part at the 24 bits float32's rounding there asked for.
    Primitive far = samples::makeBolt();
    for (Eigen::Vector3d& p : far.positions) p += Eigen::Vector3d(235933.16, -188746.52, 251662.03);
    Primitive centred = far;
    const Eigen::Vector3d centre = boundsOf(far.positions).center();
    for (Eigen::Vector3d& p : centred.positions) p -= centre;
    WriteOptions options;
    options.maxPositionError = 1e-4;
    CHECK(gltfMeshBytes(far, options) == gltfMeshBytes(centred, options));
    // With fixed bits there is no bound to round within: measured where it is.
    CHECK(gltfMeshBytes(far, WriteOptions()) > 0);
}

TEST_CASE("gltfMeshBytes and x3dMeshBytes are what a mesh of its own adds to the written file", "[io]") {
    // A bolt with normals and texture coordinates: what the plan weighs a stored part with.
    Primitive part = samples::makeBolt();
    for (const Eigen::Vector3d& p : part.positions) {
        part.normals.push_back(p.normalized());
        part.texcoords.push_back({p.x(), p.y()});
    }
    Primitive bare = part;
    bare.normals.clear();
    bare.texcoords.clear();
    Primitive untextured = part;
    untextured.texcoords.clear();
    Scene one;
    one.meshes.push_back({"", {part}});
    one.nodes.resize(1);
    one.nodes[0].mesh = 0;
    one.roots = {0};
    Scene two = one;
    two.meshes.push_back({"", {part}});
    two.nodes.push_back(one.nodes[0]);
    two.nodes[1].mesh = 1;
    two.roots = {0, 1};
    // Both writers write the same part twice once (glTF: primitives equal but for their material share their
    // accessors; X3D: a geometry node of the same text is USEd): the second part differs where it costs as many
    // bytes. glTF: moved by a length float32 holds exactly (Draco codes it alike); X3D: its triangles listed
    // backwards.
    Scene twoApart = two;
    for (Eigen::Vector3d& p : twoApart.meshes[1].primitives[0].positions) p.x() += 8;
    Scene twoListedOtherwise = two;
    std::vector<Triangle>& triangles = twoListedOtherwise.meshes[1].primitives[0].triangles;
    std::reverse(triangles.begin(), triangles.end());
    TemporaryFolder folder;
    struct Case {
        const char* extension;
        bool draco;
        double margin;  // the second node's own bytes: glTF {"mesh":1} and its root index; X3D none (it does nothing)
        bool viewsShared;  // plain glTF: the second part's data goes in the first's views, whose JSON it measures
    };
    for (const Case& c :
         {Case{".glb", true, 24, false}, Case{".glb", false, 120, true}, Case{".x3d", false, 40, false}}) {
        INFO(c.extension << " draco " << c.draco);
        WriteOptions options;
        options.draco = c.draco;
        const auto first = folder / (std::string("one") + c.extension), second = folder / (std::string("two") + c.extension);
        writeScene(one, first, options);
        writeScene(std::string(c.extension) == ".glb" ? twoApart : twoListedOtherwise, second, options);
        const double added = double(std::filesystem::file_size(second)) - double(std::filesystem::file_size(first));
        const bool x3d = std::string(c.extension) == ".x3d";
        const auto measure = [&](const Primitive& p) { return double(x3d ? x3dMeshBytes(p, options) : gltfMeshBytes(p, options)); };
        CHECK(measure(part) == Approx(added).margin(c.margin));
        if (!c.viewsShared) CHECK(measure(part) <= added);
        // Normals and texture coordinates are measured: in glTF a bare bolt costs far fewer bytes (0.73 of them);
        // in X3D, where the browser makes the bolt's smooth normals, its texture coordinates (written as float32
        // text) cost a fifth (the bare bolt, flat, keeps its vertices apart).
        if (x3d)
            CHECK(measure(untextured) < 0.85 * measure(part));
        else
            CHECK(measure(bare) < 0.75 * measure(part));
    }
}

TEST_CASE("Draco encodings kept for reuse write the same file byte for byte, and a changed part is encoded anew",
          "[io]") {
    Primitive part = samples::makeBolt();
    for (const Eigen::Vector3d& p : part.positions) part.normals.push_back(p.normalized());
    Scene scene = samples::singleMeshScene("bolt", part, {0.8, 0.2, 0.1, 1});
    TemporaryFolder folder;
    const auto written = [&](const Scene& s, const WriteOptions& options, const char* name) {
        writeScene(s, folder / name, options);
        return readFileBytes(folder / name);
    };
    WriteOptions plain;
    plain.maxPositionError = 1e-4;
    WriteOptions reusing = plain;
    reusing.encodings = makePrimitiveEncodings();
    const Primitive& stored = scene.meshes[0].primitives[0];
    CHECK_FALSE(reusing.encodings->find(fingerprintOf(stored, reusing)));
    const auto expected = written(scene, plain, "plain.glb");
    CHECK(written(scene, reusing, "first.glb") == expected);
    CHECK(reusing.encodings->find(fingerprintOf(stored, reusing)));  // kept
    CHECK(written(scene, reusing, "again.glb") == expected);         // and reused
    // One coordinate moved, a normal turned, another material, another bound: none is taken for the kept one.
    std::vector<Scene> changed(4, scene);
    changed[0].meshes[0].primitives[0].positions[7].x() += 1e-9;
    changed[1].meshes[0].primitives[0].normals[3] = -changed[1].meshes[0].primitives[0].normals[3];
    changed[2].materials.push_back(changed[2].materials[0]);
    changed[2].meshes[0].primitives[0].material = 1;
    changed[3].meshes[0].primitives[0].maxPositionError = 1e-5;
    for (std::size_t c = 0; c < changed.size(); ++c) {
        INFO("change " << c);
        const Primitive& other = changed[c].meshes[0].primitives[0];
        CHECK(fingerprintOf(other, reusing) != fingerprintOf(stored, reusing));
        CHECK(written(changed[c], reusing, "changed.glb") == written(changed[c], plain, "changed_plain.glb"));
    }
    WriteOptions finer = reusing;
    finer.maxPositionError = 1e-5;
    CHECK(fingerprintOf(stored, finer) != fingerprintOf(stored, reusing));
    WriteOptions plainFiner = plain;
    plainFiner.maxPositionError = 1e-5;
    CHECK(written(scene, finer, "finer.glb") == written(scene, plainFiner, "finer_plain.glb"));
}

TEST_CASE("gltfNodeBytes and x3dNodeBytes are what a node drawing a stored mesh adds to the written file", "[io]") {
    // Instance nodes as a plan makes them: rigid, mirrored, scaled to grid steps, named or not.
    Scene one;
    one.meshes.push_back({"", {samples::makeBolt()}});
    one.nodes.resize(1);
    one.nodes[0].mesh = 0;
    one.roots = {0};
    Eigen::Matrix4d turned = Eigen::Matrix4d::Identity(), mirrored, onGrid;
    turned.topLeftCorner<3, 3>() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    turned.topRightCorner<3, 1>() = Eigen::Vector3d(1.25, -3.5, 0.123456789);
    mirrored = turned;
    mirrored.col(0) *= -1;
    onGrid = turned;
    onGrid.topLeftCorner<3, 3>() *= 1.0 / 256;
    TemporaryFolder folder;
    std::set<std::size_t> sizes;
    for (const Eigen::Matrix4d& transform : {turned, mirrored, onGrid})
        for (const char* name : {"", "Wheel.001"}) {
            Node node;
            node.transform = transform;
            node.name = name;
            node.mesh = 0;
            for (const char* extension : {".glb", ".x3d"}) {
                INFO(extension << " name '" << name << "'\n" << transform);
                const bool x3d = std::string(extension) == ".x3d";
                // X3D groups a mesh that several nodes draw, once (the Group the others USE): measured on a mesh
                // that two nodes draw already.
                Scene before = one;
                if (x3d) {
                    before.nodes.push_back(one.nodes[0]);
                    before.nodes.back().transform(0, 3) = 3;
                    before.roots.push_back(1);
                }
                Scene after = before;
                after.roots.push_back(int(after.nodes.size()));
                after.nodes.push_back(node);
                const auto first = folder / (std::string("one") + extension),
                           second = folder / (std::string("two") + extension);
                writeScene(before, first);
                writeScene(after, second);
                const double added =
                    double(std::filesystem::file_size(second)) - double(std::filesystem::file_size(first));
                const std::size_t measured = x3d ? x3dNodeBytes(node) : gltfNodeBytes(node);
                // GLB pads its JSON chunk to 4 bytes.
                CHECK(double(measured) == Approx(added).margin(x3d ? 0 : 4));
                sizes.insert(measured);
            }
        }
    CHECK(sizes.size() >= 6);  // the transform and the name are what is measured
}

TEST_CASE(
    "glTF animations: key times shared by their channels are written once, data of one type in one view, and long "
    "keys coded by meshopt without loss where the file is smaller for it",
    "[io]") {
    // Three nodes turned, moved and scaled over the same `keys` times: a smooth curve of float32 values.
    auto animated = [](std::size_t keys) {
        Scene scene;
        Primitive triangle;
        triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        triangle.triangles = {{0, 1, 2}};
        scene.meshes.push_back({"", {triangle}});
        scene.nodes.resize(3);
        scene.roots = {0, 1, 2};
        Animation animation{"walk", {}};
        for (int n = 0; n < 3; ++n) {
            scene.nodes[std::size_t(n)].mesh = 0;
            AnimationChannel channel;
            channel.node = n;
            channel.path = n == 0   ? AnimationChannel::Path::Rotation
                           : n == 1 ? AnimationChannel::Path::Translation
                                    : AnimationChannel::Path::Scale;
            for (std::size_t k = 0; k < keys; ++k) {
                const double t = double(k) / 30;
                channel.times.push_back(double(float(t)));
                const Eigen::Quaterniond turn(Eigen::AngleAxisd(t, Eigen::Vector3d(0.3, 0.9, 0.2).normalized()));
                const std::vector<double> value =
                    n == 0   ? std::vector<double>{turn.x(), turn.y(), turn.z(), turn.w()}
                    : n == 1 ? std::vector<double>{std::sin(t), 0.5 * t, 1 + 0.1 * std::cos(t)}
                             : std::vector<double>{1 + 0.1 * std::cos(t), 1, 1 + 0.05 * std::sin(t)};
                for (double x : value) channel.values.push_back(double(float(x)));
            }
            animation.channels.push_back(channel);
        }
        scene.animations.push_back(animation);
        validateScene(scene);
        return scene;
    };
    TemporaryFolder folder;
    auto samplersOf = [](const nlohmann::json& json) {
        std::set<int> inputs;
        for (const auto& sampler : json["animations"][0]["samplers"]) inputs.insert(sampler["input"].get<int>());
        return inputs;
    };
    auto meshoptViews = [](const nlohmann::json& json) {
        std::size_t views = 0;
        for (const auto& view : json["bufferViews"]) views += view.contains("extensions");
        return views;
    };
    for (const std::size_t keys : {std::size_t(300), std::size_t(3)})
        for (const bool draco : {true, false}) {
            INFO(keys << " keys, draco " << draco);
            const Scene scene = animated(keys);
            WriteOptions options;
            options.draco = draco;
            const auto file = folder / ("walk" + std::to_string(keys) + (draco ? "d" : "p") + ".glb");
            writeScene(scene, file, options);
            const nlohmann::json json = glbJson(file);
            CHECK(samplersOf(json).size() == 1);
            // Coded where it pays: long keys of compressed output; never in plain output.
            const bool coded = keys == 300 && draco;
            CHECK(meshoptViews(json) == (coded ? 3 : 0));
            // One view for each type of data: the translations and the scales share one.
            const auto& samplers = json["animations"][0]["samplers"];
            const auto viewOf = [&](std::size_t s) {
                return json["accessors"][samplers[s]["output"].get<std::size_t>()]["bufferView"].get<int>();
            };
            CHECK(viewOf(1) == viewOf(2));
            CHECK(viewOf(0) != viewOf(1));
            const bool required = json.contains("extensionsRequired") &&
                                  std::count(json["extensionsRequired"].begin(), json["extensionsRequired"].end(),
                                             "EXT_meshopt_compression");
            CHECK(required == coded);
            // Read back, every value as written.
            const Scene read = readScene(file);
            REQUIRE(read.animations.size() == 1);
            REQUIRE(read.animations[0].channels.size() == 3);
            for (std::size_t c = 0; c < 3; ++c) {
                CHECK(read.animations[0].channels[c].times == scene.animations[0].channels[c].times);
                CHECK(read.animations[0].channels[c].values == scene.animations[0].channels[c].values);
            }
            if (interopAvailable()) CHECK(validatorErrors(file).empty());
        }
    // --no-gpu-instancing, for viewers without the extensions: no meshopt.
    WriteOptions without;
    without.gpuInstancing = false;
    writeScene(animated(300), folder / "walk-without.glb", without);
    CHECK(meshoptViews(glbJson(folder / "walk-without.glb")) == 0);
}

TEST_CASE("Animations are written to X3D as a TimeSensor, interpolators and ROUTEs", "[io][x3d]") {
    Scene scene;
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.triangles = {{0, 1, 2}};
    scene.meshes.push_back({"", {triangle}});
    scene.nodes.resize(2);
    scene.nodes[0].mesh = scene.nodes[1].mesh = 0;
    scene.nodes[1].name = "slider";
    scene.roots = {0, 1};
    AnimationChannel turn, slide;
    turn.node = 0;
    turn.path = AnimationChannel::Path::Rotation;
    turn.times = {0, 1.5, 3};
    const double half = std::sqrt(0.5);
    turn.values = {0, 0, 0, 1, 0, 0, half, half, 0, 0, 1, 0};  // quarter and half turns about z
    slide.node = 1;
    slide.interpolation = AnimationChannel::Interpolation::Step;
    slide.times = {1, 3};
    slide.values = {0, 0, 0, 2, 0, 0};
    scene.animations.push_back({"walk", {turn, slide}});
    validateScene(scene);
    TemporaryFolder folder;
    writeScene(scene, folder / "walk.x3d");
    const std::string text = readTextFile(folder / "walk.x3d");
    INFO(text);
    CHECK(text.find("<TimeSensor DEF='walk' cycleInterval='3' loop='true'/>") != std::string::npos);
    CHECK(text.find("<Transform DEF='node0'") != std::string::npos);  // a DEF for the unnamed node's ROUTE
    CHECK(text.find("<OrientationInterpolator DEF='walk_channel0' key='0 0.5 1' keyValue='1 0 0 0, 0 0 1 1.5707963, 0 0 1 3.1415927'/>") !=
          std::string::npos);
    // STEP: every key but the first doubled, the earlier value holding until it.
    CHECK(text.find("<PositionInterpolator DEF='walk_channel1' key='0.33333334 1 1' keyValue='0 0 0, 0 0 0, 2 0 0'/>") !=
          std::string::npos);
    CHECK(text.find("<ROUTE fromNode='walk' fromField='fraction_changed' toNode='walk_channel0' toField='set_fraction'/>") !=
          std::string::npos);
    CHECK(text.find("<ROUTE fromNode='walk_channel0' fromField='value_changed' toNode='node0' toField='set_rotation'/>") !=
          std::string::npos);
    CHECK(text.find("<ROUTE fromNode='walk_channel1' fromField='value_changed' toNode='slider' toField='set_translation'/>") !=
          std::string::npos);
    // Read back: the same channels, the doubled STEP key nudged to increase (glTF asks for it).
    const Scene back = readScene(folder / "walk.x3d");
    CHECK(back.warnings.empty());
    validateScene(back);
    REQUIRE(back.animations.size() == 1);
    CHECK(back.animations[0].name == "walk");
    REQUIRE(back.animations[0].channels.size() == 2);
    const AnimationChannel &turned = back.animations[0].channels[0], &slid = back.animations[0].channels[1];
    CHECK(back.nodes[std::size_t(turned.node)].name == "node0");
    CHECK(back.nodes[std::size_t(slid.node)].name == "slider");
    CHECK(turned.path == AnimationChannel::Path::Rotation);
    REQUIRE(turned.times.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) {
        CHECK(turned.times[k] == Approx(turn.times[k]).margin(1e-6));
        const Eigen::Quaterniond a(turn.values[4 * k + 3], turn.values[4 * k], turn.values[4 * k + 1], turn.values[4 * k + 2]),
            b(turned.values[4 * k + 3], turned.values[4 * k], turned.values[4 * k + 1], turned.values[4 * k + 2]);
        CHECK(a.angularDistance(b) < 1e-6);
    }
    CHECK(slid.path == AnimationChannel::Path::Translation);
    REQUIRE(slid.times.size() == 3);
    CHECK(slid.times[1] == Approx(3));
    CHECK(slid.times[2] > slid.times[1]);
    CHECK(slid.times[2] < 3 + 1e-5);
    CHECK(slid.values == std::vector<double>{0, 0, 0, 0, 0, 0, 2, 0, 0});
}

TEST_CASE("An image several materials show is written to X3D once and USEd, and its data: URL reads back", "[io][x3d]") {
    TemporaryFolder folder;
    Scene scene;
    // Not a real PNG: the readers and writers keep image bytes as they are. Every byte value, so that
    // every base64 digit and both paddings are exercised.
    std::vector<std::uint8_t> image(256 + 2);
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = std::uint8_t(i * 7);
    scene.textures = {{"a", "", "image/png", image}, {"b", "", "image/png", image}, {"c", "", "image/jpeg", {1, 2, 3, 4}}};
    for (int texture : {0, 1, 2}) {
        Material material;
        material.name = "m" + std::to_string(texture);
        material.baseColorTexture.texture = texture;
        scene.materials.push_back(material);
    }
    Mesh mesh;
    for (int material : {0, 1, 2}) {
        Primitive triangle;
        triangle.positions = {{0, 0, double(material)}, {1, 0, double(material)}, {0, 1, double(material)}};
        triangle.texcoords = {{0, 0}, {1, 0}, {0, 1}};
        triangle.triangles = {{0, 1, 2}};
        triangle.material = material;
        mesh.primitives.push_back(triangle);
    }
    scene.meshes.push_back(mesh);
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    writeScene(scene, folder / "shared.x3d");
    const std::string text = readTextFile(folder / "shared.x3d");
    auto count = [&](const std::string& what) { return occurrences(text, what); };
    CHECK(count("data:image/png;base64,") == 1);
    CHECK(count("data:image/jpeg;base64,") == 1);
    CHECK(count("<ImageTexture USE='texture0'") == 1);  // in the Appearance's or the material's texture field
    const Scene again = readScene(folder / "shared.x3d");
    REQUIRE(again.materials.size() == 3);
    for (int m : {0, 1, 2}) {
        REQUIRE(again.materials[std::size_t(m)].baseColorTexture.texture >= 0);
        const Texture& texture = again.textures[std::size_t(again.materials[std::size_t(m)].baseColorTexture.texture)];
        CHECK(texture.bytes == scene.textures[std::size_t(m)].bytes);
        CHECK(texture.mimeType == scene.textures[std::size_t(m)].mimeType);
    }
    CHECK(again.warnings.empty());
}

TEST_CASE("An X3D Shape that Transforms USE comes out as it went in: DEF'd once by its name, each USE one line",
          "[io][x3d]") {
    TemporaryFolder folder;
    std::string input =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Interchange\" version=\"3.3\">\n"
        "  <Scene>\n    <Transform>\n      <Shape DEF=\"Post\">\n        <Appearance><Material "
        "diffuseColor=\"0.8 0.2 0.2\"/></Appearance>\n        <Cylinder/>\n      </Shape>\n"
        "    </Transform>\n";
    for (int k = 1; k < 40; ++k)
        input += "    <Transform translation=\"" + std::to_string(3 * k) + " 0 " + std::to_string(k % 7) +
                 "\" rotation=\"0 1 0 " + std::to_string(0.1 * k).substr(0, 4) +
                 "\">\n      <Shape USE=\"Post\"/>\n"
                 "    </Transform>\n";
    input += "  </Scene>\n</X3D>\n";
    writeTextFile(folder / "posts.x3d", input);
    compressFile(folder / "posts.x3d", folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK(occurrences(text, "<Shape DEF='Post'>") == 1);
    CHECK(occurrences(text, "><Shape USE='Post'/></Transform>\n") == 39);
    CHECK(occurrences(text, "<Group") == 0);
    CHECK(occurrences(text, "DEF=") == 1);  // no Transform takes the Shape's name
    CHECK(text.size() < input.size());
    const Scene again = readScene(folder / "out.x3d");
    CHECK(std::count_if(again.nodes.begin(), again.nodes.end(), [](const Node& n) { return n.name == "Post"; }) == 40);
    CHECK(decompressFile(folder / "out.x3d", folder / "flat.glb", folder / "posts.x3d").verified);
}

TEST_CASE(
    "X3D output names only what is USEd or was named, groups a mesh only where several nodes draw it, and "
    "writes no Transform that does nothing",
    "[io][x3d]") {
    TemporaryFolder folder;
    Scene scene;
    Material paint, plain;
    paint.name = "paint";
    paint.baseColorFactor = {0.8, 0.1, 0.1, 1};
    scene.materials = {paint, plain};
    for (int m : {0, 1}) {
        Primitive triangle;
        triangle.positions = {{0, 0, double(m)}, {1, 0, double(m)}, {0, 1, double(m)}};
        triangle.triangles = {{0, 1, 2}};
        triangle.material = 0;
        Primitive other = triangle;
        other.material = m;  // the second mesh's second primitive in the unnamed material
        for (Eigen::Vector3d& p : other.positions) p.x() += 2;
        scene.meshes.push_back({"", {triangle, other}, "", {}});
    }
    // Mesh 0 drawn twice, by a node named as the writer would name its Group, and by a node that moves it; mesh 1
    // once, by a node that does nothing.
    scene.nodes.resize(3);
    scene.nodes[0].mesh = 0;
    scene.nodes[0].name = "mesh0";
    scene.nodes[1].mesh = 0;
    scene.nodes[1].transform(0, 3) = 5;
    scene.nodes[2].mesh = 1;
    scene.roots = {0, 1, 2};
    writeScene(scene, folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    auto count = [&](const std::string& what) { return occurrences(text, what); };
    CHECK(count("<Transform DEF='mesh0'>") == 1);
    CHECK(count("<Group DEF='mesh0_2'>") == 1);
    CHECK(count("<Group USE='mesh0_2'/>") == 1);
    CHECK(count("<Group") == 2);      // mesh 1's Shapes stand in the Scene
    CHECK(count("<Transform") == 2);  // not around mesh 1
    CHECK(count("<Appearance DEF='paint'>") == 1);
    CHECK(count("<Appearance USE='paint'/>") == 2);
    CHECK(count("DEF=") == 3);  // the unnamed material, used once, has none
    const Scene again = readScene(folder / "out.x3d");
    CHECK(sceneStatistics(again).trianglesDrawn == 6);
    CHECK(std::count_if(again.materials.begin(), again.materials.end(),
                        [](const Material& m) { return m.name == "paint"; }) == 1);
    CHECK(again.warnings.empty());
}

TEST_CASE(
    "Draco's speeds: a small primitive is encoded at several, the smallest kept, and a large one or a level "
    "asked at one",
    "[writers]") {
    const Scene spheres = samples::makeThreeSpheresScene();
    Primitive part = spheres.meshes[0].primitives[0];
    for (const Primitive& more : spheres.meshes[0].primitives)
        part = more.triangles.size() > part.triangles.size() ? more : part;
    WriteOptions options;
    CHECK(dracoSpeedsWorthTrying(part, options) == std::vector<int>{0, 1, 2, 5, 8});
    // Every speed but 0 on its own, as a compression level asks it: the default is no larger than any, and
    // smaller than speed 1 alone (measured: speed 0 and 1 code these spheres in 30 bytes more than 8).
    std::size_t fewest = SIZE_MAX;
    for (const int speed : {1, 2, 5, 8}) {
        WriteOptions one;
        one.compressionLevel = 10 - speed;
        CHECK(dracoSpeedsWorthTrying(part, one) == std::vector<int>{speed});
        fewest = std::min(fewest, gltfMeshBytes(part, one));
    }
    WriteOptions speedOne;
    speedOne.compressionLevel = 9;
    CHECK(gltfMeshBytes(part, options) <= fewest);
    CHECK(gltfMeshBytes(part, options) < gltfMeshBytes(part, speedOne));

    Primitive large;  // 20200 triangles: one speed, speed 0
    for (std::uint32_t i = 0; i < 10100; ++i) {
        large.positions.push_back({double(i), 0, 0});
        large.positions.push_back({double(i), 1, 0});
    }
    for (std::uint32_t i = 0; i + 1 < 10100; ++i) {
        large.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 1});
        large.triangles.push_back({2 * i + 1, 2 * i + 2, 2 * i + 3});
    }
    CHECK(dracoSpeedsWorthTrying(large, options) == std::vector<int>{0});
}

TEST_CASE(
    "Triangles of zero area are kept as many, drawing nothing: at one point under Draco and in X3D, as they are "
    "in plain glTF",
    "[io]") {
    // A cube's 12 triangles and 4 of zero area: two corners at one vertex index, two vertices at one point, all
    // three at one point, and one whose vertices no other triangle uses. Draco's edgebreaker would drop the 4, and
    // viewers count them (render_compare.sh: the triangles drawn).
    Primitive cube;
    for (int i = 0; i < 8; ++i) cube.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    cube.positions.push_back(cube.positions[3]);  // 8: at 3's point
    cube.positions.push_back({0.5, 0.5, 0.5});    // 9 and 10: used by zero-area triangles alone
    cube.positions.push_back({0.5, 0.5, 0.5});
    for (const Eigen::Vector3d& p : cube.positions) cube.texcoords.push_back({p.x(), p.y()});
    cube.normals.assign(cube.positions.size(), Eigen::Vector3d::UnitZ());
    cube.triangles.insert(cube.triangles.end(), {{0, 0, 5}, {3, 8, 6}, {8, 3, 3}, {9, 10, 9}});
    const Scene scene = sceneOfOneMesh("cube", cube);
    auto zeroArea = [](const TriangleMesh& mesh) {
        return std::count_if(mesh.triangles.begin(), mesh.triangles.end(), [&](const Triangle& t) {
            const auto& p = mesh.positions;
            return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm() == 0;
        });
    };
    TemporaryFolder folder;
    for (const bool draco : {true, false}) {
        INFO("draco " << draco);
        WriteOptions options;
        options.draco = draco;
        const auto file = folder / (draco ? "draco.glb" : "plain.glb");
        writeScene(scene, file, options);
        const TriangleMesh drawn = worldMesh(readScene(file));
        CHECK(drawn.triangles.size() == 16);
        CHECK(zeroArea(drawn) == 4);
        const nlohmann::json json = glbJson(file);
        const auto& primitives = json["meshes"][0]["primitives"];
        if (draco) {
            // The Draco primitive, and one of a vertex of the cube with its texture coordinates (not its normal),
            // indices without a buffer view: 12 zeros.
            REQUIRE(primitives.size() == 2);
            const auto& indices = json["accessors"][primitives[1]["indices"].get<std::size_t>()];
            CHECK_FALSE(indices.contains("bufferView"));
            CHECK(indices["count"] == 12);
            CHECK(primitives[1]["attributes"].contains("TEXCOORD_0"));
            CHECK_FALSE(primitives[1]["attributes"].contains("NORMAL"));
            CHECK(json["accessors"][primitives[1]["attributes"]["POSITION"].get<std::size_t>()]["max"] ==
                  nlohmann::json::array({0, 0, 0}));
        } else {
            CHECK(primitives.size() == 1);  // the triangles as they are
        }
        if (interopAvailable()) CHECK(validatorErrors(file).empty());
    }
    // Without texture coordinates, the point is a vertex at the origin where the primitive has one, and its
    // position then an accessor without a buffer view too (zeros), a corner each, without indices; elsewhere it is
    // written, and indexed.
    for (const double offset : {0.0, 0.25}) {
        INFO("offset " << offset);
        Primitive bare = cube;
        bare.texcoords.clear();
        for (Eigen::Vector3d& p : bare.positions) p -= Eigen::Vector3d::Constant(offset);
        const auto file = folder / "bare.glb";
        writeScene(sceneOfOneMesh("cube", bare), file, {});
        const nlohmann::json json = glbJson(file);
        const auto& point = json["meshes"][0]["primitives"][1];
        const auto& position = json["accessors"][point["attributes"]["POSITION"].get<std::size_t>()];
        CHECK(position.contains("bufferView") == (offset != 0));
        CHECK(point.contains("indices") == (offset != 0));
        CHECK(position["count"] == (offset != 0 ? 1 : 12));
        const TriangleMesh drawn = worldMesh(readScene(file));
        CHECK(drawn.triangles.size() == 16);
        CHECK(zeroArea(drawn) == 4);
        if (interopAvailable()) CHECK(validatorErrors(file).empty());
    }
    // X3D: a face of 6 corners at one point, a fan of 4 triangles; X_ITE draws 16, and so does our reader.
    const auto x3d = folder / "cube.x3d";
    writeScene(scene, x3d, {});
    CHECK(readTextFile(x3d).find("<IndexedFaceSet coordIndex='0 0 0 0 0 0'><Coordinate point='0 0 0'/>") !=
          std::string::npos);
    CHECK(worldMesh(readScene(x3d)).triangles.size() == 16);
    if (x3dInteropAvailable())
        CHECK(runJson("node " + quoted(sharedDir() / "bench/x3d_count.js") + " " + quoted(x3d) + " --json")["tris"] ==
              16);
    if (renderAvailable()) checkRendersSame(folder / "plain.glb", folder / "draco.glb", "a");
    // Skinned, two corners at one point may part once the joints move them: the triangles stay as they are.
    Primitive skinned = cube;
    skinned.attributes.push_back({"JOINTS_0", 4, {}});
    skinned.attributes.push_back({"WEIGHTS_0", 4, {}});
    for (std::size_t v = 0; v < skinned.positions.size(); ++v) {
        skinned.attributes[0].values.insert(skinned.attributes[0].values.end(), {double(v == 8), 0, 0, 0});
        skinned.attributes[1].values.insert(skinned.attributes[1].values.end(), {1, 0, 0, 0});
    }
    writeScene(sceneOfOneMesh("skinned", skinned), folder / "skinned.glb", {});
    const Scene back = readScene(folder / "skinned.glb");
    CHECK(glbJson(folder / "skinned.glb")["meshes"][0]["primitives"].size() == 2);  // edgebreaker's and sequential
    CHECK(worldMesh(back).triangles.size() == 16);
    // The triangles {3, 8, 6} and {8, 3, 3}: corners at one point that keep their own joints.
    std::size_t parted = 0;
    for (const Primitive& p : back.meshes.at(0).primitives)
        for (const Triangle& t : p.triangles)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                parted += p.positions[a] == p.positions[b] &&
                          p.attributes.at(0).values[4 * a] != p.attributes.at(0).values[4 * b];
            }
    CHECK(parted == 3);
}

TEST_CASE("File names with spaces and % are percent-encoded in the URIs a .gltf writes, and decoded where read",
          "[io]") {
    // The box of the shared specular-glossiness sample, its image renamed to need encoding.
    TemporaryFolder folder;
    const fs::path source = modelPath("pbr/box_specgloss");
    fs::copy_file(source / "BoxTextured0.bin", folder / "BoxTextured0.bin");
    fs::copy_file(source / "CesiumLogoFlat.png", folder / "Cesium Logo 100%.png");
    nlohmann::json root = nlohmann::json::parse(readTextFile(source / "BoxTextured.gltf"));
    REQUIRE(root["images"].size() == 1);
    root["images"][0]["uri"] = "Cesium%20Logo%20100%25.png";
    const fs::path input = folder / "box.gltf";
    writeTextFile(input, root.dump());
    const Scene read = readScene(input);
    REQUIRE(read.textures.size() == 1);
    CHECK(read.textures[0].bytes.size() == fs::file_size(source / "CesiumLogoFlat.png"));

    const fs::path output = folder / "the box 100%.gltf";
    const CompressionReport report = compressFile(input, output);
    // The report counts the image the input names (the ratio would be off by its bytes).
    CHECK(report.inputBytes ==
          fs::file_size(input) + fs::file_size(folder / "BoxTextured0.bin") + fs::file_size(source / "CesiumLogoFlat.png"));
    const nlohmann::json written = nlohmann::json::parse(readTextFile(output));
    CHECK(written["buffers"][0]["uri"] == "the%20box%20100%25.bin");
    CHECK(fs::exists(folder / "the box 100%.bin"));
    CHECK(report.outputBytes == fs::file_size(output) + fs::file_size(folder / "the box 100%.bin"));
    CHECK(readScene(output).textures.at(0).bytes == read.textures[0].bytes);
    if (interopAvailable()) CHECK(validatorErrors(output).empty());
}

TEST_CASE(
    "What a file says about itself (copyright, asset extras, X3D meta tags, the scene's name) comes out of "
    "every tool as it went in",
    "[io]") {
    TemporaryFolder folder;
    Primitive box;
    samples::appendMesh(box, samples::boxMesh({0, 0, 0}, {1, 2, 3}));
    Scene scene = samples::singleMeshScene("box", box, {0.5, 0.5, 0.5, 1});
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "plain.gltf", plain);
    nlohmann::json root = nlohmann::json::parse(readTextFile(folder / "plain.gltf"));
    root["asset"]["copyright"] = "CC-BY 4.0 Model by someone";
    root["asset"]["extras"] = {{"author", "someone"}, {"license", "CC-BY-4.0"}, {"views", 3}};
    root["scenes"][0]["name"] = "Main";
    root["scenes"][0]["extras"] = {{"layer", 2}};
    // KHR_xmp_json_ld: packets in the file, named by the asset, the node that draws the box and its material.
    root["extensionsUsed"].push_back("KHR_xmp_json_ld");
    root["extensions"]["KHR_xmp_json_ld"]["packets"] = {{{"dc:rights", "CC-BY"}}, {{"dc:title", "box"}}};
    root["asset"]["extensions"]["KHR_xmp_json_ld"]["packet"] = 0;
    REQUIRE(root["nodes"].size() == 1);
    root["nodes"][0]["extensions"]["KHR_xmp_json_ld"]["packet"] = 1;
    root["materials"][0]["extensions"]["KHR_xmp_json_ld"]["packet"] = 1;
    // A group above it, named: the output draws the tiles under nodes of its own, which is said.
    root["nodes"].push_back({{"name", "assembly"}, {"children", {0}}});
    root["scenes"][0]["nodes"] = {1};
    const fs::path input = folder / "noted.gltf";
    writeTextFile(input, root.dump());
    fs::copy_file(folder / "plain.bin", folder / "noted.bin");

    const CompressionReport compressed = compressFile(input, folder / "compressed.glb");
    CHECK(std::any_of(compressed.warnings.begin(), compressed.warnings.end(), [](const std::string& warning) {
        return warning.find("1 node names, extras or extensions (e.g. 'assembly') not kept: they group") !=
               std::string::npos;
    }));
    CHECK(decompressFile(folder / "compressed.glb", folder / "rebuilt.gltf", input).verified);
    for (const char* name : {"compressed.glb", "rebuilt.gltf"}) {
        INFO(name);
        const fs::path file = folder / name;
        const nlohmann::json written =
            file.extension() == ".glb" ? glbJson(file) : nlohmann::json::parse(readTextFile(file));
        CHECK(written["asset"]["copyright"] == "CC-BY 4.0 Model by someone");
        CHECK(written["asset"]["extras"]["author"] == "someone");
        CHECK(written["asset"]["extras"]["views"] == 3);
        CHECK(written["scenes"][0]["name"] == "Main");
        CHECK(written["scenes"][0]["extras"]["layer"] == 2);
        CHECK(written["extensions"]["KHR_xmp_json_ld"]["packets"][1]["dc:title"] == "box");
        CHECK(written["asset"]["extensions"]["KHR_xmp_json_ld"]["packet"] == 0);
        CHECK(written["materials"][0]["extensions"]["KHR_xmp_json_ld"]["packet"] == 1);
        std::size_t nodesNaming = 0;
        for (const auto& node : written["nodes"])
            nodesNaming += node.contains("extensions") && node["extensions"].contains("KHR_xmp_json_ld") &&
                           node["extensions"]["KHR_xmp_json_ld"]["packet"] == 1;
        CHECK(nodesNaming == (file.extension() == ".glb"));  // symdecompress draws all in one node
        CHECK(std::count(written["extensionsUsed"].begin(), written["extensionsUsed"].end(), "KHR_xmp_json_ld") == 1);
        // The digest describes the file it is in: the compressed file's, none in the rebuilt one.
        CHECK(written["asset"]["extras"].contains("symcompress_digest") == (file.extension() == ".glb"));
    }
    // Through X3D, as meta tags, and back.
    const CompressionReport x3d = compressFile(input, folder / "compressed.x3d");
    CHECK(std::any_of(x3d.warnings.begin(), x3d.warnings.end(), [](const std::string& warning) {
        return warning.find("glTF extensions passed through on 3 objects") != std::string::npos;
    }));
    const std::string text = readTextFile(folder / "compressed.x3d");
    CHECK(text.find("<meta name='copyright' content='CC-BY 4.0 Model by someone'/>") != std::string::npos);
    CHECK(text.find("<meta name='license' content='CC-BY-4.0'/>") != std::string::npos);
    compressFile(folder / "compressed.x3d", folder / "again.glb");
    const nlohmann::json again = glbJson(folder / "again.glb");
    CHECK(again["asset"]["copyright"] == "CC-BY 4.0 Model by someone");
    CHECK(again["asset"]["extras"]["license"] == "CC-BY-4.0");
    CHECK(again["asset"]["extras"]["views"] == "3");  // X3D's meta tags hold text

    // An X3D file's meta tags, a name given twice included, through X3D output.
    writeTextFile(folder / "noted.x3d",
                  "<X3D version='3.3'><head><meta name='title' content='Two boxes'/><meta name='reference' "
                  "content='a'/><meta name='reference' content='b'/><meta name='generator' content='someone else'/>"
                  "</head><Scene><Shape><Box/></Shape></Scene></X3D>");
    compressFile(folder / "noted.x3d", folder / "noted_out.x3d");
    const std::string out = readTextFile(folder / "noted_out.x3d");
    for (const char* tag : {"<meta name='title' content='Two boxes'/>", "<meta name='reference' content='a'/>",
                            "<meta name='reference' content='b'/>", "<meta name='symcompress_digest' content='12 "})
        CHECK(out.find(tag) != std::string::npos);
    CHECK(out.find("someone else") == std::string::npos);
    CHECK(out.find("generator") == std::string::npos);  // the digest's tag names symcompress
    const RebuildReport rebuilt = decompressFile(folder / "noted_out.x3d", folder / "noted_rebuilt.glb");
    CHECK(rebuilt.verified);
    CHECK(rebuilt.trianglesOriginal == 12);
    // The digest's tag of files written before 2026-12-07 (its JSON) is still read.
    writeTextFile(folder / "old.x3d",
                  "<X3D version='3.3'><head><meta name='symcompress' content='{&quot;symcompress_digest&quot;:[12,"
                  "24.0,5e-05,0.0,-1.0,-1.0,-1.0,1.0,1.0,1.0]}'/></head><Scene><Shape><Box/></Shape></Scene></X3D>");
    CHECK(decompressFile(folder / "old.x3d", folder / "old_rebuilt.glb").verified);
    // OBJ holds none of it: said.
    const CompressionReport obj = compressFile(input, folder / "compressed.obj");
    CHECK(std::any_of(obj.warnings.begin(), obj.warnings.end(), [](const std::string& warning) {
        return warning.find("4 notes of what the file says about itself") != std::string::npos;
    }));
}
