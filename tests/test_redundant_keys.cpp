// Animation keys that interpolation gives back are dropped within the allowance, measured in the poses against a
// dense sampling of them; keys that carry motion, cubic splines and what no pose shows stay; the file keeps one
// accessor of times for channels that shared one, and verifies.
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
#include <random>

using namespace symcompress;
using namespace symcompress::testing;
using namespace symcompress::samples;

namespace {

using Path = AnimationChannel::Path;
constexpr int kKeys = 61;

// A 2 x 1 x 0.5 box on node 0 keyed as an exporter samples every frame: 61 keys over 2 s of a steady turn about z,
// 6 degrees a key, and of a translation along x that goes out for 30 keys and back for 30 (its turning point at
// 1 s), both at the same times.
Scene bakedBox() {
    Primitive box;
    appendMesh(box, boxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 0.5)));
    Scene scene = singleMeshScene("box", box, Eigen::Vector4d(1, 1, 1, 1));
    AnimationChannel turn, move;
    turn.node = move.node = 0;
    turn.path = Path::Rotation;
    move.path = Path::Translation;
    for (int k = 0; k < kKeys; ++k) {
        const double time = k / 30.0;
        const Eigen::Quaterniond q(Eigen::AngleAxisd(k * M_PI / 30, Eigen::Vector3d::UnitZ()));
        turn.times.push_back(time);
        turn.values.insert(turn.values.end(), {q.x(), q.y(), q.z(), q.w()});
        move.times.push_back(time);
        move.values.insert(move.values.end(), {0.1 * (k <= 30 ? k : 60 - k), 0, 0});
    }
    scene.animations.push_back({"baked", {turn, move}});
    validateScene(scene);
    return scene;
}

// The farthest a vertex of `b`'s first animation lies from where `a`'s puts it, over 1200 times across the
// animation (ten between each two keys of the box's).
double poseDistance(const Scene& a, const Scene& b) {
    double out = 0;
    for (int i = 0; i <= 1200; ++i) {
        const double time = 2.0 * i / 1200;
        const TriangleMesh pa = posedMesh(a, a.animations[0], time), pb = posedMesh(b, b.animations[0], time);
        REQUIRE(pa.positions.size() == pb.positions.size());
        for (std::size_t v = 0; v < pa.positions.size(); ++v)
            out = std::max(out, (pa.positions[v] - pb.positions[v]).norm());
    }
    return out;
}

}  // namespace

TEST_CASE("Keys that interpolation gives back are dropped, the poses within the allowance and the times shared",
          "[optimize][animation]") {
    Scene scene = bakedBox();
    const Scene original = scene;
    const double allowed = 1e-4;
    const RedundantKeys dropped = dropRedundantKeys(scene, allowed);
    const std::vector<AnimationChannel>& channels = scene.animations[0].channels;
    // The turn needs a key at least every half turn (slerp takes the shorter way), the translation its turning point.
    CHECK(channels[0].times == channels[1].times);
    CHECK(channels[0].times.size() >= 3);
    CHECK(channels[0].times.size() <= 5);
    CHECK(channels[0].times.front() == 0);
    CHECK(channels[0].times.back() == 2);  // the animation's length
    CHECK(std::count(channels[0].times.begin(), channels[0].times.end(), 1.0) == 1);
    CHECK(dropped.keysDropped == 2 * (kKeys - channels[0].times.size()));
    const double distance = poseDistance(original, scene);
    CHECK(distance <= allowed);
    CHECK(dropped.deviation <= allowed);
    CHECK(dropped.deviation == Approx(distance).margin(1e-12));
}

TEST_CASE("Keys stay where interpolation does not give them back, in cubic splines, and where no pose shows them",
          "[optimize][animation]") {
    Scene scene = bakedBox();
    SECTION("a turn that jitters: every key a turning point") {
        std::mt19937_64 random(7);
        std::uniform_real_distribution<double> jitter(-0.2, 0.2);
        AnimationChannel& turn = scene.animations[0].channels[0];
        for (int k = 0; k < kKeys; ++k) {
            const Eigen::Quaterniond q(Eigen::AngleAxisd(k * M_PI / 30 + jitter(random), Eigen::Vector3d::UnitZ()));
            std::copy(q.coeffs().data(), q.coeffs().data() + 4, turn.values.begin() + 4 * k);
        }
        CHECK(dropRedundantKeys(scene, 1e-3).keysDropped == 0);
        CHECK(scene.animations[0].channels[0].times.size() == std::size_t(kKeys));
    }
    SECTION("an allowance of nothing") {
        CHECK(dropRedundantKeys(scene, 0).keysDropped == 0);
        CHECK(scene.animations[0].channels[1].times.size() == std::size_t(kKeys));
    }
    SECTION("a cubic spline") {
        for (AnimationChannel& channel : scene.animations[0].channels) {
            channel.interpolation = AnimationChannel::Interpolation::CubicSpline;
            const std::size_t width = channel.components();
            std::vector<double> values;  // zero tangents about each value
            for (std::size_t k = 0; k < channel.times.size(); ++k) {
                values.insert(values.end(), width, 0.0);
                values.insert(values.end(), channel.values.begin() + std::ptrdiff_t(k * width),
                              channel.values.begin() + std::ptrdiff_t((k + 1) * width));
                values.insert(values.end(), width, 0.0);
            }
            channel.values = std::move(values);
        }
        validateScene(scene);
        CHECK(dropRedundantKeys(scene, 1e-3).keysDropped == 0);
    }
    SECTION("a camera's motion, which no pose measures") {
        scene.cameras.push_back(Camera{});
        scene.nodes[0].camera = 0;
        CHECK(dropRedundantKeys(scene, 1e-3).keysDropped == 0);
    }
}

