#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>

using namespace symcompress;

namespace {

// One triangle in the z = 0 plane, normal +z, counter-clockwise seen from +z.
Primitive unitTriangle() {
    Primitive primitive;
    primitive.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    primitive.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    primitive.triangles = {{0, 1, 2}};
    return primitive;
}

Scene sceneWithOneMesh(const Primitive& primitive) {
    Scene scene;
    scene.meshes.push_back({"m", {primitive}});
    return scene;
}

Eigen::Vector3d faceNormal(const Primitive& primitive, const Triangle& t) {
    return (primitive.positions[t[1]] - primitive.positions[t[0]])
        .cross(primitive.positions[t[2]] - primitive.positions[t[0]])
        .normalized();
}

}  // namespace

TEST_CASE("flattenScene composes parent and child transforms", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    Node parent, child;
    parent.transform.topRightCorner<3, 1>() = Eigen::Vector3d(10, 0, 0);
    child.transform.topLeftCorner<3, 3>() = Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    child.mesh = 0;
    parent.children = {1};
    scene.nodes = {parent, child};
    scene.roots = {0};
    validateScene(scene);
    const auto world = flattenScene(scene);
    REQUIRE(world.size() == 1);
    // (1,0,0) turned a quarter about z is (0,1,0), then moved by 10 along x.
    CHECK((world[0].primitive.positions[1] - Eigen::Vector3d(10, 1, 0)).norm() < 1e-12);
    CHECK(world[0].node == 1);
}

TEST_CASE("flattenScene flips the winding under a mirror and keeps normals outward", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    Node mirror;
    mirror.transform.diagonal() << 1, 1, -1, 1;  // z -> -z
    mirror.mesh = 0;
    scene.nodes = {mirror};
    scene.roots = {0};
    const Primitive flat = flattenScene(scene)[0].primitive;
    // The mirrored triangle lies in the same plane, but its surface normal must follow the mirrored vertex normal.
    CHECK((flat.normals[0] - Eigen::Vector3d(0, 0, -1)).norm() < 1e-12);
    CHECK(faceNormal(flat, flat.triangles[0]).dot(flat.normals[0]) > 0.999);
}

TEST_CASE("flattenScene transforms normals by the inverse transpose", "[scene]") {
    // A slanted triangle under a non-uniform scale: the transformed normal must stay perpendicular.
    Primitive primitive;
    primitive.positions = {{0, 0, 0}, {1, 0, 1}, {0, 1, 0}};
    const Eigen::Vector3d normal = Eigen::Vector3d(-1, 0, 1).normalized();
    primitive.normals = {normal, normal, normal};
    primitive.triangles = {{0, 1, 2}};
    Scene scene = sceneWithOneMesh(primitive);
    Node node;
    node.transform.diagonal() << 3, 1, 0.5, 1;
    node.mesh = 0;
    scene.nodes = {node};
    scene.roots = {0};
    const Primitive flat = flattenScene(scene)[0].primitive;
    CHECK(std::abs(flat.normals[0].norm() - 1) < 1e-12);
    CHECK(faceNormal(flat, flat.triangles[0]).dot(flat.normals[0]) == Approx(1).epsilon(1e-12));
}

TEST_CASE("sceneStatistics counts instances and bounds what is drawn", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    scene.meshes[0].primitives[0].positions.push_back({100, 100, 100});  // unreferenced: not drawn
    for (int i = 0; i < 3; ++i) {
        Node node;
        node.mesh = 0;
        node.transform(0, 3) = 2.0 * i;
        scene.nodes.push_back(node);
        scene.roots.push_back(i);
    }
    const SceneStatistics statistics = sceneStatistics(scene);
    CHECK(statistics.trianglesStored == 1);
    CHECK(statistics.trianglesDrawn == 3);
    CHECK(statistics.bounds.min().isApprox(Eigen::Vector3d(0, 0, 0)));
    CHECK(statistics.bounds.max().isApprox(Eigen::Vector3d(5, 1, 0)));
    const Scene flat = expandInstances(scene);
    CHECK(sceneStatistics(flat).trianglesDrawn == 3);
    CHECK(sceneStatistics(flat).trianglesStored == 3);
}

