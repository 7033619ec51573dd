// posedMesh and the decoder's check of animations: poses worked out by hand, and an animation changed in a file.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"

#include "test_support.hpp"

#include <meshoptimizer.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>

using namespace symcompress;
using symcompress::testing::glbJson;
using symcompress::testing::TemporaryFolder;

namespace {

Eigen::Matrix4d translation(double x, double y, double z) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, z);
    return m;
}

// A strip from x = 0 to 2 skinned by two joints (node 0 at the origin, node 1 its child at x = 1), each vertex
// weighted x / 2 to joint 1; node 1 turns about z from 0 to `degrees` over a second.
Scene bendingStrip(double degrees) {
    Scene scene;
    Primitive strip;
    VertexAttribute joints{"JOINTS_0", 4, {}}, weights{"WEIGHTS_0", 4, {}};
    for (double x : {0.0, 1.0, 2.0})
        for (double y : {-0.1, 0.1}) {
            strip.positions.push_back({x, y, 0});
            joints.values.insert(joints.values.end(), {0, 1, 0, 0});
            weights.values.insert(weights.values.end(), {1 - x / 2, x / 2, 0, 0});
        }
    strip.triangles = {{0, 2, 1}, {1, 2, 3}, {2, 4, 3}, {3, 4, 5}};
    strip.attributes = {joints, weights};
    scene.meshes.push_back({"strip", {strip}});
    scene.nodes.resize(3);
    scene.nodes[0].name = "root joint";
    scene.nodes[0].children = {1};
    scene.nodes[1].name = "elbow";
    scene.nodes[1].transform = translation(1, 0, 0);
    scene.nodes[2].name = "skinned";
    scene.nodes[2].mesh = 0;
    scene.nodes[2].skin = 0;
    scene.roots = {0, 2};
    scene.skins.push_back({"arm", {0, 1}, {Eigen::Matrix4d::Identity(), translation(-1, 0, 0)}, 0});
    AnimationChannel bend;
    bend.node = 1;
    bend.path = AnimationChannel::Path::Rotation;
    bend.times = {0, 1};
    const Eigen::Quaterniond turned(Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()));
    bend.values = {0, 0, 0, 1, turned.x(), turned.y(), turned.z(), turned.w()};
    scene.animations.push_back({"bend", {bend}});
    validateScene(scene);
    return scene;
}

// A triangle on a node moved by one channel of the given interpolation, keys and values.
Scene movedTriangle(AnimationChannel channel) {
    Scene scene;
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.triangles = {{0, 1, 2}};
    scene.meshes.push_back({"", {triangle}});
    scene.nodes.resize(2);
    scene.nodes[0].mesh = 0;
    scene.nodes[1].mesh = 0;  // not animated: not drawn by posedMesh
    scene.roots = {0, 1};
    channel.node = 0;
    scene.animations.push_back({"move", {channel}});
    validateScene(scene);
    return scene;
}

// The scene drawn at `time` of its first animation.
TriangleMesh posedAtFirst(const Scene& scene, double time) { return posedMesh(scene, scene.animations[0], time); }

}  // namespace

TEST_CASE("posedMesh: a skinned strip bent by its elbow, each vertex where its weights put it", "[verify]") {
    const Scene scene = bendingStrip(90);
    // At 1 s the elbow has turned 90 degrees; at 0.5 s, 45 (slerp).
    for (const double time : {1.0, 0.5, 0.0, 3.0}) {
        INFO("time " << time);
        const double angle = std::min(std::max(time, 0.0), 1.0) * M_PI / 2;
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const TriangleMesh posed = posedAtFirst(scene, time);
        REQUIRE(posed.positions.size() == 6);
        REQUIRE(posed.triangles.size() == 4);
        for (std::size_t v = 0; v < 6; ++v) {
            const Eigen::Vector3d rest = scene.meshes[0].primitives[0].positions[v];
            const double w = rest.x() / 2;
            const Eigen::Vector3d byElbow = Eigen::Vector3d(1, 0, 0) + turn * (rest - Eigen::Vector3d(1, 0, 0));
            CHECK((posed.positions[v] - ((1 - w) * rest + w * byElbow)).norm() < 1e-12);
        }
    }
    // The tip at 90 degrees, worked out by hand: (1, 0, 0) + (-0.1, 1, 0).
    CHECK((posedAtFirst(scene, 1).positions[5] - Eigen::Vector3d(0.9, 1, 0)).norm() < 1e-12);
    // Weights that sum to a half are scaled to 1, as three.js does: the same poses.
    Scene halved = scene;
    for (double& w : halved.meshes[0].primitives[0].attributes[1].values) w /= 2;
    CHECK((posedAtFirst(halved, 0.5).positions[3] - posedAtFirst(scene, 0.5).positions[3]).norm() < 1e-12);
}

