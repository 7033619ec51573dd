// One error budget (--max-error): each mesh's position bits keep it within its share, symdecompress verifies
// the rebuilt surface against it; copies tessellated each on its own are instanced when they agree as
// surfaces, and a copy just beyond the budget, or scaled, stays apart.
#include "geometry/bounds.hpp"
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/detail/compression_plan.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// The largest distance from a corner of `original` to the nearest position of `decoded` (Draco reorders the
// vertices): a lower bound of how far the quantization moved a corner, exact while it stays below half the
// distance between corners.
double largestMove(const Primitive& original, const Primitive& decoded) {
    double largest = 0;
    for (const Eigen::Vector3d& p : original.positions) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d& q : decoded.positions) nearest = std::min(nearest, (p - q).squaredNorm());
        largest = std::max(largest, nearest);
    }
    return std::sqrt(largest);
}

Scene sceneOf(Primitive primitive) {
    Scene scene;
    scene.meshes.push_back({});
    scene.meshes[0].primitives.push_back(std::move(primitive));
    scene.nodes.push_back({});
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    return scene;
}

// A closed ellipsoid of revolution about z (radius `radius`, half as wide as tall), tessellated by
// `segments` azimuths and 12 rings with every vertex slid along the surface at random by up to a fifth of
// its spacing, each quad split along a random diagonal: the same surface as any other such part within the
// chords' sagitta, tessellated otherwise. Normals are the surface's own at each vertex (smooth).
Primitive tessellatedPart(double radius, int segments, std::mt19937& random) {
    constexpr int kRings = 12;
    std::uniform_real_distribution<double> slide(-0.2, 0.2);
    Primitive part;
    auto add = [&](double polar, double azimuth) {
        const Eigen::Vector3d direction(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                        std::cos(polar));
        part.positions.push_back(radius * Eigen::Vector3d(direction.x(), direction.y(), 2 * direction.z()));
        // The gradient of x^2 + y^2 + z^2 / 4 there.
        part.normals.push_back(Eigen::Vector3d(direction.x(), direction.y(), direction.z() / 2).normalized());
        return std::uint32_t(part.positions.size() - 1);
    };
    const std::uint32_t north = add(0, 0);
    std::vector<std::vector<std::uint32_t>> rings;
    const double start = 2 * M_PI * slide(random);
    for (int r = 1; r < kRings; ++r) {
        rings.emplace_back();
        for (int s = 0; s < segments; ++s) {
            const double azimuthSlide = slide(random), polarSlide = slide(random);  // in this order (drawnVector)
            rings.back().push_back(
                add(M_PI * (r + polarSlide) / kRings, start + 2 * M_PI * (s + azimuthSlide) / segments));
        }
    }
    const std::uint32_t south = add(M_PI, 0);
    std::bernoulli_distribution diagonal(0.5);
    for (int s = 0; s < segments; ++s) {
        const int t = (s + 1) % segments;
        part.triangles.push_back({north, rings.front()[s], rings.front()[t]});
        part.triangles.push_back({south, rings.back()[t], rings.back()[s]});
        for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
            const std::uint32_t a = rings[r][s], b = rings[r + 1][s], c = rings[r + 1][t], d = rings[r][t];
            if (diagonal(random)) {
                part.triangles.push_back({a, b, c});
                part.triangles.push_back({a, c, d});
            } else {
                part.triangles.push_back({a, b, d});
                part.triangles.push_back({b, c, d});
            }
        }
    }
    return part;
}

