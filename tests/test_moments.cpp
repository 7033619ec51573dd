// The moments engine against ground truth derived independently: brute-force quadrature of
// |s x w|^(2p) over the triangles, orthonormality of the harmonics on the sphere, the action of
// rotations and reflections, and the critical points that Theorem 1 of the paper predicts.
#include "sample_scenes.hpp"
#include "symcompress/detail/congruence_descriptor.hpp"
#include "symcompress/detail/moments.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/detail/spherical_harmonics.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace symcompress;
using samples::randomRotation;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d randomDirection(std::mt19937_64& random) {
    std::normal_distribution<double> normal;
    Eigen::Vector3d w;
    do w = samples::drawnVector([&] { return normal(random); });
    while (w.norm() < 1e-3);
    return w.normalized();
}

// A random rotation, times a reflection when `reflect`.
Eigen::Matrix3d randomOrthogonal(std::mt19937_64& random, bool reflect) {
    Eigen::Matrix3d q = randomRotation(random);
    if (reflect) q.col(0) = -q.col(0);
    return q;
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Matrix3d& linear, const Eigen::Vector3d& shift) {
    TriangleMesh result = mesh;
    for (auto& p : result.positions) p = linear * p + shift;
    // Keep the outward orientation under reflections (the moments do not depend on it).
    if (linear.determinant() < 0)
        for (auto& t : result.triangles) std::swap(t[1], t[2]);
    return result;
}

// Integral over the triangles of f(s - centroid), by a Duffy-collapsed Gauss product rule on each of the
// 4 sub-triangles of every triangle: exact for the polynomial integrands used here (degree <= 16 needs
// 10 nodes per direction; 12 are used), but evaluating |s x w|^(2p) directly at each point.
template <class F>
double bruteForceIntegral(const TriangleMesh& mesh, const Eigen::Vector3d& centroid, F&& f) {
    std::vector<double> x, wx;
    gaussLegendre(12, x, wx);
    double sum = 0;
    auto integrateTriangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        const double area2 = (b - a).cross(c - a).norm();  // twice the area
        double total = 0;
        for (std::size_t i = 0; i < x.size(); ++i)
            for (std::size_t j = 0; j < x.size(); ++j) {
                const double u = 0.5 * (x[i] + 1), v = 0.5 * (x[j] + 1);
                // (u, v) in the unit square -> (u, (1 - u) v) in the reference triangle, Jacobian (1 - u).
                const Eigen::Vector3d s = a + u * (b - a) + (1 - u) * v * (c - a);
                total += 0.25 * wx[i] * wx[j] * (1 - u) * f(s - centroid);
            }
        return total * area2;
    };
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const Eigen::Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
        sum += integrateTriangle(a, ab, ca) + integrateTriangle(ab, b, bc) + integrateTriangle(ca, bc, c) +
               integrateTriangle(ab, bc, ca);
    }
    return sum;
}

Eigen::Vector3d bruteForceCentroid(const TriangleMesh& mesh) {
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double area = 0;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const double triangleArea = 0.5 * (b - a).cross(c - a).norm();
        weighted += triangleArea * (a + b + c) / 3;
        area += triangleArea;
    }
    return weighted / area;
}

// A closed surface with no symmetry at all, away from the origin: a dodecahedron with one vertex pulled
// out, fanned from random points, rotated and shifted.
TriangleMesh asymmetricSurface() {
    Polyhedron solid = makeDodecahedron();
    for (auto i : solid.faces[0]) solid.vertices[i] *= 1.2;  // the neighbouring faces bend: still a closed surface
    TriangleMesh mesh = triangulateWithRandomFanPoints(solid, 7);
    std::mt19937_64 random(11);
    return transformed(mesh, randomRotation(random) * 2.5, Eigen::Vector3d(3, -1, 0.5));
}

double largestCoefficient(const MomentCoefficients& c, int order) {
    double largest = 0;
    for (const auto& band : c.bands[order / 2 - 1]) largest = std::max(largest, band.cwiseAbs().maxCoeff());
    return largest;
}

}  // namespace

TEST_CASE("Gauss-Legendre rules integrate polynomials of degree 2n - 1 exactly", "[moments]") {
    for (int n : {1, 5, 12, 30}) {
        std::vector<double> x, w;
        gaussLegendre(n, x, w);
        for (int k = 0; k <= 2 * n - 1; ++k) {
            double sum = 0;
            for (int i = 0; i < n; ++i) sum += w[i] * std::pow(x[i], k);
            const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
            INFO("n = " << n << ", x^" << k);
            CHECK(std::abs(sum - exact) < 1e-14);
        }
    }
}