TEST_CASE("posedMesh interpolates as the sampler says: step, linear, cubic spline, morph weights", "[verify]") {
    AnimationChannel step;
    step.path = AnimationChannel::Path::Translation;
    step.interpolation = AnimationChannel::Interpolation::Step;
    step.times = {0, 1};
    step.values = {0, 0, 0, 5, 0, 0};
    const Scene stepped = movedTriangle(step);
    CHECK(posedAtFirst(stepped, 0.5).positions[1] == Eigen::Vector3d(1, 0, 0));
    CHECK(posedAtFirst(stepped, 2).positions[1] == Eigen::Vector3d(6, 0, 0));  // after the last key: the last
    CHECK(posedAtFirst(stepped, 0.5).positions.size() == 3);                   // the node not animated is left out

    // Hermite: halfway between keys 2 s apart, the values' mean plus (u^3 - 2u^2 + u) * 2 s * out-tangent.
    AnimationChannel spline = step;
    spline.interpolation = AnimationChannel::Interpolation::CubicSpline;
    spline.times = {0, 2};
    spline.values = {0, 0, 0, 0, 0, 0, 1, 0, 0, /**/ 0, 0, 0, 2, 0, 0, 0, 0, 0};
    CHECK((posedAtFirst(movedTriangle(spline), 1).positions[0] - Eigen::Vector3d(1.25, 0, 0)).norm() < 1e-12);

    AnimationChannel linear = step;
    linear.interpolation = AnimationChannel::Interpolation::Linear;
    CHECK((posedAtFirst(movedTriangle(linear), 0.25).positions[2] - Eigen::Vector3d(1.25, 1, 0)).norm() < 1e-12);

    // A morph target lifting every vertex by 1, weighted 0 to 1 over a second.
    Scene morphed = movedTriangle(linear);
    morphed.animations[0].channels[0].path = AnimationChannel::Path::Weights;
    morphed.animations[0].channels[0].weights = 1;
    morphed.animations[0].channels[0].values = {0, 1};
    morphed.meshes[0].primitives[0].targets = {{{"POSITION", 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}}}};
    validateScene(morphed);
    CHECK((posedAtFirst(morphed, 0.25).positions[1] - Eigen::Vector3d(1, 0, 0.25)).norm() < 1e-12);
}

TEST_CASE("symdecompress draws every animation: a changed key is not verified, the same one is", "[verify]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(bendingStrip(90), folder / "original.glb", plain);
    writeScene(bendingStrip(80), folder / "changed.glb", plain);
    const RebuildReport same = decompressFile(folder / "original.glb", folder / "flat.glb", folder / "original.glb");
    CHECK(same.verified);
    CHECK(same.posesCompared == 2);
    CHECK(same.posedDeviation == 0);
    // The rest pose is the same: only the poses tell the files apart (the tip moves 0.17, a twelfth of the
    // bent strip's diagonal).
    const RebuildReport changed = decompressFile(folder / "changed.glb", folder / "flat.glb", folder / "original.glb");
    CHECK(changed.maxDeviation == 0);
    CHECK(changed.posedDeviation > 0.05);
    CHECK_FALSE(changed.verified);
    // An animation left out is no match either.
    Scene still = bendingStrip(90);
    still.animations.clear();
    writeScene(still, folder / "still.glb", plain);
    const RebuildReport missing = decompressFile(folder / "still.glb", folder / "flat.glb", folder / "original.glb");
    CHECK(std::isinf(missing.posedDeviation));
    CHECK_FALSE(missing.verified);
    // X3D holds no skins: the strip comes out at rest, and its poses are not compared, which is said.
    writeScene(bendingStrip(90), folder / "strip.x3d", plain);
    const RebuildReport x3d = decompressFile(folder / "strip.x3d", folder / "flat.glb", folder / "original.glb");
    CHECK(x3d.verified);
    CHECK(x3d.posesCompared == 0);
    CHECK(std::any_of(x3d.warnings.begin(), x3d.warnings.end(),
                      [](const std::string& w) { return w.find("animations are not compared") != std::string::npos; }));
}

