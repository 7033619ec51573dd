// Classifying orthogonal maps and naming finite groups of them (Schoenflies notation).
#include "symcompress/symmetry.hpp"

#include "point_group_closure.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <map>

namespace symcompress {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Frobenius distance below which two group elements are one: far below the distance between distinct
// elements of any group with folds up to 360 (about 0.025), far above what refined data leaves.
constexpr double kSameElement = 5e-3;
// Axes of elements refined one by one on approximate data agree to about the tolerance: two axes within
// 0.005 rad are one, and an axis within 0.005 rad of perpendicular is perpendicular.
constexpr double kSameAxis = 1.25e-5;  // 1 - |cos| at 0.005 rad
constexpr double kPerpendicular = 0.005;
// Angles this close to 0 or pi are 0 or pi: products of maps refined on noisy data carry errors of about
// the data's, and no element of a group with folds up to 360 comes near (2 pi / 360 = 0.017).
constexpr double kSnapAngle = 2e-3;

// The rotation axis of a proper rotation R by angle in (0, pi].
Eigen::Vector3d rotationAxis(const Eigen::Matrix3d& r, double angle) {
    if (angle < kPi - 1e-4) return Eigen::Vector3d(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1)).normalized();
    // Near a half turn R + I = 2 a a^T: take its largest column.
    const Eigen::Matrix3d s = r + Eigen::Matrix3d::Identity();
    int column;
    s.colwise().norm().maxCoeff(&column);
    Eigen::Vector3d axis = s.col(column).normalized();
    // Polish with the antisymmetric part's sign when the angle is a little below pi.
    const Eigen::Vector3d antisymmetric(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
    if (antisymmetric.dot(axis) < 0) axis = -axis;
    return axis;
}

// atan2 rather than acos of the trace: acos loses half the digits near 0 and pi, where mirrors and the
// identity are.
double rotationAngle(const Eigen::Matrix3d& r) {
    const Eigen::Vector3d antisymmetric(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
    return std::atan2(antisymmetric.norm() / 2, (r.trace() - 1) / 2);
}

bool sameAxis(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return 1 - std::abs(a.dot(b)) < kSameAxis; }

}  // namespace

const char* kindName(Symmetry::Kind kind) {
    switch (kind) {
    case Symmetry::Kind::Identity: return "identity";
    case Symmetry::Kind::Rotation: return "rotation";
    case Symmetry::Kind::Mirror: return "mirror";
    case Symmetry::Kind::Rotoreflection: return "rotoreflection";
    case Symmetry::Kind::Inversion: return "inversion";
    }
    return "?";
}

Symmetry describeOrthogonal(const Eigen::Matrix3d& linear) {
    Symmetry s;
    s.linear = linear;
    if (linear.determinant() > 0) {
        const double angle = rotationAngle(linear);
        if (angle < kSnapAngle) return s;  // identity
        s.kind = Symmetry::Kind::Rotation;
        s.angle = angle;
        s.axis = rotationAxis(linear, angle);
        return s;
    }
    // linear = -R with R proper; -R_theta(a) is the mirror z -> -z about a composed with R_(theta + pi)(a).
    const Eigen::Matrix3d r = -linear;
    const double theta = rotationAngle(r);
    if (theta < kSnapAngle) {
        s.kind = Symmetry::Kind::Inversion;
        s.angle = kPi;
        return s;
    }
    const Eigen::Vector3d axis = rotationAxis(r, theta);
    if (theta > kPi - kSnapAngle) {
        s.kind = Symmetry::Kind::Mirror;
        s.axis = axis;
        return s;
    }
    s.kind = Symmetry::Kind::Rotoreflection;
    const double alpha = theta + kPi;  // in (pi, 2 pi): the same map is about -axis by 2 pi - alpha
    s.angle = 2 * kPi - alpha;
    s.axis = -axis;
    return s;
}

double ElementIndex::projection(const Eigen::Matrix3d& m) {
    static const Eigen::Matrix3d weights =
        (Eigen::Matrix3d() << 0.31, -0.47, 0.12, 0.58, 0.23, -0.19, -0.36, 0.27, 0.21).finished().normalized();
    return weights.cwiseProduct(m).sum();
}

ElementIndex::ElementIndex(const std::vector<Eigen::Matrix3d>& elements, double window)
    : elements_(elements), window_(window) {
    for (std::size_t i = 0; i < elements.size(); ++i) added(i);
}

void ElementIndex::added(std::size_t i) { byProjection_.emplace(projection(elements_[i]), i); }

std::vector<Eigen::Matrix3d> closeGroup(std::vector<Eigen::Matrix3d> generators, std::size_t limit) {
    std::vector<Eigen::Matrix3d> group;
    ElementIndex index(group, kSameElement);
    auto add = [&](const Eigen::Matrix3d& m) {
        if (index.find(m) != SIZE_MAX) return;
        group.push_back(m);
        index.added(group.size() - 1);
    };
    add(Eigen::Matrix3d::Identity());
    for (const auto& g : generators) add(g);
    // Products of everything with the generators until nothing new appears.
    for (std::size_t i = 0; i < group.size() && group.size() <= limit; ++i)
        for (const auto& g : generators) {
            add(group[i] * g);
            if (group.size() > limit) break;
        }
    return group;
}

std::vector<Eigen::Matrix3d> averagedOverGroup(const std::vector<Eigen::Matrix3d>& group) {
    // Each g_k becomes the orthogonal factor of the mean over j of g_(kj) g_j^T, where g_(kj) is the element
    // nearest g_k g_j: for elements about one axis whose angles drifted by e_k, the mean angle is
    // k theta + mean(e_(k+j) - e_j) = k theta, exactly where the table is right.
    std::vector<Eigen::Matrix3d> averaged(group.size());
    const ElementIndex index(group, kSameElement);
    for (std::size_t k = 0; k < group.size(); ++k) {
        Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
        for (const Eigen::Matrix3d& g : group) {
            const std::size_t product = index.find(group[k] * g);
            if (product == SIZE_MAX) return group;  // not a group within kSameElement: left as it is
            sum += group[product] * g.transpose();
        }
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
        averaged[k] = svd.matrixU() * svd.matrixV().transpose();
    }
    return averaged;
}

std::string pointGroupName(const std::vector<Eigen::Matrix3d>& group) {
    struct Axis {
        Eigen::Vector3d direction;
        int fold;
    };
    // Proper rotation axes with their order: in a finite group, the rotations about one axis and the identity
    // are the cyclic group of the axis's order, so the rotations are counted. (The order of each element, its
    // powers up to the identity, carries the error of products of refined maps: a 44-fold axis whose
    // rotations come from products of mirrors was named 4-fold.)
    std::vector<Axis> axes;
    std::vector<Eigen::Vector3d> mirrors, rotoreflectionAxes;
    bool inversion = false;
    for (const auto& m : group) {
        const Symmetry s = describeOrthogonal(m);
        switch (s.kind) {
        case Symmetry::Kind::Identity: break;
        case Symmetry::Kind::Inversion: inversion = true; break;
        case Symmetry::Kind::Mirror: mirrors.push_back(s.axis); break;
        case Symmetry::Kind::Rotoreflection: rotoreflectionAxes.push_back(s.axis); break;
        case Symmetry::Kind::Rotation: {
            auto found = std::find_if(axes.begin(), axes.end(), [&](const Axis& a) { return sameAxis(a.direction, s.axis); });
            if (found == axes.end()) axes.push_back({s.axis, 2});  // the identity and this rotation
            else ++found->fold;
            break;
        }
        }
    }
    const std::string n = axes.empty() ? "" : std::to_string(std::max_element(axes.begin(), axes.end(), [](const Axis& a, const Axis& b) {
                                                                 return a.fold < b.fold;
                                                             })->fold);
    const auto highAxes = std::count_if(axes.begin(), axes.end(), [](const Axis& a) { return a.fold >= 3; });
    if (highAxes >= 2) {  // polyhedral groups
        const int top = std::stoi(n);
        const std::string base = top == 5 ? "I" : top == 4 ? "O" : "T";
        if (inversion) return base + "h";
        if (base == "T" && !mirrors.empty()) return "Td";
        return base;
    }
    if (axes.empty()) return !mirrors.empty() ? "Cs" : inversion ? "Ci" : "C1";

    // The principal axis: of highest order; among several 2-fold axes, one with a rotoreflection about it
    // (D2d), else the first.
    const int fold = std::stoi(n);
    const Axis* principal = nullptr;
    for (const auto& a : axes)
        if (a.fold == fold && !principal) principal = &a;
    if (fold == 2)
        for (const auto& a : axes)
            for (const auto& r : rotoreflectionAxes)
                if (a.fold == 2 && sameAxis(a.direction, r)) principal = &a;
    const Eigen::Vector3d z = principal->direction;
    const bool perpendicularTwoFold = std::any_of(axes.begin(), axes.end(), [&](const Axis& a) {
        return a.fold >= 2 && std::abs(a.direction.dot(z)) < kPerpendicular;
    });
    const bool horizontalMirror = std::any_of(mirrors.begin(), mirrors.end(), [&](const Eigen::Vector3d& m) { return sameAxis(m, z); });
    const bool verticalMirror =
        std::any_of(mirrors.begin(), mirrors.end(), [&](const Eigen::Vector3d& m) { return std::abs(m.dot(z)) < kPerpendicular; });
    if (perpendicularTwoFold) return "D" + n + (horizontalMirror ? "h" : verticalMirror ? "d" : "");
    if (horizontalMirror) return "C" + n + "h";
    if (verticalMirror) return "C" + n + "v";
    if (std::any_of(rotoreflectionAxes.begin(), rotoreflectionAxes.end(), [&](const Eigen::Vector3d& r) { return sameAxis(r, z); }))
        return "S" + std::to_string(2 * fold);
    return "C" + n;
}

}  // namespace symcompress