TEST_CASE("Spherical harmonics are orthonormal up to degree 20 and match their solid-harmonic polynomials",
          "[moments]") {
    const int maxDegree = 20;
    // Product rule on the sphere, exact for the degree-40 products: Gauss-Legendre in cos(theta), uniform in phi.
    std::vector<double> z, wz;
    gaussLegendre(maxDegree + 2, z, wz);
    const int azimuths = 2 * maxDegree + 2;
    const int count = shCount(maxDegree);
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(count, count);
    for (std::size_t i = 0; i < z.size(); ++i)
        for (int j = 0; j < azimuths; ++j) {
            const double phi = 2 * kPi * j / azimuths, r = std::sqrt(1 - z[i] * z[i]);
            const auto y = evaluateSphericalHarmonics(maxDegree, {r * std::cos(phi), r * std::sin(phi), z[i]});
            const Eigen::Map<const Eigen::VectorXd> v(y.data(), count);
            gram += (wz[i] * 2 * kPi / azimuths) * v * v.transpose();
        }
    CHECK((gram - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff() < 1e-12);

    // Closed forms of the first bands (no Condon-Shortley phase).
    const Eigen::Vector3d w = Eigen::Vector3d(0.3, -0.5, 0.7).normalized();
    const auto y = evaluateSphericalHarmonics(2, w);
    const double c1 = std::sqrt(3 / (4 * kPi));
    CHECK(y[shIndex(0, 0)] == Approx(0.5 / std::sqrt(kPi)).epsilon(1e-14));
    CHECK(y[shIndex(1, -1)] == Approx(c1 * w.y()).epsilon(1e-14));
    CHECK(y[shIndex(1, 0)] == Approx(c1 * w.z()).epsilon(1e-14));
    CHECK(y[shIndex(1, 1)] == Approx(c1 * w.x()).epsilon(1e-14));
    CHECK(y[shIndex(2, 0)] == Approx(std::sqrt(5 / (16 * kPi)) * (3 * w.z() * w.z() - 1)).epsilon(1e-13));

    std::mt19937_64 random(1);
    for (int trial = 0; trial < 10; ++trial) {
        const Eigen::Vector3d u = randomDirection(random);
        const auto values = evaluateSphericalHarmonics(maxDegree, u);
        for (int l = 0; l <= maxDegree; ++l)
            for (int m = -l; m <= l; ++m) {
                INFO("l = " << l << ", m = " << m);
                CHECK(std::abs(solidHarmonic(l, m)(u) - values[shIndex(l, m)]) < 1e-12);
            }
    }
}

TEST_CASE("Rotating SH coefficients equals evaluating at the rotated direction, reflections included",
          "[moments]") {
    std::mt19937_64 random(2);
    std::uniform_real_distribution<double> uniform(-1, 1);
    for (int trial = 0; trial < 8; ++trial) {
        const Eigen::Matrix3d q = randomOrthogonal(random, trial % 2 == 1);
        for (int l : {0, 1, 2, 5, 8, 13, 20}) {
            Eigen::VectorXd c(2 * l + 1);
            for (int m = 0; m <= 2 * l; ++m) c[m] = uniform(random);
            const Eigen::VectorXd rotated = shRotationMatrix(l, q) * c;
            for (int k = 0; k < 10; ++k) {
                const Eigen::Vector3d w = randomDirection(random);
                const auto yw = evaluateSphericalHarmonics(l, w), yq = evaluateSphericalHarmonics(l, q.transpose() * w);
                double lhs = 0, rhs = 0;
                for (int m = -l; m <= l; ++m) {
                    lhs += rotated[m + l] * yw[shIndex(l, m)];
                    rhs += c[m + l] * yq[shIndex(l, m)];
                }
                INFO("l = " << l << ", reflection = " << (trial % 2));
                CHECK(std::abs(lhs - rhs) < 1e-12 * c.norm() * (2 * l + 1));
            }
        }
    }
}

TEST_CASE("Moments from the coefficients equal brute-force integrals of |s x w|^2p", "[moments]") {
    const TriangleMesh mesh = asymmetricSurface();
    MomentOptions options;
    options.maxOrder = 16;
    const MomentCoefficients coefficients = computeMomentCoefficients(mesh, options);
    const Eigen::Vector3d centroid = bruteForceCentroid(mesh);
    CHECK((coefficients.centroid - centroid).norm() < 1e-13 * centroid.norm());

    std::mt19937_64 random(3);
    for (int direction = 0; direction < 100; ++direction) {
        const Eigen::Vector3d w = randomDirection(random);
        for (int order = 2; order <= 16; order += 2) {
            const double expected = bruteForceIntegral(
                mesh, centroid, [&](const Eigen::Vector3d& s) { return std::pow(s.cross(w).squaredNorm(), order / 2); });
            const double actual = evaluateMoment(coefficients, order, w);
            INFO("order " << order << ", direction " << w.transpose());
            CHECK(std::abs(actual - expected) <= 1e-10 * expected);
            // The polynomial form (used for the derivatives) agrees with the SH sum.
            CHECK(std::abs(MomentFunction(coefficients, order).value(w) - expected) <= 1e-10 * expected);
        }
    }
}

TEST_CASE("A moment function's bound holds on the sphere, and is reached by a thin rod along its length",
          "[moments]") {
    auto largestSampled = [](const MomentFunction& f) {
        std::mt19937_64 random(5);
        double largest = 0;
        for (int direction = 0; direction < 2000; ++direction) largest = std::max(largest, f.value(randomDirection(random)));
        return largest;
    };
    MomentOptions options;
    options.maxOrder = 16;
    const MomentCoefficients shape = computeMomentCoefficients(asymmetricSurface(), options);
    // A thin box along x: |s x w| = |s| for w across it, so the bound is nearly reached.
    Polyhedron rod = makeCube();
    for (Eigen::Vector3d& v : rod.vertices) v = v.cwiseProduct(Eigen::Vector3d(10, 1e-3, 1e-3));
    const MomentCoefficients thin = computeMomentCoefficients(triangulateWithRandomFanPoints(rod, 3), options);
    for (int order = 2; order <= 16; order += 2) {
        INFO("order " << order);
        const MomentFunction f(shape, order), g(thin, order);
        CHECK(largestSampled(f) <= f.largestValue());
        CHECK(largestSampled(g) <= g.largestValue());
        CHECK(largestSampled(g) >= 0.99 * g.largestValue());
    }
}

TEST_CASE("The coefficients do not depend on the tessellation", "[moments]") {
    MomentOptions options;
    options.maxOrder = 16;
    for (const Polyhedron& solid : {makeCube(), makeIcosahedron(), makePrism(7, 0.8)}) {
        const MomentCoefficients fanned = computeMomentCoefficients(triangulateFaces(solid), options);
        const MomentCoefficients irregular = computeMomentCoefficients(triangulateWithRandomFanPoints(solid, 5), options);
        CHECK(std::abs(fanned.area - irregular.area) < 1e-12 * fanned.area);
        for (int order = 2; order <= 16; order += 2) {
            const double scale = largestCoefficient(fanned, order);
            for (int l = 0; l <= order / 2; ++l) {
                INFO("order " << order << ", band " << 2 * l);
                CHECK((fanned.bands[order / 2 - 1][l] - irregular.bands[order / 2 - 1][l]).cwiseAbs().maxCoeff() <=
                      1e-10 * scale);
            }
        }
    }
}

TEST_CASE("Transformed coefficients are the coefficients of the transformed surface", "[moments]") {
    const TriangleMesh mesh = asymmetricSurface();
    MomentOptions options;
    options.maxOrder = 12;
    const MomentCoefficients original = computeMomentCoefficients(mesh, options);
    std::mt19937_64 random(4);
    for (int trial = 0; trial < 6; ++trial) {
        const Eigen::Matrix3d q = randomOrthogonal(random, trial % 2 == 1);
        const MomentCoefficients moved = transformMomentCoefficients(original, q);
        const MomentCoefficients direct = computeMomentCoefficients(transformed(mesh, q, Eigen::Vector3d(1, 2, 3)), options);
        for (int order = 2; order <= 12; order += 2) {
            const double scale = largestCoefficient(original, order);
            for (int l = 0; l <= order / 2; ++l)
                CHECK((moved.bands[order / 2 - 1][l] - direct.bands[order / 2 - 1][l]).cwiseAbs().maxCoeff() <= 1e-10 * scale);
            const Eigen::Vector3d w = randomDirection(random);
            const double expected = evaluateMoment(original, order, q.transpose() * w);
            CHECK(std::abs(evaluateMoment(moved, order, w) - expected) <= 1e-12 * expected);
        }
    }
}

TEST_CASE("The congruence descriptor is invariant under isometries and tells modified shapes apart",
          "[moments][congruence]") {
    const TriangleMesh mesh = asymmetricSurface();
    MomentOptions options;
    options.maxOrder = 16;
    const CongruenceDescriptor reference = computeCongruenceDescriptor(computeMomentCoefficients(mesh, options));
    REQUIRE(int(reference.shape.size()) == CongruenceDescriptor::bandCount(16));

    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> uniform(-10, 10);
    for (int trial = 0; trial < 10; ++trial) {
        const Eigen::Matrix3d q = randomOrthogonal(random, trial % 2 == 1);
        const TriangleMesh moved = transformed(mesh, q, samples::drawnVector([&] { return uniform(random); }));
        // Retessellated as well: congruent tiles need not share their triangles.
        const CongruenceDescriptor other = computeCongruenceDescriptor(computeMomentCoefficients(moved, options));
        CHECK(descriptorDifference(reference, other) < 1e-10);
    }

    // Paper Fig. 6: a slightly modified copy (one vertex moved by 1% of the size) differs clearly.
    TriangleMesh modified = mesh;
    const Eigen::Vector3d centroid = reference.rmsRadius * Eigen::Vector3d::UnitX();
    modified.positions[0] += 0.01 * centroid;
    const double modifiedDifference =
        descriptorDifference(reference, computeCongruenceDescriptor(computeMomentCoefficients(modified, options)));
    CHECK(modifiedDifference > 1e-4);

    // A scaled copy has the same shape entries but another size: not congruent.
    const TriangleMesh scaled = transformed(mesh, 1.01 * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const CongruenceDescriptor scaledDescriptor = computeCongruenceDescriptor(computeMomentCoefficients(scaled, options));
    CHECK(descriptorDifference(reference, scaledDescriptor) > 1e-3);
    for (std::size_t i = 0; i < reference.shape.size(); ++i)
        CHECK(std::abs(reference.shape[i] - scaledDescriptor.shape[i]) <= 1e-10 * (1 + reference.shape[i]));
}

namespace {

// Whether the orthogonal map q sends the vertex set of a convex polyhedron onto itself (which, for a convex
// polyhedron, is the same as being one of its symmetries).
bool isSymmetry(const Polyhedron& solid, const Eigen::Matrix3d& q) {
    for (const auto& v : solid.vertices) {
        bool found = false;
        for (const auto& u : solid.vertices) found = found || (q * v - u).norm() < 1e-9;
        if (!found) return false;
    }
    return true;
}

// Directions that are rotation axes or mirror normals of the solid, found by trying vertex, face-centre,
// edge-midpoint and edge directions (and their horizontal parts, for prisms) against the vertex set.
std::vector<Eigen::Vector3d> symmetryDirections(const Polyhedron& solid) {
    std::vector<Eigen::Vector3d> tries{Eigen::Vector3d::UnitZ()};
    for (const auto& v : solid.vertices) tries.push_back(v);
    for (const auto& face : solid.faces) {
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (auto i : face) centre += solid.vertices[i];
        tries.push_back(centre);
        for (std::size_t k = 0; k < face.size(); ++k) {
            const Eigen::Vector3d &a = solid.vertices[face[k]], &b = solid.vertices[face[(k + 1) % face.size()]];
            tries.push_back(a + b);
            tries.push_back(a - b);
        }
    }
    const std::size_t original = tries.size();
    for (std::size_t i = 0; i < original; ++i) tries.push_back(Eigen::Vector3d(tries[i].x(), tries[i].y(), 0));

    std::vector<Eigen::Vector3d> axes;
    for (Eigen::Vector3d d : tries) {
        if (d.norm() < 1e-9) continue;
        d.normalize();
        bool known = false;
        for (const auto& a : axes) known = known || std::abs(std::abs(a.dot(d)) - 1) < 1e-12;
        if (known) continue;
        const Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity() - 2 * d * d.transpose();
        bool symmetric = isSymmetry(solid, mirror);
        for (int n = 2; n <= 12 && !symmetric; ++n)
            symmetric = isSymmetry(solid, Eigen::AngleAxisd(2 * kPi / n, d).toRotationMatrix());
        if (symmetric) axes.push_back(d);
    }
    return axes;
}

}  // namespace

TEST_CASE("Symmetry axes are critical points of every moment function (Theorem 1)", "[moments]") {
    struct Case {
        const char* name;
        Polyhedron solid;
        std::size_t expectedAxes;  // rotation axes and mirror normals, up to sign
    };
    const std::vector<Case> cases{
        {"tetrahedron", makeTetrahedron(), 3 + 4 + 6},          // 3 two-fold, 4 three-fold, 6 mirrors
        {"cube", makeCube(), 3 + 4 + 6},                        // 4-fold, 3-fold, 2-fold (= mirror normals)
        {"icosahedron", makeIcosahedron(), 6 + 10 + 15},        // 5-, 3-, 2-fold (the 15 mirrors are the 2-fold axes)
        {"hexagonal prism", makePrism(6, 0.7), 1 + 6},          // 6-fold, six 2-fold (also the mirror normals)
        {"pentagonal prism", makePrism(5, 1.3), 1 + 5 + 5},     // 5-fold, five 2-fold, five mirror normals
        {"square antiprism", makeAntiprism(4, 1.1), 1 + 4 + 4},
    };
    std::mt19937_64 random(6);
    for (const auto& c : cases) {
        const auto axes = symmetryDirections(c.solid);
        INFO(c.name);
        REQUIRE(axes.size() == c.expectedAxes);
        for (int trial = 0; trial < 3; ++trial) {
            const Eigen::Matrix3d q = randomRotation(random);
            const TriangleMesh mesh = transformed(triangulateWithRandomFanPoints(c.solid, trial), q, Eigen::Vector3d(0.3, 0.1, -2));
            MomentOptions options;
            options.maxOrder = 10;
            const MomentCoefficients coefficients = computeMomentCoefficients(mesh, options);
            for (int order = 4; order <= 10; order += 2) {
                const MomentFunction moment(coefficients, order);
                // A direction off every axis gives the scale of a typical gradient.
                double typical = 0;
                for (int k = 0; k < 20; ++k) typical = std::max(typical, moment.tangentialGradient(randomDirection(random)).norm());
                for (const auto& axis : axes) {
                    const Eigen::Vector3d w = q * axis;
                    INFO("order " << order << ", axis " << axis.transpose() << ", typical gradient " << typical);
                    CHECK(moment.tangentialGradient(w).norm() <= 1e-12 * std::max(typical, moment.value(w)));
                }
            }
        }
    }
}

TEST_CASE("Tangential gradient and Hessian match finite differences along great circles", "[moments]") {
    const TriangleMesh mesh = asymmetricSurface();
    MomentOptions options;
    options.maxOrder = 16;
    const MomentCoefficients coefficients = computeMomentCoefficients(mesh, options);
    std::mt19937_64 random(8);
    for (int order = 2; order <= 16; order += 2) {
        const MomentFunction moment(coefficients, order);
        for (int trial = 0; trial < 10; ++trial) {
            const Eigen::Vector3d w = randomDirection(random);
            const Eigen::Vector3d u = w.cross(randomDirection(random)).normalized();  // tangent at w
            auto along = [&](double t) { return moment.value(std::cos(t) * w + std::sin(t) * u); };
            const double h = 1e-4, f0 = along(0);
            const double first = (along(h) - along(-h)) / (2 * h);
            const double second = (along(h) - 2 * f0 + along(-h)) / (h * h);
            const Eigen::Vector3d gradient = moment.tangentialGradient(w);
            const Eigen::Matrix3d hessian = moment.tangentialHessian(w);
            INFO("order " << order);
            CHECK(std::abs(gradient.dot(w)) <= 1e-12 * f0 * order);
            CHECK(std::abs(gradient.dot(u) - first) <= 1e-6 * f0 * order);
            CHECK(std::abs(u.dot(hessian * u) - second) <= 1e-5 * f0 * order * order);
            CHECK((hessian * w).norm() <= 1e-12 * f0 * order * order);
            CHECK((hessian - hessian.transpose()).norm() <= 1e-12 * f0 * order * order);
        }
    }
}
