// The fundamental region of a symmetric tile (paper 7.1, docs/fundamental-regions.md): checks, the choice of
// the seed and frame, the clipping, and the inverse (rebuilding the tile from the region).
#include "symcompress/detail/fundamental_region.hpp"

#include "fundamental_region_parts.hpp"
#include "symcompress/scene_ops.hpp"
#include "symmetry/point_group_closure.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace symcompress {

namespace {

using region_detail::DirichletCone;

[[noreturn]] void fail(const std::string& problem) {
    throw std::invalid_argument("computeFundamentalRegion: " + problem);
}

double triangleArea(const Primitive& primitive, const Triangle& triangle) {
    const Eigen::Vector3d& a = primitive.positions[triangle[0]];
    return 0.5 * (primitive.positions[triangle[1]] - a).cross(primitive.positions[triangle[2]] - a).norm();
}

void checkTile(const Primitive& tile) {
    const std::size_t count = tile.positions.size();
    if (count == 0 || tile.triangles.empty()) fail("the tile is empty");
    if (!tile.normals.empty() && tile.normals.size() != count)
        fail("the tile has a normal count other than its vertex count");
    if (!tile.texcoords.empty() && tile.texcoords.size() != count)
        fail("the tile has a texcoord count other than its vertex count");
    if (!tile.colors.empty() && tile.colors.size() != count)
        fail("the tile has a color count other than its vertex count");
    for (const Eigen::Vector3d& p : tile.positions)
        if (!p.allFinite()) fail("the tile has a non-finite position");
    for (const Eigen::Vector3d& n : tile.normals)
        if (!n.allFinite()) fail("the tile has a non-finite normal");
    for (const Eigen::Vector2d& t : tile.texcoords)
        if (!t.allFinite()) fail("the tile has a non-finite texcoord");
    for (const Eigen::Vector4d& c : tile.colors)
        if (!c.allFinite()) fail("the tile has a non-finite color");
    for (const VertexAttribute& attribute : tile.attributes)
        if (attribute.count() != count || attribute.values.size() != count * std::size_t(attribute.components))
            fail("the tile's " + attribute.name + " has a count other than its vertex count");
    double area = 0;
    for (const Triangle& triangle : tile.triangles) {
        for (std::uint32_t corner : triangle)
            if (corner >= count) fail("triangle index " + std::to_string(corner) + " is out of range");
        area += triangleArea(tile, triangle);
    }
    if (!(area > 0)) fail("the tile has zero area");
}

std::size_t findElement(const std::vector<Eigen::Matrix3d>& group, const Eigen::Matrix3d& element, double tolerance) {
    for (std::size_t i = 0; i < group.size(); ++i)
        if ((group[i] - element).cwiseAbs().maxCoeff() <= tolerance) return i;
    return group.size();
}

// Returns the index of the identity.
std::size_t checkGroup(const std::vector<Eigen::Matrix3d>& group, double tolerance) {
    if (group.empty()) fail("the group is empty (it must contain at least the identity)");
    for (std::size_t i = 0; i < group.size(); ++i) {
        const Eigen::Matrix3d& g = group[i];
        if (!g.allFinite()) fail("group matrix " + std::to_string(i) + " is not finite");
        const double deviation = (g.transpose() * g - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (deviation > tolerance)
            fail("group matrix " + std::to_string(i) +
                 " is not orthogonal (|g^T g - I| = " + std::to_string(deviation) + ")");
        if (findElement(group, g, tolerance) != i)
            fail("group matrix " + std::to_string(i) + " repeats an earlier one");
    }
    const std::size_t identity = findElement(group, Eigen::Matrix3d::Identity(), tolerance);
    if (identity == group.size()) fail("the group does not contain the identity");
    // Products of matrices within `tolerance` of orthogonal ones stay within a few tolerances. An element within
    // 4 tolerances in every entry is within 12 in the Frobenius norm: the index finds it among a few (C360v: 518400
    // products, each compared with every element, took 0.35 s).
    const ElementIndex index(group, 12 * tolerance);
    for (std::size_t i = 0; i < group.size(); ++i)
        for (std::size_t j = 0; j < group.size(); ++j)
            if (const Eigen::Matrix3d product = group[i] * group[j];
                index.find(product, [&](const Eigen::Matrix3d& element) {
                    return (element - product).cwiseAbs().maxCoeff() <= 4 * tolerance;
                }) == SIZE_MAX)
                fail("the group is not closed: the product of matrices " + std::to_string(i) + " and " +
                     std::to_string(j) + " is not in it");
    return identity;
}

// The elements of G that act on the tile: all of G, unless the tile is flat and G holds the mirror in its
// plane, which fixes every point; then the subgroup preserving the tile's normal (fundamental_region.hpp).
std::vector<Eigen::Matrix3d> actingElements(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                            std::size_t identity, const Eigen::Vector3d& centre, double tolerance) {
    for (std::size_t i = 0; i < group.size(); ++i) {
        if (i == identity) continue;
        bool fixesAll = true;
        for (const Eigen::Vector3d& p : tile.positions) {
            if ((group[i] * (p - centre) - (p - centre)).norm() > tolerance) {
                fixesAll = false;
                break;
            }
        }
        if (!fixesAll) continue;
        // Only a mirror fixes a surface of non-zero area pointwise.
        const std::optional<Eigen::Vector3d> normal = region_detail::elementAxis(group[i]);
        if (group[i].determinant() > 0 || !normal)
            fail("a group element other than a mirror fixes every vertex of the tile");
        std::vector<Eigen::Matrix3d> acting;
        for (const Eigen::Matrix3d& g : group)
            if (normal->dot(g * *normal) > 0) acting.push_back(g);
        return acting;
    }
    return group;
}

// Cone normals within rounding of a coordinate axis become that axis exactly, so that snapping sets the
// coordinate exactly.
void roundAxisNormals(DirichletCone& cone) {
    for (Eigen::Vector3d& n : cone.normals) {
        Eigen::Index axis;
        const double largest = n.cwiseAbs().maxCoeff(&axis);
        if (largest > 1 - 1e-12) {
            const double sign = n[axis] > 0 ? 1.0 : -1.0;
            n.setZero();
            n[axis] = sign;
        }
    }
}

Eigen::Matrix3d roundSignedPermutation(const Eigen::Matrix3d& matrix) { return matrix.array().round().matrix(); }

// The tile in the frame (origin at the centre, axes the columns of `rotation`).
Primitive toFrame(const Primitive& tile, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre) {
    Primitive local = tile;
    for (Eigen::Vector3d& p : local.positions) p = rotation.transpose() * (p - centre);
    for (Eigen::Vector3d& n : local.normals) n = rotation.transpose() * n;
    for (VertexAttribute& attribute : local.attributes)
        transformAttribute(attribute, rotation.transpose(), rotation.transpose(), false);
    return local;
}

// R of whole triangles where the tessellation allows it (`orbits`), else S ∩ F clipped, which in
// RegionTriangles::Whole may cut no triangle.
void cutOrKeepWhole(FundamentalRegion& result, const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                    const Eigen::Vector3d& centre, const Eigen::Vector3d& seed, const DirichletCone& cone,
                    double snapTolerance, const std::optional<region_detail::TriangleOrbits>& orbits,
                    RegionTriangles triangles) {
    if (orbits) {
        result.region = region_detail::wholeTriangleRegion(tile, *orbits, nonIdentity, centre, seed);
        result.wholeTriangles = true;
        return;
    }
    region_detail::ClippedRegion clipped = region_detail::clipToCone(tile, cone, snapTolerance);
    if (triangles == RegionTriangles::Whole &&
        (clipped.trianglesCut > 0 ||
         clipped.region.triangles.size() * (nonIdentity.size() + 1) != tile.triangles.size()))
        fail(
            "the group does not map the tile's triangles onto one another without fixing one, and its planes "
            "cut triangles or leave more on one side: they cannot be kept whole");
    result.region = std::move(clipped.region);
    result.trianglesCut = clipped.trianglesCut;
}

}  // namespace

FundamentalRegion computeFundamentalRegion(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                           const Eigen::Vector3d& centre, const RegionOptions& options) {
    checkTile(tile);
    if (!centre.allFinite()) fail("the centre is not finite");
    if (!(options.snapTolerance >= 0) || !(options.groupTolerance >= 0)) fail("tolerances must be non-negative");
    const std::size_t identity = checkGroup(group, options.groupTolerance);

    FundamentalRegion result;
    result.centre = centre;
    if (group.size() == 1) {  // nothing to fold: the tile is its own region
        result.region = tile;
        result.instances = group;
        result.seed = Eigen::Vector3d::UnitX();
        result.wholeTriangles = true;
        return result;
    }

    double radius = 0;
    for (const Eigen::Vector3d& p : tile.positions) radius = std::max(radius, (p - centre).norm());
    const double tolerance = options.snapTolerance * radius;

    result.instances = actingElements(tile, group, identity, centre, std::max(tolerance, 1e-12 * radius));
    std::vector<Eigen::Matrix3d> nonIdentity;
    for (const Eigen::Matrix3d& g : result.instances)
        if ((g - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > options.groupTolerance) nonIdentity.push_back(g);
    if (nonIdentity.empty()) {
        result.region = tile;
        result.seed = Eigen::Vector3d::UnitX();
        result.wholeTriangles = true;
        return result;
    }

    std::optional<region_detail::TriangleOrbits> orbits;
    if (options.triangles != RegionTriangles::Cut)
        orbits = region_detail::triangleOrbits(tile, nonIdentity, centre, options.vertexTolerance * radius);
    if (!orbits && options.triangles == RegionTriangles::OneOfEachOrbit)  // before the seed, which takes longer
        fail("the group does not map the tile's triangles onto one another without fixing one");

    const region_detail::SeedChoice choice = region_detail::chooseSeed(tile, nonIdentity, centre, tolerance, options);
    if (!(choice.seed.norm() > 0)) fail("no seed point is free of the group's fixed sets");
    result.seed = choice.seed;

    if (options.frame == RegionFrame::Tile) {
        cutOrKeepWhole(result, tile, nonIdentity, centre, choice.seed, choice.cone, tolerance, orbits,
                       options.triangles);
        result.facetNormals = choice.cone.normals;
        return result;
    }

    // Aligned: the same cone, built again from the group and seed expressed in the frame, where signed
    // permutations are exact and planes on coordinate planes have exactly axial normals.
    const region_detail::AlignedFrame frame = region_detail::chooseAlignedFrame(nonIdentity, choice.cone.normals);
    const Eigen::Matrix3d& rotation = frame.rotation;
    std::vector<Eigen::Matrix3d> localGroup;
    for (const Eigen::Matrix3d& g : nonIdentity) {
        const Eigen::Matrix3d local = rotation.transpose() * g * rotation;
        localGroup.push_back(frame.signedPermutation ? roundSignedPermutation(local) : local);
    }
    DirichletCone localCone =
        region_detail::dirichletCone(localGroup, rotation.transpose() * choice.seed, Eigen::Vector3d::Zero());
    roundAxisNormals(localCone);
    cutOrKeepWhole(result, toFrame(tile, rotation, centre), localGroup, Eigen::Vector3d::Zero(),
                   rotation.transpose() * choice.seed, localCone, tolerance, orbits, options.triangles);
    for (const Eigen::Vector3d& n : localCone.normals) result.facetNormals.push_back(rotation * n);
    result.regionToTile.topLeftCorner<3, 3>() = rotation;
    result.regionToTile.topRightCorner<3, 1>() = centre;
    result.signedPermutationFrame = frame.signedPermutation;
    return result;
}

Eigen::Matrix4d instanceTransform(const FundamentalRegion& region, std::size_t k) {
    if (k >= region.instances.size()) throw std::out_of_range("instanceTransform: no instance " + std::to_string(k));
    const Eigen::Matrix3d& g = region.instances[k];
    Eigen::Matrix4d about = Eigen::Matrix4d::Identity();  // x -> centre + g (x - centre)
    about.topLeftCorner<3, 3>() = g;
    about.topRightCorner<3, 1>() = region.centre - g * region.centre;
    return about * region.regionToTile;
}

Primitive rebuildFromRegion(const FundamentalRegion& region) {
    const Primitive& part = region.region;
    Primitive whole;
    whole.material = part.material;
    for (std::size_t k = 0; k < region.instances.size(); ++k) {
        const Eigen::Matrix4d transform = instanceTransform(region, k);
        const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
        const Eigen::Vector3d offset = transform.topRightCorner<3, 1>();
        const auto base = static_cast<std::uint32_t>(whole.positions.size());
        for (const Eigen::Vector3d& p : part.positions) whole.positions.push_back(linear * p + offset);
        for (const Eigen::Vector3d& n : part.normals) whole.normals.push_back((linear * n).normalized());
        whole.texcoords.insert(whole.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
        whole.colors.insert(whole.colors.end(), part.colors.begin(), part.colors.end());
        if (k == 0)
            for (const VertexAttribute& attribute : part.attributes)
                whole.attributes.push_back(attribute.withoutValues());
        for (std::size_t a = 0; a < part.attributes.size(); ++a) {
            VertexAttribute turned = part.attributes[a];
            transformAttribute(turned, linear, linear, false);
            whole.attributes[a].values.insert(whole.attributes[a].values.end(), turned.values.begin(),
                                              turned.values.end());
        }
        // A mirror reverses orientation; reversing the corner order makes the copy face outward again.
        const bool mirror = linear.determinant() < 0;
        for (const Triangle& t : part.triangles) {
            if (mirror)
                whole.triangles.push_back({base + t[0], base + t[2], base + t[1]});
            else
                whole.triangles.push_back({base + t[0], base + t[1], base + t[2]});
        }
    }
    return whole;
}

}  // namespace symcompress
