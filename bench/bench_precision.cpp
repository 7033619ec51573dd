// Precision of the congruence test at each stage, like paper Tables II and III: of the pairs of tiles that
// the descriptor (up to a maximum order) calls congruent, the share that truly are; the same after the
// symmetry-group check; and after the geometric check (which the classification must get exactly right).
// The tiles are known by construction (samples::labelledCopies): the distinct parts of the given models,
// three times each at random rotations and mirrors, plus a near miss of each (one vertex pushed out by 0.2%
// of the largest part's size). The tolerance is 1e-4 of the largest part's size (absolute, as the
// classification's is), both when the models' parts are told apart and when the set is classified.
//   bench_precision MODEL...
#include "sample_scenes.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/detail/congruence_tolerances.hpp"
#include "symcompress/io.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <set>

using namespace symcompress;

namespace {

constexpr double kTolerance = 1e-4;  // relative to the largest part's diagonal
constexpr double kPerturbation = 2e-3;  // likewise: 20 times the tolerance
constexpr std::size_t kMaxBaseTriangles = 3000;

Eigen::AlignedBox3d boxOf(const TriangleMesh& mesh) {
    Eigen::AlignedBox3d box;
    for (const auto& p : mesh.positions) box.extend(p);
    return box;
}

CongruenceOptions withAbsoluteTolerance(double absolute, int maxOrder) {
    CongruenceOptions options;
    options.absoluteTolerance = absolute;
    options.maxOrder = maxOrder;
    options.symmetries = false;
    return options;
}

// Every part of the models (up to kMaxBaseTriangles, of non-zero size), then one of every class of those
// pooled at three times the bench's tolerance: no two bases are congruent, nor near the tolerance's edge.
std::vector<TriangleMesh> distinctParts(const std::vector<std::string>& models) {
    std::vector<Tile> pooled;
    double largest = 0;
    for (const std::string& model : models)
        for (Tile& tile : splitIntoTiles(flattenScene(readScene(model)))) {
            const double diagonal = boxOf(tile.mesh).diagonal().norm();
            if (tile.mesh.triangles.size() > kMaxBaseTriangles || !(diagonal > 0)) continue;
            tile.material = 0;
            largest = std::max(largest, diagonal);
            pooled.push_back(std::move(tile));
        }
    std::vector<TriangleMesh> bases;
    for (const CongruenceClass& c : classifyTiles(pooled, withAbsoluteTolerance(3 * kTolerance * largest, 8)).classes)
        bases.push_back(pooled[c.prototype].mesh);
    return bases;
}

struct Share {
    std::size_t pairs = 0, congruent = 0;
    void add(bool truly) { ++pairs, congruent += truly; }
    double percent() const { return pairs ? 100.0 * double(congruent) / double(pairs) : 100.0; }
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_precision MODEL...\n");
        return 2;
    }
    try {
        const std::vector<TriangleMesh> bases = distinctParts({argv + 1, argv + argc});
        const samples::LabelledTiles set = samples::labelledCopies(bases, 3, kPerturbation, 2026);
        const std::size_t n = set.tiles.size();
        std::vector<double> diagonals(n);
        for (std::size_t i = 0; i < n; ++i) diagonals[i] = boxOf(set.tiles[i].mesh).diagonal().norm();
        const double absolute = kTolerance * *std::max_element(diagonals.begin(), diagonals.end());
        std::printf("%zu distinct parts, %zu tiles, %zu labels\n", bases.size(), n, *std::max_element(set.labels.begin(), set.labels.end()) + 1);

        // Each tile's group, with the tolerance the classification gives a prototype.
        std::vector<SymmetryGroup> groups(n);
        for (std::size_t i = 0; i < n; ++i) {
            SymmetryOptions options;
            options.tolerance = tileSymmetryTolerance(diagonals[i], absolute, 1e-5);
            groups[i] = detectSymmetries(set.tiles[i].mesh, options);
        }

        std::printf("| max order | descriptor matches | truly congruent | after group check | truly congruent | after geometric check | truly congruent | labels split |\n");
        std::printf("|---|---|---|---|---|---|---|---|\n");
        for (int order : {2, 4, 6, 8, 10}) {
            std::vector<CongruenceDescriptor> descriptors(n);
            MomentOptions momentOptions;
            momentOptions.maxOrder = order;
            for (std::size_t i = 0; i < n; ++i)
                descriptors[i] = computeCongruenceDescriptor(momentCoefficients(computeSurfaceMoments(set.tiles[i].mesh, momentOptions)));
            // Pairs by area through a sorted index, as the classification finds them.
            std::vector<std::size_t> byArea(n);
            std::iota(byArea.begin(), byArea.end(), std::size_t(0));
            std::sort(byArea.begin(), byArea.end(), [&](std::size_t a, std::size_t b) { return descriptors[a].area < descriptors[b].area; });
            Share descriptor, group;
            for (std::size_t a = 0; a < n; ++a)
                for (std::size_t b = a + 1; b < n; ++b) {
                    const std::size_t i = byArea[a], j = byArea[b];
                    const double epsilon = std::max(descriptorTolerance(diagonals[i], absolute), descriptorTolerance(diagonals[j], absolute));
                    if (descriptors[j].area > descriptors[i].area * (1 + epsilon)) break;
                    if (descriptorDifference(descriptors[i], descriptors[j]) > epsilon) continue;
                    const bool truly = set.labels[i] == set.labels[j];
                    descriptor.add(truly);
                    if (groups[i].name == groups[j].name && groups[i].order() == groups[j].order()) group.add(truly);
                }
            const TileClassification classification = classifyTiles(set.tiles, withAbsoluteTolerance(absolute, order));
            Share geometric;
            std::set<std::pair<std::size_t, std::size_t>> labelClass;  // (label, class) pairs seen
            for (std::size_t k = 0; k < classification.classes.size(); ++k) {
                const CongruenceClass& c = classification.classes[k];
                for (std::size_t a = 0; a < c.members.size(); ++a) {
                    labelClass.emplace(set.labels[c.members[a]], k);
                    for (std::size_t b = a + 1; b < c.members.size(); ++b) geometric.add(set.labels[c.members[a]] == set.labels[c.members[b]]);
                }
            }
            std::set<std::size_t> labelsSeen;
            std::size_t split = 0;
            for (const auto& [label, k] : labelClass) split += !labelsSeen.insert(label).second;
            std::printf("| %d | %zu | %.1f%% | %zu | %.1f%% | %zu | %.1f%% | %zu |\n", order, descriptor.pairs, descriptor.percent(),
                        group.pairs, group.percent(), geometric.pairs, geometric.percent(), split);
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_precision: %s\n", error.what());
        return 1;
    }
    return 0;
}
