#include "x3d_faces.hpp"

#include <algorithm>
#include <map>
#include <tuple>

namespace symcompress::x3d {
namespace {

// X_ITE leaves out a side triangle whose two spine points are nearer than this (coincident spine points).
constexpr double kCoincident = 1e-7;

Eigen::Vector3d unitOrZero(const Eigen::Vector3d& v) {
    const double length = v.norm();
    return length > 0 ? Eigen::Vector3d(v / length) : Eigen::Vector3d::Zero();
}

// The indices of a strip (fan) split at -1: each run of corners.
std::vector<std::vector<std::int64_t>> runsOf(const std::vector<std::int64_t>& index) {
    std::vector<std::vector<std::int64_t>> runs(1);
    for (std::int64_t i : index) {
        if (i < 0) {
            if (!runs.back().empty()) runs.emplace_back();
        } else {
            runs.back().push_back(i);
        }
    }
    return runs;
}

// A strip's triangles, every second one turned back so that all face as the first.
void addStrip(const std::vector<std::int64_t>& strip, std::vector<Face>& out) {
    for (std::size_t i = 0; i + 2 < strip.size(); ++i)
        out.push_back(i % 2 ? Face{strip[i + 1], strip[i], strip[i + 2]} : Face{strip[i], strip[i + 1], strip[i + 2]});
}

void addFan(const std::vector<std::int64_t>& fan, std::vector<Face>& out) {
    for (std::size_t i = 1; i + 1 < fan.size(); ++i) out.push_back({fan[0], fan[i], fan[i + 1]});
}

template <typename AddRun>
std::vector<Face> countedRuns(const std::vector<std::int64_t>& counts, std::int64_t pointCount, AddRun addRun) {
    std::vector<Face> out;
    std::int64_t first = 0;
    for (std::int64_t count : counts) {
        std::vector<std::int64_t> run;
        for (std::int64_t p = first; p < std::min(first + count, pointCount); ++p) run.push_back(p);
        addRun(run, out);
        first += std::max<std::int64_t>(count, 0);
    }
    return out;
}

// Whether a list's first and last values are equal (an empty one counts as closed), as X_ITE decides whether
// an Extrusion's spine, scales and orientations close.
template <typename T>
bool closes(const std::vector<T>& values) {
    return values.empty() || values.front() == values.back();
}
template <>
bool closes(const std::vector<Eigen::AngleAxisd>& values) {
    return values.empty() ||
           (values.front().axis() == values.back().axis() && values.front().angle() == values.back().angle());
}

// The cross-section plane of each spine point (X3D 4.0, 13.3.5.2) as X_ITE computes it: its x, y and z axes as
// the columns of a rotation, and the spine point. Y follows the spine, Z is normal to the plane of the spine's
// turn; each keeps the previous point's where the spine gives none, and turns no more than a right angle from it.
std::vector<Eigen::Affine3d> crossSectionPlanes(const std::vector<Eigen::Vector3d>& spine) {
    const std::size_t n = spine.size();
    const bool closed = closes(spine);
    Eigen::Vector3d y = Eigen::Vector3d::Zero(), z = Eigen::Vector3d::Zero();
    if (closed) {
        const Eigen::Vector3d& s = spine[0];
        for (std::size_t i = 1; i + 2 < n && y.isZero(0); ++i)
            y = unitOrZero(unitOrZero(spine[i] - s) - unitOrZero(spine[n - 2] - s));
        for (std::size_t i = 0; i + 2 < n && z.isZero(0); ++i)
            z = unitOrZero((spine[i + 1] - spine[i]).cross(spine[n - 2] - spine[i]));
    } else {
        for (std::size_t i = 0; i + 1 < n && y.isZero(0); ++i) y = unitOrZero(spine[i + 1] - spine[i]);
        for (std::size_t i = 1; i + 1 < n && z.isZero(0); ++i)
            z = unitOrZero((spine[i + 1] - spine[i]).cross(spine[i - 1] - spine[i]));
    }
    if (y.isZero(0)) y = Eigen::Vector3d::UnitY();  // every spine point at one place
    if (z.isZero(0)) {  // a straight spine: z turned from the z axis as y is from the y axis
        z = y.dot(Eigen::Vector3d::UnitY()) < 0 && y.cross(Eigen::Vector3d::UnitY()).isZero(0)
                ? Eigen::Vector3d::UnitZ()  // y turned half a turn about the z axis
                : Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), y) * Eigen::Vector3d::UnitZ();
    }
    auto plane = [](const Eigen::Vector3d& y, const Eigen::Vector3d& z, const Eigen::Vector3d& at) {
        Eigen::Affine3d frame = Eigen::Affine3d::Identity();
        frame.linear() << y.cross(z), y, z;
        frame.translation() = at;
        return frame;
    };
    std::vector<Eigen::Affine3d> planes(n);
    planes[0] = plane(y, z, spine[0]);
    // A later point's axes from its neighbours; `previousY`, `previousZ`: the last ones the spine defined.
    Eigen::Vector3d previousY = y, previousZ = z;
    auto follow = [&](Eigen::Vector3d nextY, Eigen::Vector3d nextZ, bool keep) {
        if (previousY.dot(nextY) < 0) nextY = -nextY;
        if (previousZ.dot(nextZ) < 0) nextZ = -nextZ;
        if (nextY.isZero(0))
            nextY = previousY;
        else if (keep)
            previousY = nextY;
        if (nextZ.isZero(0))
            nextZ = previousZ;
        else if (keep)
            previousZ = nextZ;
        return std::pair{nextY, nextZ};
    };
    for (std::size_t i = 1; i + 1 < n; ++i) {
        const Eigen::Vector3d& s = spine[i];
        const auto [yi, zi] = follow(unitOrZero(unitOrZero(spine[i + 1] - s) - unitOrZero(spine[i - 1] - s)),
                                     unitOrZero((spine[i + 1] - s).cross(spine[i - 1] - s)), true);
        planes[i] = plane(yi, zi, s);
    }
    if (closed) {
        planes[n - 1] = planes[0];
    } else {
        const Eigen::Vector3d& s = spine[n - 1];
        const Eigen::Vector3d lastZ =
            n > 2 ? unitOrZero((s - spine[n - 2]).cross(spine[n - 3] - spine[n - 2])) : previousZ;
        const auto [yi, zi] = follow(unitOrZero(s - spine[n - 2]), lastZ, false);
        planes[n - 1] = plane(yi, zi, s);
    }
    return planes;
}

}  // namespace