// kCopies copies of the part, each tessellated on its own, turned and placed at random; then one copy 6%
// larger (beyond the budget the test uses) and one half as large again. Each drawn by a node of
// its own, as a modeller's export bakes them; mesh k is copy k.
constexpr int kCopies = 12;
Scene copiesTessellatedApart(bool withNormals) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> angle(0, 2 * M_PI);
    Scene scene;
    for (int k = 0; k < kCopies + 2; ++k) {
        // 32 to 52 azimuths: no two copies have the same number of triangles.
        Primitive part = tessellatedPart(k == kCopies ? 0.53 : k == kCopies + 1 ? 0.75 : 0.5, 32 + 4 * (k % 6), random);
        if (!withNormals) part.normals.clear();
        const double second = angle(random), first = angle(random);  // in this order (drawnVector)
        const Eigen::Matrix3d turn = (Eigen::AngleAxisd(first, Eigen::Vector3d(1, 2, 3).normalized()) *
                                      Eigen::AngleAxisd(second, Eigen::Vector3d::UnitZ()))
                                         .toRotationMatrix();
        const Eigen::Vector3d at(3.0 * (k % 4), 3.0 * (k / 4), 0);
        scene.meshes.push_back({});
        scene.meshes.back().primitives.push_back(transformPrimitive(part, [&] {
            Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
            m.topLeftCorner<3, 3>() = turn;
            m.topRightCorner<3, 1>() = at;
            return m;
        }()));
        Node node;
        node.name = "part " + std::to_string(k);
        node.mesh = int(scene.meshes.size()) - 1;
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    }
    return scene;
}

// The scene as an ASCII STL with its facet normals, as CAD tools export it.
void writeStl(const Scene& scene, const std::filesystem::path& file) {
    const TriangleMesh mesh = worldMesh(scene);
    std::ofstream out(file);
    out.precision(9);
    out << "solid parts\n";
    for (const Triangle& t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        out << "facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\nouter loop\n";
        for (const Eigen::Vector3d* p : {&a, &b, &c}) out << "vertex " << p->x() << ' ' << p->y() << ' ' << p->z() << '\n';
        out << "endloop\nendfacet\n";
    }
    out << "endsolid parts\n";
}

// 300 points at random on a sphere of radius 3 about (10, -4, 2), taken three at a time as triangles.
Primitive pointsOnSphere(unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> normal;
    Primitive points;
    for (int i = 0; i < 300; ++i)
        points.positions.push_back(Eigen::Vector3d(10, -4, 2) +
                                   3 * samples::drawnVector([&] { return normal(random); }).normalized());
    for (std::uint32_t i = 0; i + 2 < 300; i += 3) points.triangles.push_back({i, i + 1, i + 2});
    return points;
}

}  // namespace

TEST_CASE("Position bits from an error bound keep every corner within it, never more bits than the bound needs",
          "[budget][writers]") {
    const Primitive points = pointsOnSphere(3);
    const double range = 6;  // about the sphere's box
    TemporaryFolder folder;
    int previous = 0;
    for (const double bound : {3e-2, 1e-3, 3e-5}) {
        WriteOptions options;
        options.maxPositionError = bound;
        const int bits = positionBitsFor(points, options);
        INFO("bound " << bound << ", " << bits << " bits");
        CHECK(bits > previous);  // a tighter bound takes more bits
        CHECK(bits <= int(std::ceil(std::log2(std::sqrt(3.0) / 2 * range / bound + 1))));
        previous = bits;
        writeScene(sceneOf(points), folder / "points.glb", options);
        const Scene decoded = readScene(folder / "points.glb");
        CHECK(largestMove(points, decoded.meshes[0].primitives[0]) <= bound);
        // The primitive's own bound takes the place of the writer's.
        Primitive own = points;
        own.maxPositionError = bound;
        CHECK(positionBitsFor(own, WriteOptions{}) == bits);
    }
    WriteOptions fixed;
    fixed.positionBits = 11;
    CHECK(positionBitsFor(points, fixed) == 11);
}

