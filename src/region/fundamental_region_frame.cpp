// The frame of RegionFrame::Aligned and the quantization grid that keeps seams closed.
#include "fundamental_region_parts.hpp"
#include "geometry/bounds.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace symcompress::region_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

void addDirection(std::vector<Eigen::Vector3d>& directions, const Eigen::Vector3d& direction) {
    const double length = direction.norm();
    if (!(length > 1e-12)) return;
    const Eigen::Vector3d unit = direction / length;
    for (const Eigen::Vector3d& known : directions)
        if (std::abs(known.dot(unit)) > 1 - 1e-9) return;
    directions.push_back(unit);
}

// Directions that may be axes of a signed-permutation frame: the cone's normals, every element's axis
// and, around every 3-fold axis d, the directions at arccos(1/sqrt 3) from d through the known
// directions perpendicular to d (a 3-fold axis of a signed permutation frame is a body diagonal).
std::vector<Eigen::Vector3d> frameDirections(const std::vector<Eigen::Matrix3d>& nonIdentity,
                                             const std::vector<Eigen::Vector3d>& coneNormals) {
    std::vector<Eigen::Vector3d> directions;
    for (const Eigen::Vector3d& n : coneNormals) addDirection(directions, n);
    std::vector<Eigen::Vector3d> threeFold;
    for (const Eigen::Matrix3d& g : nonIdentity) {
        const std::optional<Eigen::Vector3d> axis = elementAxis(g);
        if (!axis) continue;
        addDirection(directions, *axis);
        const double angle = std::acos(std::clamp((g.trace() - 1) / 2, -1.0, 1.0));
        if (g.determinant() > 0 && std::abs(angle - 2 * kPi / 3) < 1e-6) threeFold.push_back(*axis);
    }
    const std::size_t known = directions.size();
    for (const Eigen::Vector3d& d : threeFold) {
        std::vector<Eigen::Vector3d> across{d.unitOrthogonal()};
        for (std::size_t i = 0; i < known; ++i)
            if (std::abs(directions[i].dot(d)) < 1e-6) across.push_back(directions[i]);
        for (const Eigen::Vector3d& m : across) {
            for (const Eigen::Vector3d& u : {Eigen::Vector3d(m), Eigen::Vector3d(d.cross(m).normalized())}) {
                addDirection(directions, d / std::sqrt(3.0) + std::sqrt(2.0 / 3.0) * u);
                addDirection(directions, d / std::sqrt(3.0) - std::sqrt(2.0 / 3.0) * u);
            }
        }
    }
    return directions;
}

struct FrameScore {
    bool signedPermutation = false;
    std::size_t alignedPlanes = 0;
    bool operator>(const FrameScore& other) const {
        if (signedPermutation != other.signedPermutation) return signedPermutation;
        return alignedPlanes > other.alignedPlanes;
    }
};

FrameScore scoreFrame(const Eigen::Matrix3d& frame, const std::vector<Eigen::Matrix3d>& nonIdentity,
                      const std::vector<Eigen::Vector3d>& coneNormals) {
    FrameScore score;
    score.signedPermutation = true;
    for (const Eigen::Matrix3d& g : nonIdentity) {
        if (!isSignedPermutation(frame.transpose() * g * frame, 1e-5)) {
            score.signedPermutation = false;
            break;
        }
    }
    for (const Eigen::Vector3d& n : coneNormals)
        score.alignedPlanes += (frame.transpose() * n).cwiseAbs().maxCoeff() > 1 - 1e-9;
    return score;
}

}  // namespace

bool isSignedPermutation(const Eigen::Matrix3d& matrix, double tolerance) {
    Eigen::Array3i perRow = Eigen::Array3i::Zero(), perColumn = Eigen::Array3i::Zero();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const double magnitude = std::abs(matrix(i, j));
            if (magnitude <= tolerance) continue;
            if (std::abs(magnitude - 1) > tolerance) return false;
            ++perRow(i);
            ++perColumn(j);
        }
    }
    return (perRow == 1).all() && (perColumn == 1).all();
}