std::vector<Face> indexedStrips(const std::vector<std::int64_t>& index) {
    std::vector<Face> out;
    for (const auto& strip : runsOf(index)) addStrip(strip, out);
    return out;
}

std::vector<Face> indexedFans(const std::vector<std::int64_t>& index) {
    std::vector<Face> out;
    for (const auto& fan : runsOf(index)) addFan(fan, out);
    return out;
}

std::vector<Face> countedStrips(const std::vector<std::int64_t>& counts, std::int64_t pointCount) {
    return countedRuns(counts, pointCount, addStrip);
}

std::vector<Face> countedFans(const std::vector<std::int64_t>& counts, std::int64_t pointCount) {
    return countedRuns(counts, pointCount, addFan);
}

std::vector<Face> quads(const std::vector<std::int64_t>& corners) {
    std::vector<Face> out;
    for (std::size_t i = 0; i + 3 < corners.size(); i += 4)
        out.push_back({corners[i], corners[i + 1], corners[i + 2], corners[i + 3]});
    return out;
}

Faces elevationGrid(std::int64_t xDimension, std::int64_t zDimension, double xSpacing, double zSpacing,
                    const std::vector<double>& height) {
    Faces out;
    if (xDimension < 2 || zDimension < 2) return out;
    for (std::int64_t z = 0; z < zDimension; ++z)
        for (std::int64_t x = 0; x < xDimension; ++x) {
            const std::size_t i = std::size_t(z * xDimension + x);
            out.points.insert(out.points.end(),
                              {xSpacing * double(x), i < height.size() ? height[i] : 0.0, zSpacing * double(z)});
            out.texcoords.insert(out.texcoords.end(),
                                 {double(x) / double(xDimension - 1), double(z) / double(zDimension - 1)});
        }
    // Each square as X_ITE cuts it, along the diagonal from (x, z) to (x + 1, z + 1): two faces, so that the
    // normals made from a creaseAngle weigh its triangles as the browser's do.
    for (std::int64_t z = 0; z + 1 < zDimension; ++z)
        for (std::int64_t x = 0; x + 1 < xDimension; ++x) {
            const std::int64_t p1 = z * xDimension + x, p2 = p1 + xDimension, p3 = p2 + 1, p4 = p1 + 1;
            const std::int64_t square = z * (xDimension - 1) + x;
            out.faces.push_back({p1, p2, p3});
            out.faces.push_back({p1, p3, p4});
            out.attributeFace.insert(out.attributeFace.end(), {square, square});
        }
    return out;
}