TEST_CASE("A part's corners also stay within a fraction of its own diagonal: a small part keeps its shape close up",
          "[budget][writers]") {
    const Primitive points = pointsOnSphere(3);  // a diagonal of about 10.4
    const double diagonal = boundsOfCorners(points.positions, points.triangles).diagonal().norm();
    WriteOptions options;
    options.maxPositionError = 0.5;  // the scene's budget: coarse for a part this small
    const int sceneBits = positionBitsFor(points, options);
    options.maxRelativePositionError = 2e-4;
    CHECK(positionErrorBound(points, options) == Approx(2e-4 * diagonal));
    const int closeUpBits = positionBitsFor(points, options);
    CHECK(closeUpBits > sceneBits + 6);
    TemporaryFolder folder;
    writeScene(sceneOf(points), folder / "points.glb", options);
    CHECK(largestMove(points, readScene(folder / "points.glb").meshes[0].primitives[0]) <= 2e-4 * diagonal);
    // Where the scene's bound is the tighter, it alone counts; without a bound, the fixed bits.
    options.maxPositionError = 1e-4 * diagonal;
    CHECK(positionErrorBound(points, options) == Approx(1e-4 * diagonal));
    options.maxPositionError = 0;
    CHECK(positionErrorBound(points, options) == 0);
    CHECK(positionBitsFor(points, options) == options.positionBits);
    // A part stored turned from the world keeps the close-up bound of the box it had there
    // (Primitive::closeUpDiagonal): its own box turned is another size.
    Primitive turned = points;
    turned.closeUpDiagonal = 2 * diagonal;
    options.maxPositionError = 0.5;
    CHECK(positionErrorBound(turned, options) == Approx(4e-4 * diagonal));
}

TEST_CASE("X3D positions are written to the fewest places that keep every corner within the error bound",
          "[budget][writers][x3d]") {
    const Primitive points = pointsOnSphere(5);
    TemporaryFolder folder;
    const Scene scene = sceneOf(points);
    writeScene(scene, folder / "exact.x3d", WriteOptions{});
    CHECK(largestMove(points, readScene(folder / "exact.x3d").meshes[0].primitives[0]) < 1e-12);
    std::uintmax_t previous = std::filesystem::file_size(folder / "exact.x3d");
    for (const double bound : {1e-4, 1e-3, 3e-2}) {
        INFO("bound " << bound);
        WriteOptions options;
        options.maxPositionError = bound;
        writeScene(scene, folder / "rounded.x3d", options);
        const double moved = largestMove(points, readScene(folder / "rounded.x3d").meshes[0].primitives[0]);
        CHECK(moved <= bound);
        CHECK(moved > bound / 20);  // no more places than the bound needs
        const std::uintmax_t bytes = std::filesystem::file_size(folder / "rounded.x3d");
        CHECK(bytes < previous);
        previous = bytes;
    }
    // A sliver whose two corners the bound's places would put at one point: written with more places.
    Primitive sliver;
    sliver.positions = {{0, 0, 0}, {4e-4, 0, 0}, {0, 1, 0}};
    sliver.triangles = {{0, 1, 2}};
    WriteOptions options;
    options.maxPositionError = 1e-2;
    writeScene(sceneOf(sliver), folder / "sliver.x3d", options);
    const Primitive read = readScene(folder / "sliver.x3d").meshes[0].primitives[0];
    CHECK(read.triangles.size() == 1);
    CHECK(largestMove(sliver, read) <= 1e-2);
}