TEST_CASE("validateScene names each broken invariant", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    Node node;
    node.mesh = 0;
    scene.nodes = {node};
    scene.roots = {0};
    REQUIRE_NOTHROW(validateScene(scene));

    SECTION("index out of range") {
        scene.meshes[0].primitives[0].triangles[0][2] = 7;
        CHECK_THROWS_WITH(validateScene(scene), Catch::Contains("out of range"));
    }
    SECTION("NaN coordinate") {
        scene.meshes[0].primitives[0].positions[1].x() = std::nan("");
        CHECK_THROWS_WITH(validateScene(scene), Catch::Contains("NaN"));
    }
    SECTION("attribute count") {
        scene.meshes[0].primitives[0].normals.pop_back();
        CHECK_THROWS_WITH(validateScene(scene), Catch::Contains("NORMAL"));
    }
    SECTION("cycle") {
        scene.nodes[0].children = {0};
        CHECK_THROWS(validateScene(scene));
    }
    SECTION("a root listed twice") {
        scene.roots = {0, 0};
        CHECK_THROWS_WITH(validateScene(scene), Catch::Contains("listed twice"));
    }
    SECTION("material") {
        scene.meshes[0].primitives[0].material = 3;
        CHECK_THROWS_WITH(validateScene(scene), Catch::Contains("material"));
    }
}

TEST_CASE("dropUnreadAttributes keeps texture coordinates only where a texture reads them", "[scene]") {
    Primitive textured = unitTriangle();
    textured.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    Scene scene;
    scene.textures.resize(2);
    scene.textures[0].bytes = {0x89, 'P', 'N', 'G'};  // textures[1]: an image that could not be read
    scene.materials.resize(3);
    scene.materials[0].baseColorTexture.texture = 0;
    scene.materials[1].baseColorTexture.texture = 1;
    // Materials: reads an image, names a missing image (its reference is kept: it still reads them), has
    // no texture, none at all (-1); the last primitive has no texture coordinates to drop.
    Mesh mesh;
    for (int material : {0, 1, 2, -1}) {
        mesh.primitives.push_back(textured);
        mesh.primitives.back().material = material;
    }
    mesh.primitives.push_back(unitTriangle());
    scene.meshes.push_back(mesh);
    CHECK(dropUnreadAttributes(scene) == 2);
    const auto& kept = scene.meshes[0].primitives;
    CHECK(kept[0].texcoords == textured.texcoords);
    CHECK(kept[1].texcoords == textured.texcoords);
    for (std::size_t p = 2; p < kept.size(); ++p) CHECK(kept[p].texcoords.empty());
    CHECK(kept[0].normals == textured.normals);  // nothing else is touched
    CHECK(dropUnreadAttributes(scene) == 0);
    validateScene(scene);
}

TEST_CASE("dropUnreadAttributes keeps an unread set of texture coordinates below one a texture reads", "[scene]") {
    // glTF numbers the sets without a gap: a normal map on TEXCOORD_1 needs TEXCOORD_0 beside it (the validator's
    // MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY), read or not. Sets above it go.
    Primitive textured = unitTriangle();
    textured.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    for (const char* name : {"TEXCOORD_1", "TEXCOORD_2", "TEXCOORD_3"})
        textured.attributes.push_back({name, 2, {0, 0, 1, 0, 0, 1}});
    Scene scene;
    scene.textures.resize(1);
    scene.textures[0].bytes = {0x89, 'P', 'N', 'G'};
    scene.materials.resize(1);
    scene.materials[0].normalTexture.texture = 0;
    scene.materials[0].normalTexture.texCoord = 1;
    Mesh mesh;
    mesh.primitives.push_back(textured);
    mesh.primitives.back().material = 0;
    scene.meshes.push_back(mesh);
    CHECK(dropUnreadAttributes(scene) == 1);
    const Primitive& kept = scene.meshes[0].primitives[0];
    CHECK(kept.texcoords == textured.texcoords);
    REQUIRE(kept.attributes.size() == 1);
    CHECK(kept.attributes[0].name == "TEXCOORD_1");
    validateScene(scene);
}

TEST_CASE("dropUnreadAttributes drops tangents no normal map reads, from morph targets too", "[scene]") {
    Primitive morphed = unitTriangle();
    morphed.attributes.push_back({"TANGENT", 4, {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}});
    morphed.targets.push_back(
        {{"POSITION", 3, {0, 0, 1, 0, 0, 1, 0, 0, 1}}, {"TANGENT", 3, {0, 1, 0, 0, 1, 0, 0, 1, 0}}});
    Scene scene;
    scene.textures.resize(1);
    scene.textures[0].bytes = {0x89, 'P', 'N', 'G'};
    scene.materials.resize(2);
    scene.materials[1].normalTexture.texture = 0;
    Mesh mesh;
    for (int material : {0, 1}) {
        mesh.primitives.push_back(morphed);
        mesh.primitives.back().material = material;
    }
    scene.meshes.push_back(mesh);
    CHECK(dropUnreadAttributes(scene) == 1);
    const auto& kept = scene.meshes[0].primitives;
    CHECK(kept[0].attributes.empty());
    REQUIRE(kept[0].targets.size() == 1);
    REQUIRE(kept[0].targets[0].size() == 1);
    CHECK(kept[0].targets[0][0] == morphed.targets[0][0]);  // the positions' displacement stays
    CHECK(kept[1].attributes == morphed.attributes);        // a normal map reads them
    CHECK(kept[1].targets == morphed.targets);
    validateScene(scene);
}