TEST_CASE(
    "A channel within the allowance of its node's rest is removed, where the animation keeps its length and "
    "no other animation keys it",
    "[optimize][animation]") {
    Scene scene = bakedBox();
    // A scale an exporter baked at 1 but for a millionth (Cesium Man's), at the same times as the others.
    AnimationChannel scale = scene.animations[0].channels[1];
    scale.path = Path::Scale;
    for (std::size_t k = 0; k < scale.times.size(); ++k)
        for (int c = 0; c < 3; ++c) scale.values[3 * k + std::size_t(c)] = 1 + (k % 2 ? 1e-6 : -1e-6);
    scene.animations[0].channels.push_back(scale);
    const std::size_t keysBefore = 3 * std::size_t(kKeys);
    auto keys = [](const Scene& s) {
        std::size_t count = 0;
        for (const AnimationChannel& channel : s.animations[0].channels) count += channel.times.size();
        return count;
    };
    SECTION("removed: its node rests within the allowance") {
        const Scene original = scene;
        const RedundantKeys dropped = dropRedundantKeys(scene, 1e-4);
        REQUIRE(scene.animations[0].channels.size() == 2);
        for (const AnimationChannel& channel : scene.animations[0].channels) CHECK(channel.path != Path::Scale);
        CHECK(dropped.channelsRemoved == 1);
        CHECK(dropped.keysDropped == keysBefore - keys(scene));
        CHECK(poseDistance(original, scene) <= 1e-4);
    }
    SECTION("kept: a scale held away from the rest") {
        for (double& value : scene.animations[0].channels[2].values) value *= 1.5;
        CHECK(dropRedundantKeys(scene, 1e-4).channelsRemoved == 0);
        CHECK(scene.animations[0].channels.size() == 3);
    }
    SECTION("kept: a millionth beyond an allowance of less") {
        CHECK(dropRedundantKeys(scene, 1e-7).channelsRemoved == 0);
        CHECK(scene.animations[0].channels.size() == 3);
    }
    SECTION("kept: another animation keys the node's scale") {
        scene.animations.push_back({"other", {scene.animations[0].channels[2]}});
        CHECK(dropRedundantKeys(scene, 1e-4).channelsRemoved == 0);
        CHECK(scene.animations[0].channels.size() == 3);
    }
    SECTION("kept: its last key is the animation's last") {
        AnimationChannel& longer = scene.animations[0].channels[2];
        longer.times.push_back(3);
        longer.values.insert(longer.values.end(), {1, 1, 1});
        CHECK(dropRedundantKeys(scene, 1e-4).channelsRemoved == 0);
        REQUIRE(scene.animations[0].channels.size() == 3);
        CHECK(scene.animations[0].channels[2].times.back() == 3);
    }
}

TEST_CASE("Keys too many to draw pose by pose are dropped, measured at the corners of the box they move",
          "[optimize][animation]") {
    // A steady turn keyed 50000 times: its 100000 poses (each key and halfway) times the box's 8 corners, ten times
    // over, are more than the vertices the probe draws (4e6) and than it measured at corners before (the same).
    Scene scene = bakedBox();
    AnimationChannel turn = scene.animations[0].channels[0];
    turn.times.clear();
    turn.values.clear();
    constexpr int kManyKeys = 50000;
    for (int k = 0; k < kManyKeys; ++k) {
        const Eigen::Quaterniond q(Eigen::AngleAxisd(k * M_PI / kManyKeys, Eigen::Vector3d::UnitZ()));
        turn.times.push_back(k / 30.0);
        turn.values.insert(turn.values.end(), {q.x(), q.y(), q.z(), q.w()});
    }
    scene.animations[0].channels = {turn};
    validateScene(scene);
    const RedundantKeys dropped = dropRedundantKeys(scene, 1e-4);
    const std::size_t kept = scene.animations[0].channels[0].times.size();
    CHECK(kept <= std::size_t(kManyKeys) / 60);
    CHECK(dropped.keysDropped == std::size_t(kManyKeys) - kept);
    CHECK(dropped.deviation <= 1e-4);
}

TEST_CASE("symcompress drops the keys a baked animation repeats, and --keep-animation-keys keeps them",
          "[optimize][animation]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    const auto input = folder / "baked.glb";
    writeScene(bakedBox(), input, plain);
    auto samplerKeys = [](const std::filesystem::path& file) {
        const nlohmann::json gltf = glbJson(file);
        std::vector<int> counts;
        for (const auto& sampler : gltf["animations"][0]["samplers"])
            counts.push_back(gltf["accessors"][sampler["input"].get<int>()]["count"].get<int>());
        CHECK(gltf["animations"][0]["samplers"][0]["input"] == gltf["animations"][0]["samplers"][1]["input"]);
        return counts;
    };

    const CompressionReport report = compressFile(input, folder / "out.glb");
    CHECK(report.optimizations.animationKeysDropped >= 2 * (kKeys - 5));
    CHECK(samplerKeys(folder / "out.glb")[0] <= 5);
    const RebuildReport verified = decompressFile(folder / "out.glb", folder / "flat.glb", input);
    CHECK(verified.verified);
    CHECK(verified.posesCompared > 0);
    if (interopAvailable()) CHECK(validatorErrors(folder / "out.glb").empty());

    CompressOptions keep;
    keep.optimize.dropKeys = false;
    CHECK(compressFile(input, folder / "kept.glb", keep).optimizations.animationKeysDropped == 0);
    CHECK(samplerKeys(folder / "kept.glb")[0] == kKeys);
    CHECK(std::filesystem::file_size(folder / "out.glb") < std::filesystem::file_size(folder / "kept.glb"));
}