TEST_CASE("The error budget bounds the rebuilt surface, and a tighter budget costs bytes", "[budget][compress]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    const Scene scene = copiesTessellatedApart(true);
    writeScene(scene, folder / "parts.glb", plain);
    std::uintmax_t looser = 0;
    for (const double budget : {2e-4, 1e-5}) {
        INFO("budget " << budget);
        CompressOptions options;
        options.maxError = budget;
        const CompressionReport report = compressFile(folder / "parts.glb", folder / "small.glb", options);
        CHECK(report.maxError == budget);
        CHECK(report.tolerance == budget / 2);
        const RebuildReport rebuilt = decompressFile(folder / "small.glb", folder / "flat.glb", folder / "parts.glb");
        CHECK(rebuilt.verified);
        CHECK(rebuilt.maxDeviation <= budget * 1.01);
        CHECK(rebuilt.allowedDeviation == Approx(budget).epsilon(0.02));
        CHECK(decompressFile(folder / "small.glb", folder / "flat.glb").verified);  // against the stored digest
        if (looser) CHECK(report.outputBytes > looser);
        looser = report.outputBytes;
    }
    SECTION("fixed bits: verified as before, with no budget stored") {
        CompressOptions options;
        options.fixedPositionBits = true;
        const CompressionReport report = compressFile(folder / "parts.glb", folder / "fixed.glb", options);
        CHECK(report.maxError == 0);
        CHECK(decompressFile(folder / "fixed.glb", folder / "flat.glb", folder / "parts.glb").verified);
    }
}

TEST_CASE("Copies tessellated each on its own are one stored copy and a node each, and a near miss and a scaled copy "
          "stay apart",
          "[budget][compress][congruence]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    const bool withNormals = GENERATE(true, false);
    INFO(std::string(withNormals ? "glTF with smooth normals" : "STL with facet normals"));
    const Scene scene = copiesTessellatedApart(withNormals);
    const std::filesystem::path input = folder / (withNormals ? "parts.glb" : "parts.stl");
    if (withNormals)
        writeScene(scene, input, plain);
    else
        writeStl(scene, input);
    CompressOptions options;
    options.maxError = 2e-3;  // the tessellations differ by up to 8e-3 (7e-4 of the diagonal), the near miss by 3e-2
    options.regions = false;  // one stored copy, a node per copy (regions would add nodes per copy)
    const CompressionReport report = compressFile(input, folder / "small.glb", options);
    auto triangles = [&](int k) { return scene.meshes[std::size_t(k)].primitives[0].triangles.size(); };
    CHECK(report.stats.instancedClasses == 1);
    CHECK(report.stats.instances == kCopies);
    // One copy, the one of fewest triangles (which stands for the others), the near miss and the scaled one.
    const std::size_t apart = triangles(kCopies) + triangles(kCopies + 1);
    std::size_t fewest = triangles(0);
    for (int k = 0; k < kCopies; ++k) fewest = std::min(fewest, triangles(k));
    CHECK(report.stats.trianglesStored == apart + fewest);
    CHECK(decompressFile(folder / "small.glb", folder / "flat.glb", input).verified);
    CHECK(report.outputBytes < *report.ablation.dracoAlone / 2);

    SECTION("with regions too: verified, no larger") {
        CompressOptions full;
        full.maxError = 2e-3;
        const CompressionReport all = compressFile(input, folder / "all.glb", full);
        CHECK(all.outputBytes <= report.outputBytes);
        CHECK(decompressFile(folder / "all.glb", folder / "flat.glb", input).verified);
    }
}

TEST_CASE("A mesh drawn by one node takes the whole error budget, a mesh several nodes draw leaves the rotations' share",
          "[budget][plan]") {
    const Scene scene = copiesTessellatedApart(true);
    CompressOptions options;
    options.maxError = 2e-3;
    options.regions = false;
    const SceneAnalysis analysis = analyzeScene(scene, analysisOptionsOf(options));
    PlanOptions plan = planOptionsOf(options);
    plan.instanceShare = options.maxError / 64;
    const CompressedScene compressed = compressAnalyzed(scene, analysis, plan);
    const Scene& out = compressed.scene;
    std::vector<int> drawers(out.meshes.size(), 0);
    for (const Node& node : out.nodes)
        if (node.mesh >= 0) ++drawers[std::size_t(node.mesh)];
    bool once = false, several = false;
    for (std::size_t m = 0; m < out.meshes.size(); ++m)
        for (const Primitive& primitive : out.meshes[m].primitives) {
            INFO("mesh " << m << ", drawn by " << drawers[m] << " nodes");
            REQUIRE(primitive.maxPositionError > 0);
            if (drawers[m] == 1) {
                // The near miss and the scaled copy, stored as they are, under the identity: no deviation.
                once = true;
                CHECK(primitive.maxPositionError == Approx(options.maxError * analysis.diagonal));
            } else {
                several = true;
                CHECK(primitive.maxPositionError <=
                      (options.maxError - plan.instanceShare) * analysis.diagonal);
            }
        }
    CHECK(once);
    CHECK(several);
}

