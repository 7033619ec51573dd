// bolts.glb: 12 copies of one bolt baked into the vertices of a single mesh, each at a random position and
// orientation, every third one mirrored. The bolt is one closed surface of 1248 triangles: a 24-sided shaft
// with 10 thread ridges and a chamfered tip under a head of six lobes. Its group is C6 (order 6): the
// lobes and rings have mirror planes, but the diagonals that split the chamfer's non-planar quads do not.
#include "sample_scenes.hpp"

#include "symcompress/scene_ops.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace symcompress::samples {

namespace {

constexpr int kSides = 24;

// One ring of the bolt's lathe: radius of even and odd corners at height z.
struct Ring {
    double evenRadius;
    double oddRadius;
    double z;
};

Eigen::Vector3d ringCorner(const Ring& ring, int k) {
    const double angle = 2 * M_PI * k / kSides;
    const double radius = ((k / 2) % 2 == 0) ? ring.evenRadius : ring.oddRadius;  // six lobes of two corners
    return {radius * std::cos(angle), radius * std::sin(angle), ring.z};
}

// Appends a flat-shaded triangle (its own three vertices, so that normals stay sharp).
void addFlatTriangle(Primitive& out, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (const Eigen::Vector3d& corner : {a, b, c}) {
        out.positions.push_back(corner);
        out.normals.push_back(normal);
    }
    out.triangles.push_back({base, base + 1, base + 2});
}

// Bakes `copies` placements of `part` into one primitive; every `mirrorEvery`-th copy is mirrored.
Primitive bakeCopies(const Primitive& part, int copies, int mirrorEvery, double spread, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(-1, 1);
    Primitive out;
    for (int copy = 0; copy < copies; ++copy) {
        const Eigen::Quaterniond rotation = drawnQuaternion([&] { return uniform(random); }).normalized();
        Eigen::Matrix3d linear = rotation.toRotationMatrix();
        const bool mirrored = mirrorEvery > 0 && copy % mirrorEvery == mirrorEvery - 1;
        if (mirrored) linear.col(0) = -linear.col(0);
        const Eigen::Vector3d offset = spread * drawnVector([&] { return uniform(random); });
        const Eigen::Matrix3d normalMatrix = linear.inverse().transpose();
        const auto base = static_cast<std::uint32_t>(out.positions.size());
        for (std::size_t v = 0; v < part.positions.size(); ++v) {
            // Round to float32 as a real file would store it.
            out.positions.push_back((linear * part.positions[v] + offset).cast<float>().cast<double>());
            out.normals.push_back((normalMatrix * part.normals[v]).normalized());
        }
        for (Triangle t : part.triangles) {
            if (mirrored) std::swap(t[1], t[2]);
            out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
        }
    }
    return out;
}

}  // namespace

Primitive makeBolt() {
    std::vector<Ring> rings = {{0.38, 0.38, 0.0}, {0.5, 0.5, 0.12}};
    for (int ridge = 0; ridge < 10; ++ridge) {  // the thread, as rings (a helix would break the mirrors)
        const double z = 0.2 + 0.26 * ridge;
        rings.push_back({0.44, 0.44, z});
        rings.push_back({0.5, 0.5, z + 0.13});
    }
    for (const Ring& ring : std::vector<Ring>{{0.5, 0.5, 3.0}, {1.0, 0.87, 3.0}, {1.0, 0.87, 3.7}, {0.9, 0.78, 3.8}})
        rings.push_back(ring);
    Primitive bolt;
    for (std::size_t level = 0; level + 1 < rings.size(); ++level)
        for (int k = 0; k < kSides; ++k) {
            const Eigen::Vector3d a = ringCorner(rings[level], k), b = ringCorner(rings[level], k + 1),
                                  c = ringCorner(rings[level + 1], k + 1), d = ringCorner(rings[level + 1], k);
            addFlatTriangle(bolt, a, b, c);
            addFlatTriangle(bolt, a, c, d);
        }
    // Caps fanned from their centres, so that the tessellation keeps the 6-fold symmetry.
    const Eigen::Vector3d bottomCentre(0, 0, rings.front().z), topCentre(0, 0, rings.back().z);
    for (int k = 0; k < kSides; ++k) {
        addFlatTriangle(bolt, bottomCentre, ringCorner(rings.front(), k + 1), ringCorner(rings.front(), k));
        addFlatTriangle(bolt, topCentre, ringCorner(rings.back(), k), ringCorner(rings.back(), k + 1));
    }
    return bolt;
}

Scene singleMeshScene(const std::string& name, Primitive primitive, const Eigen::Vector4d& colour) {
    Material material;
    material.name = name + "-material";
    material.baseColorFactor = colour;
    material.metallicFactor = 0.8;
    material.roughnessFactor = 0.35;
    primitive.material = 0;
    Scene scene = sceneOfOneMesh(name, std::move(primitive));
    scene.materials.push_back(material);
    return scene;
}

Scene makeBoltsScene() {
    return singleMeshScene("bolts", bakeCopies(makeBolt(), 12, 3, 12.0, 20261122u), {0.7, 0.7, 0.75, 1});
}


}  // namespace symcompress::samples