TEST_CASE("Draco rounds skin weights only as far as skinWeightError allows in every pose", "[io][verify]") {
    const Scene scene = bendingStrip(90);
    TemporaryFolder folder;
    // Each vertex's weights in the file, found by its position (the strip's six are far apart).
    auto weightsRead = [&](double error) {
        WriteOptions options;
        options.skinWeightError = error;
        writeScene(scene, folder / "strip.glb", options);
        const Scene read = readScene(folder / "strip.glb");
        const Primitive& original = scene.meshes[0].primitives[0];
        const Primitive& back = read.meshes.at(0).primitives.at(0);
        REQUIRE(back.positions.size() == 6);
        const VertexAttribute* weights = nullptr;
        for (const VertexAttribute& attribute : back.attributes)
            if (attribute.name == "WEIGHTS_0") weights = &attribute;
        REQUIRE(weights);
        double largest = 0;
        for (std::size_t v = 0; v < 6; ++v) {
            std::size_t nearest = 0;
            for (std::size_t o = 1; o < 6; ++o)
                if ((original.positions[o] - back.positions[v]).norm() <
                    (original.positions[nearest] - back.positions[v]).norm())
                    nearest = o;
            for (int c = 0; c < 4; ++c)
                largest =
                    std::max(largest, std::abs(weights->vertex(v)[c] - original.attributes[1].vertex(nearest)[c]));
        }
        return largest;
    };
    // Bent 90 degrees, the tip is drawn by the elbow alone, 1.42 from where the root joint would put it (the most
    // of any vertex and pose): 1e-4 asks 16 bits, 4 weights * half a step * 1.42 * 2 (the motion between keys) =
    // 8.7e-5 (15 bits would be 1.7e-4).
    const double rounded = weightsRead(1e-4);
    CHECK(rounded > 0);
    CHECK(rounded <= 0.5 / ((1 << 16) - 1) + 1e-9);
    CHECK(rounded > 0.5 / ((1 << 18) - 1));
    // An error that no 24 bits keep: the weights as read.
    CHECK(weightsRead(1e-12) == 0);
    CHECK(weightsRead(0) == 0);
}