TEST_CASE("Hundreds of small parts verify within the budget: the area may change by their perimeters times it",
          "[budget][compress]") {
    // 500 shared copies of a small part over a large floor (the toy scene of ../shared/bench): a corner moved
    // by the budget changes a small triangle's area by more than ten times the budget's share of the scene's.
    TemporaryFolder folder;
    const auto input = folder / "shared500.glb";
    REQUIRE(runCommand("python3 " + quoted(sharedDir() / "bench/make_toy_scene.py") + " " + quoted(input) +
                       " --baked 0 --shared 500 --dupes 0")
                .status == 0);
    CompressOptions sceneBudgetOnly;
    sceneBudgetOnly.closeUpError = 0;  // each part quantized by the scene's budget alone: a blob takes 8 bits
    const CompressionReport coarse = compressFile(input, folder / "small.glb", sceneBudgetOnly);
    const RebuildReport rebuilt = decompressFile(folder / "small.glb", folder / "flat.glb", input);
    CHECK(rebuilt.maxDeviation <= rebuilt.allowedDeviation);
    CHECK(std::abs(rebuilt.areaRatio - 1) > 10 * rebuilt.allowedDeviation);  // what the old rule refused
    CHECK(rebuilt.verified);
    CHECK(decompressFile(folder / "small.glb", folder / "flat.glb").verified);  // against the digest

    SECTION("by default each part also keeps its shape close up, and the scene renders as its input") {
        const CompressionReport closeUp = compressFile(input, folder / "close.glb");
        CHECK(closeUp.outputBytes > coarse.outputBytes);
        CHECK(closeUp.outputBytes < coarse.outputBytes * 1.05);  // a few bits more for one stored blob
        const Scene in = readScene(input);
        const Primitive& blob = in.meshes[0].primitives[0];
        const double partDiagonal = boundsOfCorners(blob.positions, blob.triangles).diagonal().norm();
        const TriangleMesh world = worldMesh(in);
        const double sceneDiagonal = boundsOfCorners(world.positions, world.triangles).diagonal().norm();
        // Drawn by nodes (float transforms, not a GPU batch's rounded ones): the blob's own quantization.
        CompressOptions asNodes;
        asNodes.write.gpuInstancing = false;
        compressFile(input, folder / "nodes.glb", asNodes);
        CHECK(decompressFile(folder / "nodes.glb", folder / "flat.glb", input).maxDeviation * sceneDiagonal <=
              5e-5 * partDiagonal);
        if (renderAvailable()) {
            checkRendersSame(input, folder / "close.glb");
            // The scene's budget alone: 1.2 to 1.5% of the blobs' pixels differ (2.7% of their normals' colours).
            const CommandResult coarseRender = renderCompare(input, folder / "small.glb", "lit", "a");
            CHECK(coarseRender.status != 0);
        }
    }
}

