// posedMesh and the decoder's check of animations: poses worked out by hand, and an animation changed in a file.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace symcompress;
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

}  // namespace

TEST_CASE("posedMesh: a skinned strip bent by its elbow, each vertex where its weights put it", "[verify]") {
    const Scene scene = bendingStrip(90);
    // At 1 s the elbow has turned 90 degrees; at 0.5 s, 45 (slerp).
    for (const double time : {1.0, 0.5, 0.0, 3.0}) {
        INFO("time " << time);
        const double angle = std::min(std::max(time, 0.0), 1.0) * M_PI / 2;
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const TriangleMesh posed = posedMesh(scene, 0, time);
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
    CHECK((posedMesh(scene, 0, 1).positions[5] - Eigen::Vector3d(0.9, 1, 0)).norm() < 1e-12);
    // Weights that sum to a half are scaled to 1, as three.js does: the same poses.
    Scene halved = scene;
    for (double& w : halved.meshes[0].primitives[0].attributes[1].values) w /= 2;
    CHECK((posedMesh(halved, 0, 0.5).positions[3] - posedMesh(scene, 0, 0.5).positions[3]).norm() < 1e-12);
}

TEST_CASE("posedMesh interpolates as the sampler says: step, linear, cubic spline, morph weights", "[verify]") {
    AnimationChannel step;
    step.path = AnimationChannel::Path::Translation;
    step.interpolation = AnimationChannel::Interpolation::Step;
    step.times = {0, 1};
    step.values = {0, 0, 0, 5, 0, 0};
    const Scene stepped = movedTriangle(step);
    CHECK(posedMesh(stepped, 0, 0.5).positions[1] == Eigen::Vector3d(1, 0, 0));
    CHECK(posedMesh(stepped, 0, 2).positions[1] == Eigen::Vector3d(6, 0, 0));  // after the last key: the last
    CHECK(posedMesh(stepped, 0, 0.5).positions.size() == 3);                   // the node not animated is left out

    // Hermite: halfway between keys 2 s apart, the values' mean plus (u^3 - 2u^2 + u) * 2 s * out-tangent.
    AnimationChannel spline = step;
    spline.interpolation = AnimationChannel::Interpolation::CubicSpline;
    spline.times = {0, 2};
    spline.values = {0, 0, 0, 0, 0, 0, 1, 0, 0, /**/ 0, 0, 0, 2, 0, 0, 0, 0, 0};
    CHECK((posedMesh(movedTriangle(spline), 0, 1).positions[0] - Eigen::Vector3d(1.25, 0, 0)).norm() < 1e-12);

    AnimationChannel linear = step;
    linear.interpolation = AnimationChannel::Interpolation::Linear;
    CHECK((posedMesh(movedTriangle(linear), 0, 0.25).positions[2] - Eigen::Vector3d(1.25, 1, 0)).norm() < 1e-12);

    // A morph target lifting every vertex by 1, weighted 0 to 1 over a second.
    Scene morphed = movedTriangle(linear);
    morphed.animations[0].channels[0].path = AnimationChannel::Path::Weights;
    morphed.animations[0].channels[0].weights = 1;
    morphed.animations[0].channels[0].values = {0, 1};
    morphed.meshes[0].primitives[0].targets = {{{"POSITION", 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}}}};
    validateScene(morphed);
    CHECK((posedMesh(morphed, 0, 0.25).positions[1] - Eigen::Vector3d(1, 0, 0.25)).norm() < 1e-12);
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