namespace {

// The strip waving: its elbow swings +-60 degrees and its root joint sways along y, keyed 10 times a second.
Scene wavingStrip() {
    Scene scene = bendingStrip(0);
    AnimationChannel& swing = scene.animations[0].channels[0];
    AnimationChannel sway;
    sway.node = 0;
    sway.path = AnimationChannel::Path::Translation;
    swing.times.clear();
    swing.values.clear();
    for (int k = 0; k < 40; ++k) {
        const double time = k / 10.0, angle = M_PI / 3 * std::sin(time * M_PI / 2);
        const Eigen::Quaterniond turned(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
        swing.times.push_back(time);
        swing.values.insert(swing.values.end(), {turned.x(), turned.y(), turned.z(), turned.w()});
        sway.times.push_back(time);
        sway.values.insert(sway.values.end(), {0, 0.3 * std::cos(time), 0});
    }
    scene.animations[0].channels.push_back(sway);
    validateScene(scene);
    return scene;
}

// Whether the file's key values are the scene's as float32 holds them, channel by channel.
bool keysAsRead(const Scene& scene, const std::filesystem::path& file) {
    const Scene read = readScene(file);
    if (read.animations.size() != 1 || read.animations[0].channels.size() != scene.animations[0].channels.size())
        return false;
    for (std::size_t c = 0; c < scene.animations[0].channels.size(); ++c) {
        const std::vector<double>& values = scene.animations[0].channels[c].values;
        const std::vector<double>& back = read.animations[0].channels[c].values;
        if (back.size() != values.size()) return false;
        for (std::size_t i = 0; i < values.size(); ++i)
            if (back[i] != double(float(values[i]))) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("Animation keys rounded by meshopt's filters only as far as animationKeyError allows in every pose",
          "[io][verify]") {
    const Scene scene = wavingStrip();
    TemporaryFolder folder;
    // The file's filters and bits, and how far its poses lie from the original's at each key and halfway.
    struct Written {
        std::vector<std::string> filters;
        double deviation = 0;
        std::uintmax_t bytes = 0;
    };
    auto written = [&](double error) {
        WriteOptions options;
        options.animationKeyError = error;
        options.maxPositionError = 1e-9;  // Draco's rounding of the positions out of the way
        const auto file = folder / "waving.glb";
        writeScene(scene, file, options);
        Written out;
        out.bytes = std::filesystem::file_size(file);
        const nlohmann::json json = glbJson(file);
        for (const auto& view : json["bufferViews"])
            if (view.contains("extensions") && view["extensions"]["EXT_meshopt_compression"].contains("filter"))
                out.filters.push_back(view["extensions"]["EXT_meshopt_compression"]["filter"]);
        const Scene read = readScene(file);
        REQUIRE(read.animations.size() == 1);
        for (int k = 0; k < 79; ++k) {
            const double time = k / 20.0;
            const TriangleMesh back = posedMesh(read, read.animations[0], time),
                               original = posedMesh(scene, scene.animations[0], time);
            // Draco orders the vertices its way; each is the nearest (the strip's are at least 0.2 apart).
            REQUIRE(back.positions.size() == original.positions.size());
            for (const Eigen::Vector3d& p : back.positions) {
                double nearest = std::numeric_limits<double>::infinity();
                for (const Eigen::Vector3d& q : original.positions) nearest = std::min(nearest, (p - q).norm());
                out.deviation = std::max(out.deviation, nearest);
            }
        }
        return out;
    };
    // As read: float32 keys, the poses as the original's to float32's rounding.
    const Written asRead = written(0);
    CHECK(asRead.filters.empty());
    CHECK(asRead.deviation < 1e-6);
    // Rounded: filtered, within the allowance (the tip of the strip 2 from the root), and fewer bytes the more
    // the allowance.
    const Written fine = written(1e-5), coarse = written(1e-3);
    CHECK(fine.filters.size() == 2);  // rotations, and the translations
    CHECK(fine.deviation <= 1e-5);
    CHECK(fine.deviation > 1e-7);
    CHECK(coarse.deviation <= 1e-3);
    CHECK(coarse.deviation > fine.deviation);
    CHECK(coarse.bytes < fine.bytes);
    CHECK(fine.bytes < asRead.bytes);
    // Neither Draco nor meshopt (--no-gpu-instancing): the keys as read.
    WriteOptions plain;
    plain.animationKeyError = 1e-3;
    plain.gpuInstancing = false;
    writeScene(scene, folder / "plain.glb", plain);
    CHECK(keysAsRead(scene, folder / "plain.glb"));
}

TEST_CASE("Rotations a file rounded by the quaternion filter come back as read, at its bits", "[io][verify]") {
    // The strip's elbow keyed where y and w are nearly equal in size (as one of gltfpack's fox's keys), and rounded
    // by 12 bits of the filter as gltfpack writes it: decoded, the component it rebuilt may come out the larger, so
    // that meshopt's encoder, which leaves out the largest, rounds the other one and moves the key.
    Scene scene = wavingStrip();
    AnimationChannel& swing = scene.animations[0].channels[0];
    std::vector<float> floats;
    for (std::size_t k = 0; k < swing.times.size(); ++k) {
        const Eigen::Quaterniond q =
            Eigen::Quaterniond(-0.687, -0.1675, 0.687 + 3e-4 * std::sin(3.0 * double(k)), 0.1675).normalized();
        floats.insert(floats.end(), {float(q.x()), float(q.y()), float(q.z()), float(q.w())});
    }
    const std::size_t keys = swing.times.size();
    std::vector<std::int16_t> shorts(floats.size());
    meshopt_encodeFilterQuat(shorts.data(), keys, 8, 12, floats.data());
    meshopt_decodeFilterQuat(shorts.data(), keys, 8);
    for (std::size_t i = 0; i < shorts.size(); ++i) swing.values[i] = std::max(shorts[i] / 32767.0, -1.0);
    auto keyAsRead = [&](const std::vector<double>& values, std::size_t k) {
        double same = 0, opposite = 0;
        for (std::size_t c = 4 * k; c < 4 * k + 4; ++c) {
            same = std::max(same, std::abs(values[c] - swing.values[c]));
            opposite = std::max(opposite, std::abs(values[c] + swing.values[c]));
        }
        return std::min(same, opposite) <= 0.5 / 32767;
    };
    // Meshopt's own encoder moves some key.
    const std::vector<float> read(swing.values.begin(), swing.values.end());
    std::vector<std::int16_t> again(read.size());
    meshopt_encodeFilterQuat(again.data(), keys, 8, 12, read.data());
    meshopt_decodeFilterQuat(again.data(), keys, 8);
    const std::vector<double> reencoded(again.begin(), again.end());
    std::vector<double> decoded;
    for (double c : reencoded) decoded.push_back(std::max(c / 32767.0, -1.0));
    bool moved = false;
    for (std::size_t k = 0; k < keys; ++k) moved = moved || !keyAsRead(decoded, k);
    REQUIRE(moved);
    // Written within 1e-6: the file's own 12 bits, each key as read (16 bits give the keys back too, but code
    // larger; without the right component left out, 12 bits moved some key beyond the allowance).
    TemporaryFolder folder;
    WriteOptions options;
    options.animationKeyError = 1e-6;
    options.maxPositionError = 1e-9;
    writeScene(scene, folder / "grid.glb", options);
    // The rotations' view holds the filter's keys at 12 bits: the scale in each key's fourth value.
    const nlohmann::json json = glbJson(folder / "grid.glb");
    const std::string glb = testing::readTextFile(folder / "grid.glb");
    std::uint32_t jsonLength = 0;
    std::memcpy(&jsonLength, glb.data() + 12, 4);
    const char* binary = glb.data() + 20 + jsonLength + 8;
    std::set<int> scales;
    for (const auto& view : json["bufferViews"]) {
        if (!view.contains("extensions") ||
            view["extensions"]["EXT_meshopt_compression"].value("filter", "") != "QUATERNION")
            continue;
        const auto& meshopt = view["extensions"]["EXT_meshopt_compression"];
        std::vector<std::int16_t> filtered(4 * meshopt["count"].get<std::size_t>());
        REQUIRE(
            meshopt_decodeVertexBuffer(filtered.data(), meshopt["count"], 8,
                                       reinterpret_cast<const unsigned char*>(binary) + meshopt.value("byteOffset", 0),
                                       meshopt["byteLength"]) == 0);
        for (std::size_t k = 0; k < filtered.size(); k += 4) scales.insert(filtered[k + 3] | 3);
    }
    CHECK(scales == std::set<int>{2047});
    const Scene back = readScene(folder / "grid.glb");
    REQUIRE(back.animations.size() == 1);
    const std::vector<double>& written = back.animations[0].channels[0].values;
    REQUIRE(written.size() == swing.values.size());
    for (std::size_t k = 0; k < keys; ++k) CHECK(keyAsRead(written, k));
}

TEST_CASE(
    "Animation keys given an allowance beside the budget (--animation-error), which the rest pose keeps "
    "whole, and the poses verified against the sum",
    "[io][verify]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(wavingStrip(), folder / "waving.glb", plain);
    const CompressionReport shared = compressFile(folder / "waving.glb", folder / "shared.glb");
    CompressOptions beside;
    beside.animationError = 1e-2;
    const CompressionReport own = compressFile(folder / "waving.glb", folder / "own.glb", beside);
    CHECK(shared.animationKeyShare > 0);
    CHECK(shared.animationError == 0);
    CHECK(own.animationKeyShare == 0);
    CHECK(own.animationError == 1e-2);
    CHECK(std::filesystem::file_size(folder / "own.glb") < std::filesystem::file_size(folder / "shared.glb"));
    // The digest holds the poses' allowance: the budget and the keys'.
    SurfaceDigest digest;
    REQUIRE(SurfaceDigest::fromJson(readScene(folder / "own.glb").extrasJson, digest));
    CHECK(digest.maxError == Approx(beside.maxError));
    CHECK(digest.poseError == Approx(beside.maxError + 1e-2));
    // The keys use their allowance, beyond the budget, and the file verifies; the rest pose within the budget.
    const RebuildReport verified = decompressFile(folder / "own.glb", folder / "flat.glb", folder / "waving.glb");
    CHECK(verified.verified);
    CHECK(verified.maxDeviation <= verified.allowedDeviation);
    CHECK(verified.posedDeviation > verified.allowedDeviation);
    CHECK(verified.posedDeviation <= verified.allowedPosedDeviation);
    CHECK(verified.allowedPosedDeviation == Approx((beside.maxError + 1e-2) * 1.01));
    // Without an allowance of its own the poses keep the budget.
    const RebuildReport kept = decompressFile(folder / "shared.glb", folder / "flat.glb", folder / "waving.glb");
    CHECK(kept.verified);
    CHECK(kept.allowedPosedDeviation == kept.allowedDeviation);
    // X3D writes keys as read: the allowance changes nothing, and the user is told.
    const CompressionReport x3d = compressFile(folder / "waving.glb", folder / "own.x3d", beside);
    CHECK(x3d.animationError == 0);
    CHECK(std::any_of(x3d.warnings.begin(), x3d.warnings.end(), [](const std::string& warning) {
        return warning.find("--animation-error changes nothing") != std::string::npos;
    }));
}

TEST_CASE("Animation keys that move a camera are kept as read", "[io]") {
    Scene scene = wavingStrip();
    scene.cameras.push_back({});
    scene.nodes.push_back({});
    scene.nodes.back().camera = 0;
    scene.nodes[1].children.push_back(int(scene.nodes.size()) - 1);  // the elbow carries a camera
    validateScene(scene);
    TemporaryFolder folder;
    WriteOptions options;
    options.animationKeyError = 1e-3;
    writeScene(scene, folder / "camera.glb", options);
    // The elbow's rotations as read; the root joint's translations (it carries the camera too) as well.
    CHECK(keysAsRead(scene, folder / "camera.glb"));
}

TEST_CASE("Morph weights rounded with a key's weights in one element of the filter, and read back as scalars",
          "[io][verify]") {
    // A triangle with two targets (one lifting it by 1, one sliding it by 1), their weights keyed 400 times.
    AnimationChannel weights;
    weights.path = AnimationChannel::Path::Weights;
    weights.weights = 2;
    for (int k = 0; k < 400; ++k) {
        weights.times.push_back(k / 100.0);
        weights.values.insert(weights.values.end(), {0.5 + 0.5 * std::sin(k / 30.0), 0.0001 * k});
    }
    AnimationChannel still;
    still.times = {0};
    still.values = {0, 0, 0};
    Scene scene = movedTriangle(still);
    weights.node = 0;
    scene.animations[0].channels = {weights};
    scene.meshes[0].primitives[0].targets = {{{"POSITION", 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}}},
                                             {{"POSITION", 3, {1, 0, 0, 1, 0, 0, 1, 0, 0}}}};
    scene.meshes[0].weights = {0, 0};
    validateScene(scene);
    TemporaryFolder folder;
    WriteOptions options;
    options.animationKeyError = 1e-4;
    writeScene(scene, folder / "morphed.glb", options);
    // One filtered view, an element to a key (two weights, 8 bytes).
    const nlohmann::json json = glbJson(folder / "morphed.glb");
    std::vector<int> strides;
    for (const auto& view : json["bufferViews"])
        if (view.contains("extensions") && view["extensions"]["EXT_meshopt_compression"].contains("filter"))
            strides.push_back(view["extensions"]["EXT_meshopt_compression"]["byteStride"]);
    CHECK(strides == std::vector<int>{8});
    // Its one primitive is morphed, which Draco never codes: no Draco extension is named.
    CHECK(json["extensionsUsed"] == nlohmann::json{"EXT_meshopt_compression"});
    // Read back as 800 scalars, each within the allowance (a weight moves a vertex by itself times 1).
    const Scene read = readScene(folder / "morphed.glb");
    REQUIRE(read.animations.size() == 1);
    const std::vector<double>& back = read.animations[0].channels.at(0).values;
    REQUIRE(back.size() == weights.values.size());
    double farthest = 0;
    for (std::size_t i = 0; i < back.size(); ++i) farthest = std::max(farthest, std::abs(back[i] - weights.values[i]));
    CHECK(farthest > 0);
    CHECK(farthest <= 1e-4);
}

TEST_CASE(
    "A morphed primitive's vertices rounded by meshopt's exponential filter within the position bound in every "
    "pose",
    "[io][verify]") {
    // A 9 by 9 sheet of vertices off any grid, with normals, and two targets that lift and slide part of it (their
    // displacements mostly zero beside a nonzero component: the filter's exponent must not be taken from the zeros).
    Primitive sheet;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j) {
            sheet.positions.push_back({i / 8.0 + jitter(random), j / 8.0 + jitter(random), jitter(random)});
            const double y = jitter(random), x = jitter(random);  // in this order (samples::drawnVector)
            sheet.normals.push_back(Eigen::Vector3d(x, y, 1).normalized());
        }
    for (std::uint32_t i = 0; i < 8; ++i)
        for (std::uint32_t j = 0; j < 8; ++j) {
            const std::uint32_t v = i * 9 + j;
            sheet.triangles.push_back({v, v + 9, v + 1});
            sheet.triangles.push_back({v + 1, v + 9, v + 10});
        }
    VertexAttribute lift{"POSITION", 3, {}}, slide{"POSITION", 3, {}}, tilt{"NORMAL", 3, {}};
    for (std::size_t v = 0; v < sheet.positions.size(); ++v) {
        const double x = sheet.positions[v].x();
        lift.values.insert(lift.values.end(), {0, 0, x > 0.5 ? 0.3 * x + jitter(random) : 0.0});
        slide.values.insert(slide.values.end(), {0.01 * x, 0, 0});
        tilt.values.insert(tilt.values.end(), {x > 0.5 ? -0.2 : 0.0, 0, 0});
    }
    sheet.targets = {{lift, tilt}, {slide}};
    AnimationChannel weights;
    weights.path = AnimationChannel::Path::Weights;
    weights.weights = 2;
    for (int k = 0; k < 20; ++k) {
        weights.times.push_back(k / 10.0);
        weights.values.insert(weights.values.end(), {0.5 + 0.5 * std::sin(k / 3.0), k / 19.0});
    }
    Scene scene = sceneOfOneMesh("sheet", sheet);
    scene.meshes[0].weights = {0, 0};
    weights.node = 0;
    scene.animations.push_back({"wave", {weights}});
    validateScene(scene);

    TemporaryFolder folder;
    WriteOptions options;
    options.maxPositionError = 1e-4;
    writeScene(scene, folder / "rounded.glb", options);
    const nlohmann::json json = glbJson(folder / "rounded.glb");
    bool filteredVertices = false;
    for (const auto& view : json["bufferViews"])
        filteredVertices |= view.value("target", 0) == 34962 &&
                            view["extensions"]["EXT_meshopt_compression"].value("filter", "") == "EXPONENTIAL";
    CHECK(filteredVertices);
    // The vertices keep their order (no Draco): each one, at rest and at every key, within the bound.
    const Scene read = readScene(folder / "rounded.glb");
    REQUIRE(read.animations.size() == 1);
    double farthest = 0;
    for (const double time : weights.times) {
        const TriangleMesh asRead = posedMesh(scene, scene.animations[0], time);
        const TriangleMesh back = posedMesh(read, read.animations[0], time);
        REQUIRE(back.positions.size() == asRead.positions.size());
        for (std::size_t v = 0; v < back.positions.size(); ++v)
            farthest = std::max(farthest, (back.positions[v] - asRead.positions[v]).norm());
    }
    CHECK(farthest > 1e-6);  // rounded, not as read
    CHECK(farthest <= 1e-4);
    // Without a bound, or without Draco (the plain writer stores every value as read), nothing is rounded.
    for (const bool draco : {true, false}) {
        WriteOptions exact;
        exact.draco = draco;
        writeScene(scene, folder / "exact.glb", exact);
        const Scene exactRead = readScene(folder / "exact.glb");
        const Primitive& out = exactRead.meshes.at(0).primitives.at(0);
        REQUIRE(out.positions.size() == sheet.positions.size());
        for (std::size_t v = 0; v < out.positions.size(); ++v)
            CHECK(out.positions[v] == sheet.positions[v].cast<float>().cast<double>());
        REQUIRE(out.targets.size() == 2);
        const std::vector<float> lifted(lift.values.begin(), lift.values.end());
        const auto displaced = std::find_if(out.targets[0].begin(), out.targets[0].end(),
                                            [](const VertexAttribute& a) { return a.name == "POSITION"; });
        REQUIRE(displaced != out.targets[0].end());
        CHECK(displaced->values == std::vector<double>(lifted.begin(), lifted.end()));
    }
}