TEST_CASE("Draco's size is not monotonic in the position bits: more bits within the bound are tried, the smallest kept",
          "[budget][writers]") {
    const Primitive points = pointsOnSphere(3);
    WriteOptions options;
    options.maxPositionError = 1e-3;
    const int fewest = positionBitsFor(points, options);
    const std::vector<int> more = positionBitsWorthTrying(points, options, fewest);
    CHECK(more.size() <= 2);
    for (std::size_t k = 0; k < more.size(); ++k) CHECK(more[k] == fewest + 1 + int(k));
    Primitive onGrid = points;
    onGrid.positionGrid = QuantizationGrid{};
    CHECK(positionBitsWorthTrying(onGrid, options, fewest).empty());
    CHECK(positionBitsWorthTrying(points, WriteOptions{}, fewest).empty());  // fixed bits

    // The grass cards' scene (731 cards of 8 triangles, stored as they are, in one mesh per material as the plan
    // stores them where they are opaque): smaller than at the fewest bits alone, and within the bound.
    CompressOptions asTheyAre;
    asTheyAre.instancing = false;
    TemporaryFolder folder;
    Scene opaque = readScene(modelPath("cge_grass_flowers/grass_flowers.x3d"));
    for (Material& material : opaque.materials) material.alphaMode = Material::AlphaMode::Opaque;
    WriteOptions plain;
    plain.draco = false;
    writeScene(opaque, folder / "opaque.glb", plain);
    compressFile(folder / "opaque.glb", folder / "grass.glb", asTheyAre);
    const Scene grass = readScene(folder / "grass.glb");
    Scene merged;
    merged.meshes.push_back({});
    Primitive& all = merged.meshes[0].primitives.emplace_back();
    for (const Primitive& primitive : grass.meshes[0].primitives)
        if (primitive.triangles.size() > all.triangles.size()) all = primitive;
    all.material = -1;  // the texture coordinates kept, the scene's materials not
    merged.nodes.push_back({});
    merged.nodes[0].mesh = 0;
    merged.roots = {0};
    REQUIRE(all.triangles.size() <= 20000);
    WriteOptions bounded;
    bounded.maxPositionError = 5e-5 * boundsOfCorners(all.positions, all.triangles).diagonal().norm();
    WriteOptions fixed;
    fixed.positionBits = positionBitsFor(all, bounded);
    REQUIRE_FALSE(positionBitsWorthTrying(all, bounded, fixed.positionBits).empty());
    writeScene(merged, folder / "tried.glb", bounded);
    writeScene(merged, folder / "fewest.glb", fixed);
    CHECK(std::filesystem::file_size(folder / "tried.glb") < std::filesystem::file_size(folder / "fewest.glb"));
    CHECK(largestMove(all, readScene(folder / "tried.glb").meshes[0].primitives[0]) <= bounded.maxPositionError);
}

TEST_CASE(
    "Texture coordinates move by at most half of 1/16 of a texel, on a grid of that step where their bits over "
    "their span would be finer",
    "[budget][writers]") {
    // Coordinates over [0.2, 0.8] of a 1024-pixel texture: 9830 sixteenths of a texel, 14 bits, whose own steps
    // over the span (0.6 / 16383) are finer than a sixteenth (1 / 16384): the grid is stretched to it.
    Primitive points = pointsOnSphere(9);
    std::mt19937 random(4);
    std::uniform_real_distribution<double> uniform(0.2, 0.8);
    for (std::size_t v = 0; v < points.positions.size(); ++v)
        points.texcoords.push_back({uniform(random), uniform(random)});
    points.texcoords[0] = {0.2, 0.2};
    points.texcoords[1] = {0.8, 0.8};
    points.material = 0;
    Scene scene = sceneOf(points);
    // A PNG's signature and header: 1024 by 1024 (the writer reads the size, never the pixels).
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                     0,    0,   4,   0,   0,    0,    4,    0,    8, 6, 0, 0,  0,   0,   0,   0};
    scene.textures.push_back({"checker", "", "image/png", png, {}});
    scene.materials.push_back({});
    scene.materials[0].baseColorTexture.texture = 0;
    TemporaryFolder folder;
    writeScene(scene, folder / "textured.glb");
    const Primitive decoded = readScene(folder / "textured.glb").meshes[0].primitives[0];
    REQUIRE(decoded.texcoords.size() == decoded.positions.size());
    double largest = 0;
    for (std::size_t v = 0; v < points.positions.size(); ++v) {
        std::size_t nearest = 0;
        for (std::size_t d = 1; d < decoded.positions.size(); ++d)
            if ((decoded.positions[d] - points.positions[v]).norm() <
                (decoded.positions[nearest] - points.positions[v]).norm())
                nearest = d;
        largest = std::max(largest, (decoded.texcoords[nearest] - points.texcoords[v]).cwiseAbs().maxCoeff());
    }
    const double sixteenth = 1.0 / (1024 * 16);
    CHECK(largest <= sixteenth / 2 * (1 + 1e-3));
    CHECK(largest > 0.6 / 16383 / 2 * 1.2);  // beyond the half step of 14 bits over the span alone
}