AlignedFrame chooseAlignedFrame(const std::vector<Eigen::Matrix3d>& nonIdentity,
                                const std::vector<Eigen::Vector3d>& coneNormals) {
    // The tile's own frame wins ties: models often have their symmetry planes on coordinate planes.
    AlignedFrame best;
    FrameScore bestScore = scoreFrame(best.rotation, nonIdentity, coneNormals);
    const FrameScore perfect{true, coneNormals.size()};
    const std::vector<Eigen::Vector3d> directions = frameDirections(nonIdentity, coneNormals);
    for (const Eigen::Vector3d& first : directions) {
        if (!(perfect > bestScore)) break;
        std::vector<Eigen::Vector3d> partners = directions;
        for (const Eigen::Matrix3d& g : nonIdentity) partners.push_back(g * first);
        partners.push_back(first.unitOrthogonal());
        for (const Eigen::Vector3d& partner : partners) {
            if (std::abs(first.dot(partner)) > 1e-6) continue;
            const Eigen::Vector3d second = (partner - first.dot(partner) * first).normalized();
            Eigen::Matrix3d frame;
            frame << first, second, first.cross(second);
            const FrameScore score = scoreFrame(frame, nonIdentity, coneNormals);
            if (score > bestScore) {
                bestScore = score;
                best.rotation = frame;
                if (!(perfect > bestScore)) break;
            }
        }
    }
    best.signedPermutation = bestScore.signedPermutation;
    return best;
}

}  // namespace symcompress::region_detail

namespace symcompress {

QuantizationGrid seamPreservingGrid(const FundamentalRegion& region, int bits) {
    // One bit has a single step, which an aligned grid cannot stretch over a box across a grid point.
    if (bits < 2 || bits > 30) throw std::invalid_argument("seamPreservingGrid: bits must be in [2, 30]");
    if (region.region.positions.empty()) throw std::invalid_argument("seamPreservingGrid: the region is empty");
    const Eigen::AlignedBox3d box = boundsOf(region.region.positions);
    const double levels = std::ldexp(1.0, bits) - 1;  // the largest quantized value
    const double extent = std::max(box.sizes().maxCoeff(), 1e-300);
    if (!std::isfinite(extent) || !box.min().allFinite())
        throw std::invalid_argument("seamPreservingGrid: the region's positions are not finite");
    // The smallest power-of-two step whose grid, aligned on multiples of the step, reaches over the box.
    int exponent = static_cast<int>(std::ceil(std::log2(extent / levels)));
    for (;; ++exponent) {
        const double step = std::ldexp(1.0, exponent);
        const Eigen::Vector3d origin = (box.min() / step).array().floor() * step;
        if (((origin.array() + step * levels) >= box.max().array()).all()) {
            QuantizationGrid grid;
            grid.origin = origin;
            grid.range = step * levels;
            grid.bits = bits;
            return grid;
        }
    }
}

QuantizationGrid seamPreservingGridWithin(const FundamentalRegion& region, double maxError) {
    constexpr int kMostBits = 24;  // a float32's mantissa
    if (region.region.positions.empty()) throw std::invalid_argument("seamPreservingGrid: the region is empty");
    // The grid's step is at least the box's extent over its levels: fewer bits than that bound cannot do.
    const double extent = boundsOf(region.region.positions).sizes().maxCoeff();
    const double fewest = std::floor(std::log2(std::max(std::sqrt(3.0) / 2 * extent / maxError, 1.0)));
    for (int bits = std::clamp(int(fewest), 2, kMostBits);; ++bits) {
        QuantizationGrid grid = seamPreservingGrid(region, bits);
        const double step = grid.range / (std::ldexp(1.0, bits) - 1);
        if (std::sqrt(3.0) / 2 * step <= maxError || bits == kMostBits) return grid;
    }
}

RegionInGridSteps inGridSteps(const FundamentalRegion& region, const QuantizationGrid& grid) {
    if (grid.bits < 1 || grid.bits > 30 || !(grid.range > 0)) throw std::invalid_argument("inGridSteps: invalid grid");
    const double levels = std::ldexp(1.0, grid.bits) - 1;
    const double step = grid.range / levels;
    RegionInGridSteps result{region, grid};
    for (Eigen::Vector3d& p : result.region.region.positions) p /= step;
    result.region.regionToTile.topLeftCorner<3, 3>() *= step;
    result.grid.origin = grid.origin / step;
    result.grid.range = levels;
    return result;
}

}  // namespace symcompress