TEST_CASE("validateScene checks animation channels", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    AnimationChannel channel;
    channel.node = 0;
    channel.path = AnimationChannel::Path::Rotation;
    channel.times = {0, 1};
    channel.values = {0, 0, 0, 1, 0, 0, 1, 0};
    scene.animations.push_back({"turn", {channel}});
    validateScene(scene);
    auto expectBroken = [&](auto&& breakIt, const char* problem) {
        Scene broken = scene;
        breakIt(broken.animations[0].channels[0]);
        INFO(problem);
        CHECK_THROWS_WITH(validateScene(broken), Catch::Contains(problem));
    };
    expectBroken([](AnimationChannel& c) { c.node = 3; }, "node index out of range");
    expectBroken([](AnimationChannel& c) { c.path = AnimationChannel::Path::Scale; }, "8 values for 2 keys");
    expectBroken([](AnimationChannel& c) { c.interpolation = AnimationChannel::Interpolation::CubicSpline; }, "8 values for 2 keys");
    expectBroken([](AnimationChannel& c) { c.values[2] = std::nan(""); }, "NaN");
    expectBroken([](AnimationChannel& c) { c.times = {1, 1}; }, "key times do not increase");
    expectBroken([](AnimationChannel& c) { c.times = {-1e30f, 1e-30f}; }, "negative key times");
}

TEST_CASE("validateScene checks cameras and lights, and expandInstances keeps them where they were", "[scene]") {
    Scene scene = sceneWithOneMesh(unitTriangle());
    scene.nodes.resize(3);
    scene.nodes[0].mesh = 0;
    scene.nodes[0].children = {1};
    scene.nodes[0].transform.topRightCorner<3, 1>() = Eigen::Vector3d(5, 0, 0);
    scene.nodes[1].camera = 0;
    scene.nodes[1].transform.topRightCorner<3, 1>() = Eigen::Vector3d(0, 2, 0);
    scene.nodes[2].light = 0;
    scene.roots = {0, 2};
    scene.cameras.push_back(Camera{});
    scene.lights.push_back(Light{});
    validateScene(scene);
    auto expectBroken = [&](auto&& breakIt, const char* problem) {
        Scene broken = scene;
        breakIt(broken);
        INFO(problem);
        CHECK_THROWS_WITH(validateScene(broken), Catch::Contains(problem));
    };
    expectBroken([](Scene& s) { s.nodes[1].camera = 1; }, "camera index out of range");
    expectBroken([](Scene& s) { s.nodes[2].light = -2; }, "light index out of range");
    expectBroken([](Scene& s) { s.cameras[0].yfov = 0; }, "a perspective camera needs yfov and znear above 0");
    expectBroken([](Scene& s) { s.cameras[0].zfar = 0.01; }, "zfar is not beyond znear");
    expectBroken([](Scene& s) { s.cameras[0].projection = Camera::Projection::Orthographic; }, "0 <= znear < zfar");
    expectBroken([](Scene& s) { s.cameras[0].aspectRatio = std::nan(""); }, "NaN");
    expectBroken([](Scene& s) { s.lights[0].intensity = -1; }, "negative colour, intensity or range");
    expectBroken([](Scene& s) { s.lights[0].type = Light::Type::Spot, s.lights[0].outerConeAngle = 2; }, "a spot light needs");

    const Scene flat = expandInstances(scene);
    validateScene(flat);
    REQUIRE(flat.cameras.size() == 1);
    REQUIRE(flat.lights.size() == 1);
    const std::vector<Eigen::Matrix4d> world = worldTransforms(flat);
    int cameras = 0;
    for (std::size_t n = 0; n < flat.nodes.size(); ++n)
        if (flat.nodes[n].camera == 0) {
            ++cameras;
            CHECK(world[n].topRightCorner<3, 1>() == Eigen::Vector3d(5, 2, 0));
        }
    CHECK(cameras == 1);
}