TEST_CASE("Where whole bits keep the corners well within the bound, a coarser grid of those bits uses the rest",
          "[budget][writers]") {
    const Primitive points = pointsOnSphere(5);
    TemporaryFolder folder;
    WriteOptions twelve;
    twelve.positionBits = 12;
    twelve.encodingTrials = false;
    writeScene(sceneOf(points), folder / "twelve.glb", twelve);
    const double atTwelve = largestMove(points, readScene(folder / "twelve.glb").meshes[0].primitives[0]);
    // A bound 1.6 times what 12 bits move the corners by: 11 bits (twice the step) do not keep it.
    WriteOptions options;
    options.maxPositionError = 1.6 * atTwelve;
    REQUIRE(positionBitsFor(points, options) == 12);
    const std::optional<QuantizationGrid> coarser = coarserPositionGrid(points, options, 12);
    REQUIRE(coarser);
    CHECK(coarser->bits == 12);
    const Eigen::AlignedBox3d box = boundsOfCorners(points.positions, points.triangles);
    CHECK(coarser->range > box.sizes().maxCoeff() * 1.05);
    CHECK(coarser->range < box.sizes().maxCoeff() * 2);
    CHECK((coarser->origin - box.min()).norm() < 1e-5);
    // Written with it where it codes smaller: the corners move farther than 12 bits' own grid moves them, within
    // the bound.
    writeScene(sceneOf(points), folder / "coarser.glb", options);
    const double moved = largestMove(points, readScene(folder / "coarser.glb").meshes[0].primitives[0]);
    CHECK(moved <= options.maxPositionError);
    CHECK(moved > atTwelve);
    CHECK(std::filesystem::file_size(folder / "coarser.glb") < std::filesystem::file_size(folder / "twelve.glb"));
    // None without a bound, for a primitive with a grid of its own, or where the bound leaves no room.
    CHECK(!coarserPositionGrid(points, twelve, 12));
    CHECK(!coarserPositionGrid(points, WriteOptions{}, 12));
    Primitive onGrid = points;
    onGrid.positionGrid = QuantizationGrid{};
    CHECK(!coarserPositionGrid(onGrid, options, 12));
    WriteOptions tight = options;
    tight.maxPositionError = atTwelve;
    CHECK(!coarserPositionGrid(points, tight, 12));
}