Faces extrusion(const ExtrusionFields& fields) {
    Faces out;
    const auto& spine = fields.spine;
    const auto& section = fields.crossSection;
    const std::size_t spines = spine.size(), sections = section.size();
    if (spines < 2 || sections < 2) return out;

    // Points: spine point n's cross-section is points n * sections to n * sections + sections - 1.
    const std::vector<Eigen::Affine3d> planes = crossSectionPlanes(spine);
    std::vector<Eigen::Vector3d> points;
    for (std::size_t n = 0; n < spines; ++n) {
        Eigen::Affine3d place = planes[n];
        if (!fields.orientation.empty()) place.rotate(fields.orientation[std::min(n, fields.orientation.size() - 1)]);
        if (!fields.scale.empty()) {
            const Eigen::Vector2d& s = fields.scale[std::min(n, fields.scale.size() - 1)];
            place.scale(Eigen::Vector3d(s.x(), 1, s.y()));
        }
        for (const Eigen::Vector2d& c : section) points.push_back(place * Eigen::Vector3d(c.x(), 0, c.y()));
    }
    auto index = [&](std::size_t n, std::size_t k) { return std::int64_t(n * sections + k); };
    auto addPoint = [&](const Eigen::Vector3d& p) {
        out.points.insert(out.points.end(), {p.x(), p.y(), p.z()});
        return std::int64_t(out.points.size() / 3 - 1);
    };
    for (const Eigen::Vector3d& p : points) addPoint(p);
    std::map<std::tuple<std::int64_t, double, double>, std::int64_t> texcoordAt;  // (point, s, t) -> index
    auto addCorner = [&](Face& face, std::int64_t point, double s, double t) {
        face.push_back(point);
        auto [entry, added] = texcoordAt.try_emplace({point, s, t}, std::int64_t(out.texcoords.size() / 2));
        if (added) out.texcoords.insert(out.texcoords.end(), {s, t});
        out.texcoordOfCorner.push_back(entry->second);
    };

    // The sides: between spine points n and n + 1, cross-section points k and k + 1, two triangles; where the
    // spine, its scales and orientations close, the last spine point is the first, and where the cross-section
    // closes, its last point is its first. A side of two coincident points draws nothing, and its corner is
    // the last one before the coincidence along that edge (X_ITE: one point for the normals of a cone's tip).
    const bool closed = closes(spine) && closes(fields.orientation) && closes(fields.scale);
    const bool closedSection = closes(section);
    const double along = double(spines - 1), across = double(sections - 1);
    std::int64_t left = index(0, 0), right = index(0, closedSection ? 0 : sections - 1);
    for (std::size_t n = 0; n + 1 < spines; ++n)
        for (std::size_t k = 0; k + 1 < sections; ++k) {
            const std::size_t n1 = closed && n + 2 == spines ? 0 : n + 1;
            const std::size_t k1 = closedSection && k + 2 == sections ? 0 : k + 1;
            std::int64_t i1 = index(n, k), i2 = index(n, k1), i3 = index(n1, k1), i4 = index(n1, k);
            const bool side1 = (points[std::size_t(i2)] - points[std::size_t(i3)]).norm() >= kCoincident;
            const bool side2 = (points[std::size_t(i4)] - points[std::size_t(i1)]).norm() >= kCoincident;
            if (k == 0) {
                if (side2)
                    left = i1;
                else
                    i1 = left;
            }
            if (k + 2 == sections) {
                if (side1)
                    right = i2;
                else
                    i3 = right;
            }
            const double s0 = double(k) / across, s1 = double(k + 1) / across;
            const double t0 = double(n) / along, t1 = double(n + 1) / along, middle = (t0 + t1) / 2;
            if (side1) {
                Face& face = out.faces.emplace_back();
                addCorner(face, i1, s0, side2 ? t0 : middle);
                addCorner(face, i2, s1, t0);
                addCorner(face, i3, s1, t1);
            }
            if (side2) {
                Face& face = out.faces.emplace_back();
                addCorner(face, i1, s0, t0);
                addCorner(face, i3, s1, side1 ? t1 : middle);
                addCorner(face, i4, s0, t1);
            }
        }

    // The caps: the cross-section (less its closing point) at the first spine point, turned back, and at the
    // last; texture coordinates from the cross-section's box, its longer side 1.
    const std::size_t capPoints = closedSection ? sections - 1 : sections;
    Eigen::Vector2d low = section[0], high = section[0];
    for (const Eigen::Vector2d& c : section) low = low.cwiseMin(c), high = high.cwiseMax(c);
    const double capSize = (high - low).maxCoeff();
    if (!(capSize > 0) || capPoints < 3) return out;
    auto addCap = [&](std::size_t n, bool reversed) {
        Face& face = out.faces.emplace_back();
        for (std::size_t j = 0; j < capPoints; ++j) {
            const std::size_t k = reversed ? capPoints - 1 - j : j;
            const Eigen::Vector2d st = (section[k] - low) / capSize;
            addCorner(face, addPoint(points[std::size_t(index(n, k))]), st.x(), st.y());
        }
    };
    if (fields.beginCap) addCap(0, true);
    if (fields.endCap) addCap(spines - 1, false);
    return out;
}

}  // namespace symcompress::x3d
