#include "triangle_bvh.hpp"

#include <algorithm>

namespace symcompress {

Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denominator = va + vb + vc;
    if (!(denominator > 0)) return a;  // no area: a is as good as any corner
    return a + (vb / denominator) * ab + (vc / denominator) * ac;
}

namespace {
constexpr std::uint32_t kLeafSize = 4;
}

TriangleBvh::TriangleBvh(const TriangleMesh& mesh) : mesh_(mesh) {
    const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
    if (count == 0) return;
    order_.resize(count);
    std::vector<Eigen::Vector3d> centers(count);
    for (std::uint32_t t = 0; t < count; ++t) {
        order_[t] = t;
        const Triangle& tri = mesh.triangles[t];
        centers[t] = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3;
    }
    nodes_.reserve(2 * (count / kLeafSize + 1));
    nodes_.emplace_back();
    build(0, 0, count, centers);
    corners_.reserve(3 * std::size_t(count));
    for (const std::uint32_t t : order_)
        for (auto v : mesh.triangles[t]) corners_.push_back(mesh.positions[v]);
}

void TriangleBvh::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end,
                        std::vector<Eigen::Vector3d>& centers) {
    if (end - begin <= kLeafSize) {
        Eigen::AlignedBox3d box;
        for (std::uint32_t i = begin; i < end; ++i)
            for (auto v : mesh_.triangles[order_[i]]) box.extend(mesh_.positions[v]);
        nodes_[node].box = box;
        nodes_[node].first = begin;
        nodes_[node].count = end - begin;
        return;
    }
    // An inner node's box is the union of its children's (found below, bottom up: each corner is read once,
    // not once per level); the split needs only the box of the centers.
    Eigen::AlignedBox3d centerBox;
    for (std::uint32_t i = begin; i < end; ++i) centerBox.extend(centers[order_[i]]);
    int axis;
    centerBox.sizes().maxCoeff(&axis);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y) { return centers[x][axis] < centers[y][axis]; });
    const auto children = static_cast<std::uint32_t>(nodes_.size());
    nodes_[node].first = children;
    nodes_.emplace_back();
    nodes_.emplace_back();
    build(children, begin, middle, centers);
    build(children + 1, middle, end, centers);
    nodes_[node].box = nodes_[children].box.merged(nodes_[children + 1].box);
}

double TriangleBvh::squaredDistance(const Eigen::Vector3d& p, double bound, Eigen::Vector3d* closest,
                                    std::uint32_t* triangle, const Eigen::Vector3d* facing) const {
    return search<false>(p, bound, 0, closest, triangle, facing);
}

double TriangleBvh::squaredDistanceAbove(const Eigen::Vector3d& p, double enough, double bound) const {
    return search<true>(p, bound, enough, nullptr, nullptr, nullptr);
}

template <bool kStopWithinEnough>
double TriangleBvh::search(const Eigen::Vector3d& p, double bound, double enough, Eigen::Vector3d* closest,
                           std::uint32_t* triangle, const Eigen::Vector3d* facing) const {
    if (nodes_.empty()) return bound;
    double best = bound;
    // Each node with its box's distance to p, computed once: when it is pushed (to order the children).
    struct Entry {
        std::uint32_t node;
        double distance;
    };
    Entry stack[128];
    int top = 0;
    stack[top++] = {0, nodes_[0].box.squaredExteriorDistance(p)};
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.distance >= best) continue;
        const Node& node = nodes_[entry.node];
        if (node.count > 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                const Eigen::Vector3d& a = corners_[3 * std::size_t(i)];
                const Eigen::Vector3d& b = corners_[3 * std::size_t(i) + 1];
                const Eigen::Vector3d& c = corners_[3 * std::size_t(i) + 2];
                if (facing && (b - a).cross(c - a).dot(*facing) <= 0) continue;
                // The triangle's box first: no nearer than the best so far, the triangle is not either.
                const Eigen::Vector3d outside =
                    (a.cwiseMin(b).cwiseMin(c) - p).cwiseMax(p - a.cwiseMax(b).cwiseMax(c)).cwiseMax(0.0);
                if (outside.squaredNorm() >= best) continue;
                const Eigen::Vector3d q = closestPointOnTriangle(p, a, b, c);
                const double d = (q - p).squaredNorm();
                if (d < best) {
                    best = d;
                    if (closest) *closest = q;
                    if (triangle) *triangle = order_[i];
                    if (kStopWithinEnough && best <= enough) return best;
                }
            }
            continue;
        }
        // Nearer child last, so that it is searched first.
        const std::uint32_t a = node.first, b = node.first + 1;
        const double aDistance = nodes_[a].box.squaredExteriorDistance(p),
                     bDistance = nodes_[b].box.squaredExteriorDistance(p);
        const bool aNearer = aDistance < bDistance;
        stack[top++] = aNearer ? Entry{b, bDistance} : Entry{a, aDistance};
        stack[top++] = aNearer ? Entry{a, aDistance} : Entry{b, bDistance};
    }
    return best;
}

}  // namespace symcompress