TEST_CASE("A scene a hundred-millionth or a millionth across verifies within the budget", "[budget][compress]") {
    // Draco keeps an explicit grid's origin and range as six decimals: the coarser grid of a scene 1e-8 across
    // decoded every corner to one point, one 1e-6 across came out 1.1 times the budget.
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    for (const double scale : {1e-8, 1e-6}) {
        INFO("scale " << scale);
        // Four L-shaped parts (a cube and a flat box through its side), baked in one primitive.
        Primitive parts;
        auto addBox = [&](const Eigen::Vector3d& center, const Eigen::Vector3d& size) {
            const auto first = std::uint32_t(parts.positions.size());
            for (int i = 0; i < 8; ++i) {
                const Eigen::Vector3d corner(i & 1, (i >> 1) & 1, i >> 2);
                parts.positions.push_back(scale * (center + (corner.array() - 0.5).matrix().cwiseProduct(size)));
            }
            for (const Triangle& t : std::vector<Triangle>{{0, 2, 1},
                                                           {1, 2, 3},
                                                           {4, 5, 6},
                                                           {5, 7, 6},
                                                           {0, 1, 4},
                                                           {1, 5, 4},
                                                           {2, 6, 3},
                                                           {3, 6, 7},
                                                           {0, 4, 2},
                                                           {2, 4, 6},
                                                           {1, 3, 5},
                                                           {3, 7, 5}})
                parts.triangles.push_back({first + t[0], first + t[1], first + t[2]});
        };
        for (int k = 0; k < 4; ++k) {
            addBox(Eigen::Vector3d(3 * k, 0, 0), Eigen::Vector3d(1, 1, 1));
            addBox(Eigen::Vector3d(3 * k + 0.75, 0.25, 0), Eigen::Vector3d(0.5, 0.5, 0.3));
        }
        writeScene(sceneOf(parts), folder / "small.glb", plain);
        compressFile(folder / "small.glb", folder / "out.glb", CompressOptions{});
        const RebuildReport rebuilt = decompressFile(folder / "out.glb", folder / "flat.glb", folder / "small.glb");
        CHECK(rebuilt.verified);
        CHECK(rebuilt.areaRatio == Approx(1).epsilon(1e-3));
    }
}

TEST_CASE(
    "A corner's move is measured to what float32 tells apart: a bound a fraction of a unit in the last place "
    "below the move keeps the bits, a whole unit below does not",
    "[budget][writers]") {
    const Primitive points = pointsOnSphere(4);
    TemporaryFolder folder;
    WriteOptions fixed;
    fixed.positionBits = 12;
    writeScene(sceneOf(points), folder / "fixed.glb", fixed);
    const double move = largestMove(points, readScene(folder / "fixed.glb").meshes[0].primitives[0]);
    // Half a unit in the last place of a float32 coordinate near 13 (the points lie within 3 of (10, -4, 2)).
    const double halfUlp = std::ldexp(1.0, -24) * 8;
    WriteOptions bounded;
    bounded.maxPositionError = move - halfUlp / 4;
    CHECK(positionBitsFor(points, bounded) == 12);
    bounded.maxPositionError = move - 4 * halfUlp;
    CHECK(positionBitsFor(points, bounded) == 13);
}

TEST_CASE("A budget finer than float32 keeps is raised to what it keeps, said in a warning, and the output verifies",
          "[budget][compress]") {
    // The unlit test's coordinates reach 2.2 on a diagonal of 4.9: float32's steps there are 5e-8 of it, and a few
    // add up (its own, Draco's dequantization): 1e-8 was printed as the budget and missed (5.6e-8).
    TemporaryFolder folder;
    const auto input = modelPath("pbr/unlit/UnlitTest.gltf");
    CompressOptions fine;
    fine.maxError = 1e-8;
    const CompressionReport report = compressFile(input, folder / "fine.glb", fine);
    CHECK(report.maxError == Approx(std::ldexp(1.0, -21)));
    CHECK(std::count_if(report.warnings.begin(), report.warnings.end(), [](const std::string& warning) {
              return warning.find("--max-error 1e-08 is finer than float32") != std::string::npos;
          }) == 1);
    const RebuildReport rebuilt = decompressFile(folder / "fine.glb", folder / "flat.glb", input);
    CHECK(rebuilt.verified);
    CHECK(rebuilt.allowedDeviation < 5e-7);
    // At a budget float32 keeps, nothing is said.
    CompressOptions keepable;
    keepable.maxError = 1e-6;
    const CompressionReport kept = compressFile(input, folder / "kept.glb", keepable);
    CHECK(kept.maxError == 1e-6);
    for (const std::string& warning : kept.warnings) CHECK(warning.find("float32") == std::string::npos);
}
