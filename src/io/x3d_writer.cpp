// X3D writer: XML encoding with X3D 3.3 Interchange nodes, so that X3D 3 and 4 readers (X_ITE, assimp,
// meshlab) load it, unless a material needs X3D 4's PhysicalMaterial or texture fields (x3d_materials.hpp). Each mesh
// becomes one DEF'd Group of Shapes the first time a node draws it and a USE afterwards, and a geometry node that an
// earlier Shape wrote the same (one part in several materials) a USE of that one; node transforms become Transforms
// (any affine matrix, mirrors included, through rotation, scale and scaleOrientation); animations become a TimeSensor,
// interpolators and ROUTEs. `.x3dz` is the same, gzip-compressed.
#include "common/color_space.hpp"
#include "common/image_alpha.hpp"
#include "common/markup_text.hpp"
#include "common/number_text.hpp"
#include "file_metadata.hpp"
#include "image_reference.hpp"
#include "rotation_and_scale.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "x3d_crease_normals.hpp"
#include "x3d_materials.hpp"
#include "x3d_polygons.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <type_traits>
#include <unordered_map>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// Each component cut by `round` (number_text.hpp) before it is printed.
template <typename Vector, typename Round = double (*)(double)>
void appendVector(std::string& out, const Vector& v, int components, Round round = [](double x) { return x; }) {
    for (int c = 0; c < components; ++c) {
        if (c) out += ' ';
        appendShortestFloat(out, round(v[c]));
    }
}

// Whether rounding to `decimals` puts two corners of a triangle with three distinct corners at one point: it
// would shade nothing, and the browser would make its normal of nothing.
bool roundingCollapses(const Primitive& primitive, int decimals) {
    auto round = [&](std::uint32_t v) {
        return primitive.positions[v].unaryExpr([&](double x) { return roundedDecimals(x, decimals); }).eval();
    };
    const auto& p = primitive.positions;
    return std::any_of(primitive.triangles.begin(), primitive.triangles.end(), [&](const Triangle& t) {
        if (hasTwoCornersAtOnePoint(p, t)) return false;
        const Eigen::Vector3d a = round(t[0]), b = round(t[1]), c = round(t[2]);
        return a == b || b == c || a == c;
    });
}

// The places after the point that keep every corner of `primitive` within its error bound
// (positionErrorBound) and collapse no triangle: the text's quantization, as
// Draco's bits are a GLB's. A corner moves by at most sqrt(3)/2 of a unit in the last place. Nothing
// (positions as they are) without a bound, or on a seam's grid, whose points the copies of a region share.
std::optional<int> positionDecimals(const Primitive& primitive, const WriteOptions& options) {
    constexpr int kMostDecimals = 12;
    const double bound = positionErrorBound(primitive, options);
    if (!(bound > 0) || primitive.positionGrid) return std::nullopt;
    int decimals = std::clamp(int(std::ceil(-std::log10(2 * bound / std::sqrt(3.0)))), -9, kMostDecimals);
    while (decimals < kMostDecimals && roundingCollapses(primitive, decimals)) ++decimals;
    return decimals;
}

// A mesh as a face set whose normals the browser makes from a creaseAngle: its vertices joined into points,
// and the angle, such that every corner gets the normal it has (creasedNormalsMatch). Nothing where no angle
// tried does: the copies of a region, whose cut faces would smooth otherwise, a tile whose normals its
// neighbours in the input made, normals a modeller set, or no normals (flat).
struct CreasedFaceSet {
    std::vector<std::uint32_t> vertexOfPoint;
    std::vector<std::vector<std::int64_t>> faces;  // the triangles, or the polygons they fan over, by point
    double creaseAngle = 0;                        // from pi up: every face at a point smoothed
};

// The points of the face set at `creaseAngle`, for each vertex, and a vertex of each point (`vertexOfPoint`): the
// vertices of a group belong to one point where, as one, the browser would give each corner its normal; otherwise
// (parts that touch without sharing their points, a crease the angle would smooth) each is a point of its own.
// Nothing where a vertex would not get its normal even alone: the angle does not match (creasedNormalsMatch).
// `groups`: vertices at one place (position as written, texture coordinates, colour); `groupNormals`: the normals
// of the faces at each group, the same at every angle tried.
std::optional<std::vector<std::uint32_t>> pointsOfVertices(const Primitive& primitive,
                                                           const std::vector<Eigen::Vector3d>& faceNormal,
                                                           const std::vector<std::vector<std::uint32_t>>& groups,
                                                           const NormalsAtPoints& groupNormals,
                                                           const std::vector<std::vector<std::uint32_t>>& facesOfVertex,
                                                           double creaseAngle,
                                                           std::vector<std::uint32_t>& vertexOfPoint) {
    const double cosCrease = std::cos(std::min(creaseAngle, M_PI));
    auto matches = [&](std::uint32_t v, const Eigen::Vector3d& sum) {
        return (sum.normalized() - primitive.normals[v]).norm() < kCreasedNormalMatch;
    };
    // As one point: each corner's normal is the mean of the faces of the group within the angle of its own.
    auto asOne = [&](std::size_t group) {
        for (std::uint32_t v : groups[group])
            for (std::uint32_t f : facesOfVertex[v])
                if (!matches(v, groupNormals.smoothed(group, faceNormal[f], cosCrease))) return false;
        return true;
    };
    auto alone = [&](std::uint32_t v) {
        for (std::uint32_t f : facesOfVertex[v]) {
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for (std::uint32_t g : facesOfVertex[v])
                if (g == f || faceNormal[f].dot(faceNormal[g]) > cosCrease) sum += faceNormal[g];
            if (!matches(v, sum)) return false;
        }
        return true;
    };
    std::vector<std::uint32_t> pointOfVertex(primitive.positions.size());
    for (std::size_t group = 0; group < groups.size(); ++group) {
        if (asOne(group)) {
            for (std::uint32_t v : groups[group]) pointOfVertex[v] = std::uint32_t(vertexOfPoint.size());
            vertexOfPoint.push_back(groups[group].front());
            continue;
        }
        if (groups[group].size() == 1) return std::nullopt;
        for (std::uint32_t v : groups[group]) {
            if (!alone(v)) return std::nullopt;
            pointOfVertex[v] = std::uint32_t(vertexOfPoint.size());
            vertexOfPoint.push_back(v);
        }
    }
    return pointOfVertex;
}

// The face set of `faces` (the primitive's triangles, or polygons they fan over), where an angle does.
std::optional<CreasedFaceSet> creasedFaceSetOf(const Primitive& primitive,
                                               const std::vector<Eigen::Vector3d>& positions,
                                               const std::vector<Eigen::Vector2d>& texcoords,
                                               const std::vector<std::vector<std::uint32_t>>& faces) {
    std::vector<Eigen::Vector3d> faceNormal;
    std::vector<std::vector<std::uint32_t>> facesOfVertex(positions.size());
    double leastCosine = 1;  // between two faces of one vertex: the crease angle lies above its angle
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell's, as creasedNormals
        for (std::size_t k = 0; k < faces[f].size(); ++k)
            normal += positions[faces[f][k]].cross(positions[faces[f][(k + 1) % faces[f].size()]]);
        if (!(normal.norm() > 0)) return std::nullopt;  // the browser's choice for a face without a normal
        faceNormal.push_back(normal.normalized());
        for (std::uint32_t v : faces[f]) {
            for (std::uint32_t g : facesOfVertex[v])
                leastCosine = std::min(leastCosine, faceNormal[f].dot(faceNormal[g]));
            facesOfVertex[v].push_back(f);
        }
    }
    const double smoothed = std::acos(std::clamp(leastCosine, -1.0, 1.0));  // the largest angle
    std::map<std::array<double, 9>, std::vector<std::uint32_t>> atPlace;
    for (std::uint32_t v = 0; v < positions.size(); ++v) {
        std::array<double, 9> key{positions[v].x(), positions[v].y(), positions[v].z()};
        if (!texcoords.empty()) key[3] = texcoords[v].x(), key[4] = texcoords[v].y();
        if (!primitive.colors.empty())
            for (int c = 0; c < 4; ++c) key[std::size_t(5 + c)] = primitive.colors[v][c];
        atPlace[key].push_back(v);
    }
    std::vector<Eigen::Vector3d> cornerNormals;
    for (const std::vector<std::uint32_t>& face : faces)
        for (std::uint32_t v : face) cornerNormals.push_back(primitive.normals[v]);
    std::vector<std::vector<std::uint32_t>> groups;
    std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> normalsAtGroup;
    normalsAtGroup.reserve(cornerNormals.size());
    for (auto& [place, vertices] : atPlace) {
        for (std::uint32_t v : vertices)
            for (std::uint32_t f : facesOfVertex[v])
                normalsAtGroup.push_back({std::uint32_t(groups.size()), faceNormal[f]});
        groups.push_back(std::move(vertices));
    }
    const NormalsAtPoints groupNormals(groups.size(), normalsAtGroup);
    // Angles to try: every face at a point smoothed (a triangle set), then the shortest decimals above the
    // largest angle smoothed, as modellers set them (0.5, 1).
    std::vector<double> angles = {4};
    for (int places = 0; places <= 3; ++places) {
        const double scale = std::pow(10.0, places), angle = std::floor(smoothed * scale + 1) / scale;
        if (angle < M_PI && std::find(angles.begin(), angles.end(), angle) == angles.end()) angles.push_back(angle);
    }
    // Of the angles that match, the one that joins the most vertices into points (flat faces that bend are each
    // apart at an angle smoothing everything, joined at one that smooths nothing), the first of equals: the
    // points of each, then every normal checked from the fewest points up.
    struct Trial {
        double angle;
        std::vector<std::uint32_t> vertexOfPoint, pointOfVertex;
    };
    std::vector<Trial> trials;
    for (const double angle : angles) {
        Trial trial{angle, {}, {}};
        std::optional<std::vector<std::uint32_t>> pointOfVertex =
            pointsOfVertices(primitive, faceNormal, groups, groupNormals, facesOfVertex, angle, trial.vertexOfPoint);
        if (!pointOfVertex) continue;
        trial.pointOfVertex = std::move(*pointOfVertex);
        trials.push_back(std::move(trial));
    }
    std::stable_sort(trials.begin(), trials.end(),
                     [](const Trial& a, const Trial& b) { return a.vertexOfPoint.size() < b.vertexOfPoint.size(); });
    for (Trial& trial : trials) {
        CreasedFaceSet set;
        set.creaseAngle = trial.angle;
        std::vector<double> points;
        for (std::uint32_t v : trial.vertexOfPoint)
            points.insert(points.end(), {positions[v].x(), positions[v].y(), positions[v].z()});
        set.faces.reserve(faces.size());
        for (const std::vector<std::uint32_t>& face : faces) {
            std::vector<std::int64_t>& written = set.faces.emplace_back();
            written.reserve(face.size());
            for (std::uint32_t v : face) written.push_back(trial.pointOfVertex[v]);
        }
        if (creasedNormalsMatch(set.faces, points, cornerNormals, trial.angle)) {
            set.vertexOfPoint = std::move(trial.vertexOfPoint);
            return set;
        }
    }
    return std::nullopt;
}

// The polygons the triangles fan over first (x3d_polygons.hpp: the browser weighs a polygon's normal once where
// it smooths, as it did for a face set read from polygons; fewer indices too), else the triangles.
std::optional<CreasedFaceSet> asCreasedFaceSet(const Primitive& primitive,
                                               const std::vector<Eigen::Vector3d>& positions,
                                               const std::vector<Eigen::Vector2d>& texcoords) {
    if (primitive.normals.empty() || primitive.triangles.empty()) return std::nullopt;
    const std::vector<std::vector<std::uint32_t>> polygons =
        x3d::fanPolygons(primitive.triangles, positions, x3d::kMostTurnOfSmoothedPolygon);
    if (polygons.size() < primitive.triangles.size())
        if (std::optional<CreasedFaceSet> set = creasedFaceSetOf(primitive, positions, texcoords, polygons)) return set;
    std::vector<std::vector<std::uint32_t>> triangles;
    for (const Triangle& t : primitive.triangles) triangles.push_back({t[0], t[1], t[2]});
    return creasedFaceSetOf(primitive, positions, texcoords, triangles);
}

// Segments as polylines, each segment that starts where the one before it ends continuing its polyline (a strip
// a-b, b-c as a b c): X3D's coordIndex then takes one index a segment instead of three.
std::vector<std::vector<std::uint32_t>> polylinesOf(const std::vector<Segment>& segments) {
    std::vector<std::vector<std::uint32_t>> polylines;
    for (const Segment& segment : segments) {
        if (polylines.empty() || polylines.back().back() != segment[0]) polylines.push_back({segment[0]});
        polylines.back().push_back(segment[1]);
    }
    return polylines;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t chunk = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                                    (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += alphabet[chunk >> 18 & 63];
        out += alphabet[chunk >> 12 & 63];
        out += i + 1 < bytes.size() ? alphabet[chunk >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[chunk & 63] : '=';
    }
    return out;
}

// A Transform's fields, each left out when it does nothing.
void appendTransform(std::string& out, const Eigen::Vector3d& translation, const Eigen::AngleAxisd& rotation,
                     const Eigen::Vector3d& scale, const Eigen::AngleAxisd& orientation) {
    auto placement = [](double x) { return rounded(x, kPlacementDigits); };
    auto turn = [](double x) { return roundedDecimals(x, kRotationDecimals); };
    if (!translation.isZero(0)) {
        out += " translation='";
        const double largest = translation.cwiseAbs().maxCoeff();
        appendVector(out, translation, 3, [&](double x) { return placement(atFloat32PrecisionOf(x, largest)); });
        out += "'";
    }
    auto appendRotation = [&](const char* field, const Eigen::AngleAxisd& value) {
        if (turn(value.angle()) == 0) return;
        out += std::string(" ") + field + "='";
        appendVector(out, value.axis(), 3, turn);
        out += ' ';
        appendShortestFloat(out, turn(value.angle()));
        out += "'";
    };
    appendRotation("rotation", rotation);
    if ((scale.array() - 1).abs().maxCoeff() > kScaleNoise) {
        out += " scale='";
        appendVector(out, scale, 3, placement);
        out += "'";
        appendRotation("scaleOrientation", orientation);
    }
}

// X3D's Transform is T * R * SR * S * SR^-1. With the SVD L = U S V^T of the linear part, R = U V^T and
// SR = V reproduce any affine matrix; a mirror shows up as a negative scale. An animated node is written
// as glTF holds it, translation, rotation and scale (no scaleOrientation), the parts its channels replace.
void appendTransformFields(std::string& out, const Eigen::Matrix4d& matrix, bool animated) {
    const Eigen::Matrix3d linear = matrix.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = matrix.topRightCorner<3, 1>();
    if (animated)
        if (const auto trs = asRotationAndScale(linear)) {
            appendTransform(out, translation, Eigen::AngleAxisd(trs->first), trs->second, Eigen::AngleAxisd::Identity());
            return;
        }
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d u = svd.matrixU(), v = svd.matrixV();
    Eigen::Vector3d scale = svd.singularValues();
    if (v.determinant() < 0) v.col(2) = -v.col(2), u.col(2) = -u.col(2);
    if (u.determinant() < 0) u.col(2) = -u.col(2), scale[2] = -scale[2];
    appendTransform(out, translation, Eigen::AngleAxisd(u * v.transpose()), scale, Eigen::AngleAxisd(v));
}

class X3dWriter {
public:
    // `file`: where the text goes, which unread images are referred to relative to (empty: as they are).
    X3dWriter(const Scene& scene, const WriteOptions& options, fs::path file = {})
        : scene_(scene), options_(options), file_(std::move(file)) {}

    std::string write() {
        // X3D 4.0 only where a material needs it (x3d_materials.hpp); X3D 3.3 otherwise, as before.
        bool physical = false;
        // Each material surfaces draw (lines and points are drawn with X3D 3.3's Material whatever theirs:
        // writeUnlitShape), and whether every surface drawing it has translucent vertex colours: AUTO blends those
        // (writeColors writes them as a ColorRGBA).
        std::map<int, bool> allTranslucent;
        for (const Mesh& mesh : scene_.meshes)
            for (const Primitive& primitive : mesh.primitives)
                if (primitive.material >= 0 && primitive.topology == Topology::Triangles && !primitive.drawsNothing())
                    allTranslucent.try_emplace(primitive.material, true).first->second &=
                        hasTranslucentCorner(primitive);
        for (const auto& [index, translucent] : allTranslucent)
            if (translucent) blendedByColors_.insert(index);
        for (const auto& [index, translucent] : allTranslucent) {
            const Material& material = scene_.materials[std::size_t(index)];
            version4_ = version4_ || x3d::needsX3d4(material) || statedAlphaMode(index);
            physical = physical || x3d::needsPhysicalMaterial(material);
        }
        // No DOCTYPE or schema location: neither is required (X3D's XML encoding validates by either, browsers
        // by neither), and together they were some 100 to 230 bytes of every file, most of a small one's.
        out_ += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile='Interchange' version='";
        out_ += version4_ ? "4.0" : "3.3";
        out_ += "'>\n<head>\n";
        // PhysicalMaterial is Shape level 2, beyond the Interchange profile's level 1.
        if (physical) out_ += "<component name='Shape' level='2'/>\n";
        // OrthoViewpoint is Navigation level 3, beyond the Interchange profile's level 1.
        if (std::any_of(scene_.cameras.begin(), scene_.cameras.end(),
                        [](const Camera& camera) { return camera.projection == Camera::Projection::Orthographic; }))
            out_ += "<component name='Navigation' level='3'/>\n";
        // What the scene's file said about itself, as meta tags (file_metadata.hpp), then the writer's: the digest
        // in a tag of its own, which names symcompress (as the generator does where there is none).
        const nlohmann::json extras = writtenExtras(scene_.extrasJson, options_.extrasJson);
        const std::string digest = extras.is_object() && extras.contains(kDigestMember)
                                       ? digestAsMetaContent(extras[kDigestMember])
                                       : std::string();
        if (digest.empty()) out_ += "<meta name='generator' content='symcompress'/>\n";
        if (!scene_.copyright.empty())
            out_ += "<meta name='copyright' content='" + escapedMarkup(scene_.copyright) + "'/>\n";
        for (const auto& [name, content] : metaTags(extras))
            out_ += "<meta name='" + escapedMarkup(name) + "' content='" + escapedMarkup(content) + "'/>\n";
        if (!digest.empty()) out_ += "<meta name='" + std::string(kDigestMember) + "' content='" + digest + "'/>\n";
        out_ += "</head>\n<Scene>\n";
        for (const std::string& node : scene_.x3dEnvironment) out_ += node + "\n";
        written_.assign(scene_.meshes.size(), false);
        drawers_.assign(scene_.meshes.size(), 0);
        shapes_.assign(scene_.meshes.size(), -1);
        namedByDrawer_.assign(scene_.meshes.size(), false);
        const std::vector<char> written = nodesUnder(scene_, scene_.roots);
        for (std::size_t n = 0; n < scene_.nodes.size(); ++n)
            if (const Node& node = scene_.nodes[n]; written[n] && node.mesh >= 0) {
                ++drawers_[std::size_t(node.mesh)];
                if (carriesNodeName(node)) namedByDrawer_[std::size_t(node.mesh)] = true;
            }
        for (const Animation& animation : scene_.animations)
            for (const AnimationChannel& channel : animation.channels) nodeDef_[channel.node];
        for (int root : scene_.roots) writeNode(root);
        for (std::size_t a = 0; a < scene_.animations.size(); ++a) writeAnimation(scene_.animations[a], a);
        out_ += "</Scene>\n</X3D>\n";
        return withDefs();
    }

private:
    static bool hasTranslucentCorner(const Primitive& primitive) {
        if (primitive.colors.empty()) return false;
        return std::any_of(primitive.triangles.begin(), primitive.triangles.end(), [&](const Triangle& t) {
            return std::any_of(t.begin(), t.end(), [&](std::uint32_t v) { return primitive.colors[v][3] != 1; });
        });
    }

    // A node as a Transform, or where it would be one without a field (no name, not animated, no transform) as
    // what it holds alone. A node that only USEs a mesh written before is one line.
    void writeNode(int index) {
        const Node& node = scene_.nodes[index];
        // Animated nodes need a DEF for their ROUTEs (nodeDef_ holds an entry for each).
        const auto animated = nodeDef_.find(index);
        const bool named = !node.name.empty() && !carriesNodeName(node);
        const bool transform = named || animated != nodeDef_.end() || !node.transform.isIdentity();
        if (!transform) {
            writeContent(node);
            return;
        }
        out_ += "<Transform";
        if (named || animated != nodeDef_.end()) {
            const std::string def = uniqueName(node.name.empty() ? "node" + std::to_string(index) : node.name);
            out_ += " DEF='" + def + "'";
            if (animated != nodeDef_.end()) animated->second = def;
        }
        appendTransformFields(out_, node.transform, animated != nodeDef_.end());
        if (node.mesh >= 0 && written_[std::size_t(node.mesh)] && node.camera < 0 && node.light < 0 &&
            node.children.empty()) {
            out_ += ">" + meshUse(node.mesh) + "</Transform>\n";
            return;
        }
        out_ += ">\n";
        writeContent(node);
        out_ += "</Transform>\n";
    }

    // Whether the name of `node` is its mesh's, which the mesh's DEF then carries (as X3D's reader names a node
    // that draws a DEF'd Shape): the mesh is one Shape, or a Group that several nodes draw.
    bool carriesNodeName(const Node& node) {
        if (node.mesh < 0 || node.name.empty() || scene_.meshes[std::size_t(node.mesh)].name != node.name) return false;
        return shapesOf(node.mesh) == 1 || drawers_[std::size_t(node.mesh)] > 1;
    }

    void writeContent(const Node& node) {
        if (node.mesh >= 0) writeMesh(node.mesh);
        if (node.camera >= 0) writeViewpoint(scene_.cameras[std::size_t(node.camera)]);
        if (node.light >= 0) writeLight(scene_.lights[std::size_t(node.light)]);
        for (int child : node.children) writeNode(child);
    }

    // A camera in its node's frame (the Transform around it places it): at the origin, looking down -z.
    // X3D's fieldOfView is the smaller of the two angles: the vertical one unless the view is narrower
    // than it is high.
    void writeViewpoint(const Camera& camera) {
        if (camera.projection == Camera::Projection::Orthographic) {
            out_ += "<OrthoViewpoint position='0 0 0' fieldOfView='";
            appendVector(out_, Eigen::Vector4d(-camera.xmag, -camera.ymag, camera.xmag, camera.ymag), 4);
        } else {
            double fieldOfView = camera.yfov;
            if (camera.aspectRatio > 0 && camera.aspectRatio < 1)
                fieldOfView = 2 * std::atan(std::tan(camera.yfov / 2) * camera.aspectRatio);
            out_ += "<Viewpoint position='0 0 0' fieldOfView='";
            appendShortestFloat(out_, fieldOfView);
        }
        out_ += "'";
        if (!camera.name.empty()) out_ += " description='" + escapedMarkup(camera.name) + "'";
        out_ += "/>\n";
    }

    // A light in its node's frame: at the origin, shining down -z. It lights the whole scene (global), as
    // glTF's do; its intensity is cut to X3D's largest, 1 (formatLosses warns); a point or spot light's
    // falls off as the X3D input had it, else with the inverse square of the distance, as glTF's does; no
    // range is X3D's largest radius.
    void writeLight(const Light& light) {
        out_ += light.type == Light::Type::Directional ? "<DirectionalLight direction='0 0 -1'"
                : light.type == Light::Type::Spot      ? "<SpotLight direction='0 0 -1' location='0 0 0'"
                                                       : "<PointLight location='0 0 0'";
        out_ += " global='true' color='";
        appendVector(out_, light.color, 3);
        out_ += "' intensity='";
        appendShortestFloat(out_, std::min(light.intensity, 1.0));
        out_ += "'";
        if (light.type != Light::Type::Directional) {
            out_ += " attenuation='";
            appendVector(out_, light.x3dAttenuation.value_or(Eigen::Vector3d(0, 0, 1)), 3);
            out_ += "' radius='";
            appendShortestFloat(out_, light.range > 0 ? light.range : std::numeric_limits<float>::max());
            out_ += "'";
        }
        if (light.type == Light::Type::Spot) {
            out_ += " beamWidth='";
            appendShortestFloat(out_, light.innerConeAngle);
            out_ += "' cutOffAngle='";
            appendShortestFloat(out_, light.outerConeAngle);
            out_ += "'";
        }
        out_ += "/>\n";
    }

    // A glTF animation as X3D 3.3 Interchange nodes: a looping TimeSensor whose cycle is the animation's
    // length, one interpolator per channel keyed on the fraction of the cycle, and ROUTEs from the clock
    // to the interpolators and from them to the Transforms. STEP keys are doubled (a jump at each key);
    // cubic splines keep their values at the keys and are interpolated linearly between them.
    void writeAnimation(const Animation& animation, std::size_t index) {
        double cycle = 0;
        for (const AnimationChannel& channel : animation.channels) cycle = std::max(cycle, channel.times.back());
        if (!(cycle > 0)) cycle = 1;
        const std::string clock = uniqueName(animation.name.empty() ? "animation" + std::to_string(index) : animation.name);
        out_ += "<TimeSensor DEF='" + clock + "' cycleInterval='";
        appendShortestFloat(out_, cycle);
        out_ += "' loop='true'/>\n";
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const AnimationChannel& channel = animation.channels[c];
            if (nodeDef_.at(channel.node).empty()) continue;  // a node no root reaches: nothing drawn to move
            if (channel.path == AnimationChannel::Path::Weights) continue;  // no morph targets (formatLosses)
            const bool rotation = channel.path == AnimationChannel::Path::Rotation;
            // A cubic spline's key is in-tangent, value, out-tangent: the value is the middle one.
            const std::size_t stride = channel.valuesPerKey(), offset = stride > channel.components() ? channel.components() : 0;
            std::vector<std::pair<double, std::size_t>> keys;  // fraction, index of the key's value
            for (std::size_t k = 0; k < channel.times.size(); ++k) {
                if (channel.interpolation == AnimationChannel::Interpolation::Step && k > 0)
                    keys.push_back({channel.times[k] / cycle, k - 1});
                keys.push_back({channel.times[k] / cycle, k});
            }
            const std::string interpolator = uniqueName(clock + "_channel" + std::to_string(c));
            out_ += std::string("<") + (rotation ? "OrientationInterpolator" : "PositionInterpolator") + " DEF='" +
                    interpolator + "' key='";
            for (std::size_t k = 0; k < keys.size(); ++k) {
                if (k) out_ += ' ';
                appendShortestFloat(out_, static_cast<float>(keys[k].first));  // key times are float32 in glTF
            }
            out_ += "' keyValue='";
            for (std::size_t k = 0; k < keys.size(); ++k) {
                if (k) out_ += ", ";
                const double* value = channel.values.data() + keys[k].second * stride + offset;
                if (rotation) {
                    const Eigen::AngleAxisd turn(Eigen::Quaterniond(value[3], value[0], value[1], value[2]).normalized());
                    const auto decimals = [](double x) { return roundedDecimals(x, kRotationDecimals); };
                    appendVector(out_, turn.axis(), 3, decimals);
                    out_ += ' ';
                    appendShortestFloat(out_, decimals(turn.angle()));
                } else {
                    appendVector(out_, Eigen::Vector3d(value[0], value[1], value[2]), 3);
                }
            }
            out_ += "'/>\n";
            const char* field = rotation ? "set_rotation" : channel.path == AnimationChannel::Path::Scale ? "set_scale" : "set_translation";
            out_ += "<ROUTE fromNode='" + clock + "' fromField='fraction_changed' toNode='" + interpolator +
                    "' toField='set_fraction'/>\n";
            out_ += "<ROUTE fromNode='" + interpolator + "' fromField='value_changed' toNode='" +
                    nodeDef_.at(channel.node) + "' toField='" + field + "'/>\n";
        }
    }

    // DEF names must be unique in the file.
    std::string uniqueName(const std::string& name) {
        std::string clean;
        for (char c : name) clean += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
        if (clean.empty() || std::isdigit(static_cast<unsigned char>(clean[0]))) clean = "n" + clean;
        std::string unique = clean;
        for (int k = 2; !names_.insert(unique).second; ++k) unique = clean + "_" + std::to_string(k);
        return unique;
    }

    // The node just opened (its name written, `<Group`) as the one later nodes USE for `key` ("mesh3",
    // "material0", "texture2"): it gets a DEF only where one does (useOf; withDefs).
    void definable(const std::string& key) { definable_[key] = {out_.size(), {}}; }

    // The DEF that a USE of `key`'s node names: the key, made unique the first time (a node read from
    // symcompress's own X3D output may be named mesh0).
    std::string useOf(const std::string& key) {
        std::string& def = definable_.at(key).def;
        if (def.empty()) def = uniqueName(key);
        return def;
    }

    // How writeMesh writes a primitive: not at all, as lines or points, as the X3D node it was read from, or as
    // its triangles (those of zero area in a Shape of their own).
    enum class Writing { Nothing, Unlit, Source, Triangles };
    static Writing writingOf(const Primitive& primitive) {
        if (primitive.drawsNothing()) return Writing::Nothing;
        if (primitive.topology != Topology::Triangles) return Writing::Unlit;
        if (primitive.x3dSource && primitive.x3dSource->cornerHash == trianglePositionsHash(primitive))
            return Writing::Source;
        return Writing::Triangles;
    }

    // How many Shapes writeMesh writes for `mesh` (a triangle primitive with triangles of zero area is two).
    std::size_t shapesOf(int mesh) {
        int& shapes = shapes_[std::size_t(mesh)];
        if (shapes < 0) {
            shapes = 0;
            for (const Primitive& primitive : scene_.meshes[std::size_t(mesh)].primitives) {
                const Writing writing = writingOf(primitive);
                if (writing == Writing::Nothing) continue;
                const auto split = writing == Writing::Triangles ? withoutZeroAreaTriangles(primitive) : std::nullopt;
                shapes += split ? int(!split->first.triangles.empty()) + 1 : 1;
            }
        }
        return std::size_t(shapes);
    }

    // The USE of a mesh written before: its one Shape, or its Group.
    std::string meshUse(int mesh) {
        return std::string(shapesOf(mesh) == 1 ? "<Shape" : "<Group") + " USE='" +
               useOf("mesh" + std::to_string(mesh)) + "'/>";
    }

    // A mesh that one node draws as its Shapes; one that several draw as its one Shape, or as a Group of its
    // Shapes, which the others USE. Its DEF is its name where that is a drawing node's (carriesNodeName).
    void writeMesh(int mesh) {
        if (shapesOf(mesh) == 0) return;  // nothing drawn: nothing to DEF or USE
        const std::string key = "mesh" + std::to_string(mesh);
        if (written_[mesh]) {
            out_ += meshUse(mesh) + "\n";
            return;
        }
        written_[mesh] = true;
        const bool shared = drawers_[std::size_t(mesh)] > 1, grouped = shared && shapesOf(mesh) > 1;
        const std::size_t start = out_.size();
        if (grouped) {
            out_ += "<Group";
            definable(key);
            out_ += ">\n";
        }
        for (const Primitive& primitive : scene_.meshes[mesh].primitives) {
            const Writing writing = writingOf(primitive);
            if (writing == Writing::Nothing) continue;
            if (writing == Writing::Unlit) {
                writeUnlitShape(primitive);
                continue;
            }
            if (writing == Writing::Source) {
                writeSourceShape(primitive);
                continue;
            }
            // Triangles of zero area apart: the browser would make their normals of nothing.
            const std::optional<std::pair<Primitive, ZeroAreaTriangles>> split = withoutZeroAreaTriangles(primitive);
            if (!split) {
                writeShape(primitive);
                continue;
            }
            if (!split->first.triangles.empty()) writeShape(split->first);
            writeZeroAreaShape(primitive.positions[split->second.vertex], split->second.count);
        }
        if (grouped) {
            out_ += "</Group>\n";
        } else if (shared || namedByDrawer_[std::size_t(mesh)]) {
            if (shapesOf(mesh) != 1) return;
            definable_[key] = {out_.find("<Shape", start) + std::strlen("<Shape"), {}};
        }
        if (namedByDrawer_[std::size_t(mesh)]) definable_.at(key).def = uniqueName(scene_.meshes[mesh].name);
    }

    std::optional<Material::AlphaMode> statedAlphaMode(int material) {
        const Material& m = scene_.materials[std::size_t(material)];
        return x3d::statedAlphaMode(
            m, translucentTexture_(m.baseColorTexture.texture) || blendedByColors_.count(material) > 0);
    }

    void writeAppearance(int material) {
        // X3D draws a Shape without an Appearance unlit white.
        if (material >= 0) {
            const Material& m = scene_.materials[std::size_t(material)];
            if (x3d::drawnWithoutMaterial(m) && m.baseColorTexture.texture < 0 && !statedAlphaMode(material)) return;
        }
        if (material < 0) {
            out_ += "<Appearance><Material/></Appearance>\n";
            return;
        }
        const std::string key = "material" + std::to_string(material);
        if (!materialWritten_.insert(material).second) {
            out_ += "<Appearance USE='" + useOf(key) + "'/>\n";
            return;
        }
        const Material& m = scene_.materials[material];
        const x3d::MaterialTextures textures = x3d::materialTextures(m);
        out_ += "<Appearance";
        definable(key);
        if (!m.name.empty()) definable_.at(key).def = uniqueName(m.name);  // the material's name, kept
        // glTF's alpha modes, which X3D 4's Appearance has, where AUTO would draw another.
        if (const auto stated = statedAlphaMode(material)) {
            out_ += stated == Material::AlphaMode::Opaque  ? " alphaMode='OPAQUE'"
                    : stated == Material::AlphaMode::Blend ? " alphaMode='BLEND'"
                                                           : " alphaMode='MASK'";
            if (stated == Material::AlphaMode::Mask) {
                out_ += " alphaCutoff='";
                appendShortestFloat(out_, m.alphaCutoff);
                out_ += "'";
            }
        }
        if (x3d::drawnWithoutMaterial(m) && textures.fields.empty()) {
            out_ += "/>\n";
            return;
        }
        out_ += ">";
        if (!x3d::drawnWithoutMaterial(m)) {  // else its texture alone, unlit
            if (x3d::isUnlit(m))
                writeUnlitMaterial(m, textures);
            else if (x3d::needsPhysicalMaterial(m))
                writePhysicalMaterial(m, textures);
            else
                writePhongMaterial(m, textures);
        }
        for (const x3d::TextureField& field : textures.fields)
            if (std::string(field.field) == "texture") writeImageTexture(field.use->texture, "");
        out_ += "</Appearance>\n";
    }

    // The Appearance of lines and points (x3d::unlitPhongOf), shared as writeAppearance's is.
    void writeUnlitAppearance(int material) {
        const std::string key = "emissive" + std::to_string(material);
        if (material >= 0 && !unlitMaterialWritten_.insert(material).second) {
            out_ += "<Appearance USE='" + useOf(key) + "'/>\n";
            return;
        }
        const PhongMaterial phong =
            x3d::unlitPhongOf(material >= 0 ? scene_.materials[std::size_t(material)] : Material{});
        out_ += "<Appearance";
        if (material >= 0) definable(key);
        out_ += ">";
        out_ += "<Material diffuseColor='0 0 0' emissiveColor='";
        appendVector(out_, phong.emissiveColor, 3);
        out_ += "'";
        appendField("transparency", phong.transparency, 0.0);
        out_ += "/></Appearance>\n";
    }

    // A field with the value it has unless that is X3D's default.
    template <typename Value>
    void appendField(const char* field, const Value& value, const Value& fallback, int components = 1) {
        if (value == fallback) return;
        out_ += std::string(" ") + field + "='";
        if constexpr (std::is_arithmetic_v<Value>)
            appendShortestFloat(out_, value);
        else
            appendVector(out_, value, components);
        out_ += "'";
    }

    // Each texture field's mapping (where the material reads more than one set), normalScale, occlusionStrength,
    // then, after the node's fields, its textures.
    void appendTextureFields(const x3d::MaterialTextures& textures) {
        for (const x3d::TextureField& field : textures.fields) {
            const std::string& mapping = textures.channels[field.channel].mapping;
            if (!mapping.empty() && std::string(field.field) != "texture")
                out_ += std::string(" ") + field.field + "Mapping='" + escapedMarkup(mapping) + "'";
            if (std::string(field.field) == "normalTexture") appendField("normalScale", field.use->scale, 1.0);
            if (std::string(field.field) == "occlusionTexture") appendField("occlusionStrength", field.use->scale, 1.0);
        }
    }
    bool writeTextureChildren(const x3d::MaterialTextures& textures) {
        bool any = false;
        for (const x3d::TextureField& field : textures.fields)
            if (std::string(field.field) != "texture") {
                if (!any) out_ += ">";
                any = true;
                writeImageTexture(field.use->texture, field.field);
            }
        return any;
    }

    // X3D 4's PhysicalMaterial is glTF's material: its colours linear, as glTF's factors.
    void writePhysicalMaterial(const Material& m, const x3d::MaterialTextures& textures) {
        out_ += "<PhysicalMaterial";
        appendField("baseColor", Eigen::Vector3d(m.baseColorFactor.head<3>()), Eigen::Vector3d::Ones().eval(), 3);
        appendField("metallic", m.metallicFactor, 1.0);
        appendField("roughness", m.roughnessFactor, 1.0);
        appendField("emissiveColor", m.emissiveFactor, Eigen::Vector3d::Zero().eval(), 3);
        appendField("transparency", 1 - m.baseColorFactor[3], 0.0);
        appendTextureFields(textures);
        out_ += writeTextureChildren(textures) ? "</PhysicalMaterial>" : "/>";
    }

    // KHR_materials_unlit as X3D 4's UnlitMaterial: the base colour, sRGB-encoded, as its emissive colour (the
    // colour drawn), the base texture as its emissive texture.
    void writeUnlitMaterial(const Material& m, const x3d::MaterialTextures& textures) {
        const PhongMaterial phong = x3d::phongOf(m);
        out_ += "<UnlitMaterial";
        appendField("emissiveColor", phong.diffuseColor, Eigen::Vector3d::Ones().eval(), 3);
        appendField("transparency", phong.transparency, 0.0);
        appendTextureFields(textures);
        out_ += writeTextureChildren(textures) ? "</UnlitMaterial>" : "/>";
    }

    // Phong's Material, its colours sRGB-encoded (x3d::phongOf), with X3D 4's texture fields where it has them.
    void writePhongMaterial(const Material& m, const x3d::MaterialTextures& textures) {
        const PhongMaterial phong = x3d::phongOf(m);
        // Fields at X3D's defaults (3.3 and 4.0 alike) are left out.
        out_ += "<Material";
        appendField("diffuseColor", phong.diffuseColor, Eigen::Vector3d::Constant(0.8).eval(), 3);
        appendField("specularColor", phong.specularColor, Eigen::Vector3d::Zero().eval(), 3);
        appendField("emissiveColor", phong.emissiveColor, Eigen::Vector3d::Zero().eval(), 3);
        appendField("ambientIntensity", phong.ambientIntensity, 0.2);
        appendField("shininess", phong.shininess, 0.2);
        appendField("transparency", phong.transparency, 0.0);
        appendTextureFields(textures);
        out_ += writeTextureChildren(textures) ? "</Material>" : "/>";
    }

    // Where an image is: the file it was read from (relative to the output), else its bytes as a data: URL.
    std::string imageUrl(const std::string& uri, const std::string& mimeType, const std::vector<std::uint8_t>& bytes) {
        if (!bytes.empty() && !x3dRefersToImageFile(uri, bytes))
            return "data:" + (mimeType.empty() ? std::string("image/png") : mimeType) + ";base64," + base64(bytes);
        return file_.empty() ? uri : imageReference(uri, file_);
    }

    // An image is written once, with a DEF, and USEd by every other material showing it with the same sampler
    // (X3D's ImageTexture holds both); `containerField` is the material's field that holds it (empty: the
    // Appearance's texture).
    void writeImageTexture(int texture, const std::string& containerField) {
        const std::vector<Texture>& textures = scene_.textures;
        int index = sameImage_[std::size_t(texture)];
        while (!(textures[std::size_t(index)].sampler == textures[std::size_t(texture)].sampler) ||
               sameImage_[std::size_t(index)] != sameImage_[std::size_t(texture)])
            ++index;  // the first texture of this image with this sampler (`texture` itself at the latest)
        const std::string field = containerField.empty() ? "" : " containerField='" + containerField + "'";
        const std::string key = "texture" + std::to_string(index);
        if (textureWritten_.count(index)) {
            out_ += "<ImageTexture USE='" + useOf(key) + "'" + field + "/>";
            return;
        }
        // A fallback image (Texture::fallback) follows as a second URL: a browser shows the first it can read.
        const Texture& image = textures[std::size_t(sameImage_[std::size_t(texture)])];
        std::string urls;
        for (std::string url :
             {imageUrl(image.uri, image.mimeType, image.bytes),
              image.fallback ? imageUrl(image.fallback->uri, image.fallback->mimeType, image.fallback->bytes)
                             : std::string()})
            if (!url.empty()) urls += (urls.empty() ? "\"" : " \"") + escapedMarkup(url) + "\"";
        if (urls.empty()) return;
        textureWritten_.insert(index);
        out_ += "<ImageTexture";
        definable(key);
        out_ += field + " url='" + urls + "'";
        writeSampler(textures[std::size_t(texture)].sampler);
    }

    // glTF's sampler: clamping alone as repeatS and repeatT (X3D 3.3's ImageTexture fields), anything else as
    // TextureProperties; the default writes nothing, X3D's default being glTF's.
    void writeSampler(const TextureSampler& sampler) {
        const bool filtered = sampler.magFilter != 0 || sampler.minFilter != 0;
        const auto repeatOrClamp = [](int wrap) { return wrap == 10497 || wrap == 33071; };
        if (!filtered && repeatOrClamp(sampler.wrapS) && repeatOrClamp(sampler.wrapT)) {
            if (sampler.wrapS == 33071) out_ += " repeatS='false'";
            if (sampler.wrapT == 33071) out_ += " repeatT='false'";
            out_ += "/>";
            return;
        }
        // Mipmaps unless the minification filter reads none (NEAREST, LINEAR).
        const bool mipmaps = sampler.minFilter != 9728 && sampler.minFilter != 9729;
        out_ += "><TextureProperties boundaryModeS='" + x3d::boundaryModeName(sampler.wrapS) + "' boundaryModeT='" +
                x3d::boundaryModeName(sampler.wrapT) + "' magnificationFilter='" +
                x3d::magnificationFilterName(sampler.magFilter) + "' minificationFilter='" +
                x3d::minificationFilterName(sampler.minFilter) + "' generateMipMaps='" + (mipmaps ? "true" : "false") +
                "'/></ImageTexture>";
    }

    // Vertex v's coordinates on a channel: its set (TEXCOORD_0, else the attribute TEXCOORD_n, else TEXCOORD_0 as
    // a viewer falls back), the channel's transform applied (as baseColorTexcoord does for the base colour).
    static Eigen::Vector2d channelTexcoord(const Primitive& primitive, const x3d::TexcoordChannel& channel,
                                           std::size_t v) {
        Eigen::Vector2d t = primitive.texcoords[v];
        const std::string set = "TEXCOORD_" + std::to_string(channel.set);
        for (const VertexAttribute& attribute : primitive.attributes)
            if (channel.set > 0 && attribute.name == set && attribute.components >= 2)
                t = {attribute.values[v * std::size_t(attribute.components)],
                     attribute.values[v * std::size_t(attribute.components) + 1]};
        return channel.transform ? Eigen::Vector2d(channel.transform->matrix() * t.homogeneous()) : t;
    }

    void writeShape(const Primitive& primitive) {
        out_ += "<Shape>\n";
        writeAppearance(primitive.material);
        const bool doubleSided = primitive.material >= 0 && scene_.materials[primitive.material].doubleSided;
        // One set of coordinates for each channel the material's textures read (x3d_materials.hpp).
        const std::vector<x3d::TexcoordChannel> channels =
            primitive.material >= 0 ? x3d::materialTextures(scene_.materials[std::size_t(primitive.material)]).channels
                                    : std::vector<x3d::TexcoordChannel>{{}};
        std::vector<std::vector<Eigen::Vector2d>> texcoordSets;
        for (const x3d::TexcoordChannel& channel : channels) {
            std::vector<Eigen::Vector2d>& texcoords = texcoordSets.emplace_back(primitive.texcoords.size());
            for (std::size_t v = 0; v < texcoords.size(); ++v) texcoords[v] = channelTexcoord(primitive, channel, v);
        }
        const std::vector<Eigen::Vector2d>& texcoords = texcoordSets[0];
        // glTF's TANGENT as X3D 4's Tangent where a normal texture reads it (the file is X3D 4 then): the browser
        // would make other tangents from the texture coordinates' derivatives, and bend the normals otherwise.
        const VertexAttribute* tangents = nullptr;
        if (primitive.material >= 0 && !primitive.normals.empty())
            for (const x3d::TextureField& field :
                 x3d::materialTextures(scene_.materials[std::size_t(primitive.material)]).fields)
                if (std::string(field.field) == "normalTexture")
                    for (const VertexAttribute& attribute : primitive.attributes)
                        if (attribute.name == "TANGENT" && attribute.components == 4) tangents = &attribute;
        // The browser makes its normals from the positions as written: where those the budget's places give
        // would turn them too far, up to two places more, cheaper than the normals' text.
        const std::optional<int> fewest = positionDecimals(primitive, options_);
        std::vector<Eigen::Vector3d> positions;
        std::optional<CreasedFaceSet> creased;
        for (int more = 0; more <= (fewest ? 2 : 0) && !creased; ++more) {
            positions = primitive.positions;
            if (fewest)
                for (Eigen::Vector3d& p : positions)
                    p = p.unaryExpr([&](double x) { return roundedDecimals(x, *fewest + more); });
            // Points join vertices with the same coordinates of one set only.
            // Tangents go beside the normals, vertex by vertex.
            if (texcoordSets.size() == 1 && !tangents) creased = asCreasedFaceSet(primitive, positions, texcoords);
        }
        if (!creased && fewest)
            for (Eigen::Vector3d& p : positions) p = p.unaryExpr([&](double x) { return roundedDecimals(x, *fewest); });
        // The vertices written, in order: every one, or one for each point of the creased face set.
        std::vector<std::uint32_t> written(creased ? creased->vertexOfPoint : std::vector<std::uint32_t>{});
        if (!creased)
            for (std::uint32_t v = 0; v < primitive.positions.size(); ++v) written.push_back(v);
        const std::size_t geometryStart = out_.size();
        const std::string solid = std::string("solid='") + (doubleSided ? "false" : "true") + "'";
        // A triangle set smooths at every point; polygons are a face set's.
        const bool faceSet = creased && (creased->creaseAngle < M_PI ||
                                         std::any_of(creased->faces.begin(), creased->faces.end(),
                                                     [](const std::vector<std::int64_t>& f) { return f.size() > 3; }));
        bool polygons = false;  // triangles joined into polygons
        if (creased && !faceSet) {
            // The browser makes the normals, the same for every copy of the mesh.
            out_ += "<IndexedTriangleSet " + solid + " index='";
            for (std::size_t f = 0; f < creased->faces.size(); ++f)
                for (std::size_t k = 0; k < 3; ++k) out_ += (f || k ? " " : "") + std::to_string(creased->faces[f][k]);
        } else if (faceSet) {
            out_ += "<IndexedFaceSet " + solid + " creaseAngle='";
            appendShortest(out_, creased->creaseAngle);
            out_ += "' coordIndex='";
            for (std::size_t f = 0; f < creased->faces.size(); ++f) {
                if (f) out_ += ' ';
                for (std::int64_t p : creased->faces[f]) out_ += std::to_string(p) + ' ';
                out_ += "-1";
            }
        } else {
            // Without normals, flat shading, as glTF draws such a mesh (X3D's default would smooth it). Triangles
            // that fan over a convex, planar polygon as one face where that is shorter: the browser cuts it back
            // into them, and a flat face or given normals shade as they did (a smooth one's normals made by the
            // browser would weigh the face once, not once a triangle).
            std::string triangleIndices, faceIndices;
            for (const Triangle& t : primitive.triangles)
                for (std::uint32_t i : t) triangleIndices += (triangleIndices.empty() ? "" : " ") + std::to_string(i);
            for (const std::vector<std::uint32_t>& polygon :
                 x3d::fanPolygons(primitive.triangles, positions, x3d::kMostTurnOfFlatPolygon)) {
                for (std::uint32_t i : polygon) faceIndices += (faceIndices.empty() ? "" : " ") + std::to_string(i);
                faceIndices += " -1";
            }
            polygons = faceIndices.size() + std::strlen("Face coordIndex") <
                       triangleIndices.size() + std::strlen("Triangle index");
            out_ += std::string(polygons ? "<IndexedFaceSet " : "<IndexedTriangleSet ") + solid +
                    (primitive.normals.empty() ? " normalPerVertex='false'" : "") +
                    (polygons ? " coordIndex='" + faceIndices : " index='" + triangleIndices);
        }
        out_ += "'>\n";
        auto writeValues = [&](const char* node, const char* field, const auto& values, int components,
                               auto transform) {
            out_ += std::string("<") + node + " " + field + "='";
            for (std::size_t i = 0; i < written.size(); ++i) {
                if (i) out_ += ' ';
                appendVector(out_, transform(values[written[i]]), components);
            }
            out_ += "'/>\n";
        };
        auto same = [](const auto& v) { return v; };
        writeValues("Coordinate", "point", positions, 3, same);
        // Unit normals to 4 decimals (within 0.01 degree; GLB output keeps 10 bits, about 0.1 degree).
        if (!primitive.normals.empty() && !creased)
            writeValues("Normal", "vector", primitive.normals, 3, [](const Eigen::Vector3d& n) -> Eigen::Vector3d {
                return n.unaryExpr([](double x) { return roundedDecimals(x, kNormalDecimals); });
            });
        if (tangents) {
            std::vector<Eigen::Vector4d> values(primitive.positions.size());
            for (std::size_t v = 0; v < values.size(); ++v)
                values[v] = Eigen::Map<const Eigen::Vector4d>(tangents->values.data() + 4 * v);
            // Unit directions to the normals' decimals, the handedness as it is.
            writeValues("Tangent", "vector", values, 4, [](const Eigen::Vector4d& t) -> Eigen::Vector4d {
                Eigen::Vector4d out = t;
                for (int c = 0; c < 3; ++c) out[c] = roundedDecimals(t[c], kNormalDecimals);
                return out;
            });
        }
        // v flipped back to X3D's, each value as float32 (as glTF stores it and browsers draw it), printed as the
        // shortest float: 1 - (1 - 0.0015) as 0.0015, not 0.0014999999999999458.
        const auto flipped = [](const Eigen::Vector2d& t) {
            return Eigen::Vector2d(asFloat32(t.x()), asFloat32(1 - t.y()));
        };
        if (!texcoords.empty() && texcoordSets.size() == 1)
            writeValues("TextureCoordinate", "point", texcoords, 2, flipped);
        if (!texcoords.empty() && texcoordSets.size() > 1) {
            out_ += "<MultiTextureCoordinate>\n";
            for (std::size_t c = 0; c < texcoordSets.size(); ++c) {
                const std::string node = "TextureCoordinate mapping='" + escapedMarkup(channels[c].mapping) + "'";
                writeValues(node.c_str(), "point", texcoordSets[c], 2, flipped);
            }
            out_ += "</MultiTextureCoordinate>\n";
        }
        if (!primitive.colors.empty()) writeColors(primitive, written);
        const std::string node = faceSet || polygons ? "IndexedFaceSet" : "IndexedTriangleSet";
        out_ += "</" + node + ">\n";
        shareGeometry(geometryStart, node);
        out_ += "</Shape>\n";
    }

    // A primitive as the X3D node it was read from (X3dGeometrySource): the browser makes its triangles again.
    void writeSourceShape(const Primitive& primitive) {
        out_ += "<Shape>\n";
        writeAppearance(primitive.material);
        const std::size_t geometryStart = out_.size();
        const std::string& xml = primitive.x3dSource->xml;
        out_ += xml + "\n";
        shareGeometry(geometryStart, xml.substr(1, xml.find_first_of(" />") - 1));
        out_ += "</Shape>\n";
    }

    // `count` triangles of zero area at one point, in a shape of their own: they draw nothing, and browsers count
    // them as they counted those of the input (withoutZeroAreaTriangles). One convex face of count + 2 corners,
    // which the browser cuts into a fan of `count` triangles: 2 bytes a triangle.
    void writeZeroAreaShape(const Eigen::Vector3d& at, std::size_t count) {
        out_ += "<Shape>\n";
        const std::size_t geometryStart = out_.size();
        out_ += "<IndexedFaceSet coordIndex='0";
        for (std::size_t i = 1; i < count + 2; ++i) out_ += " 0";
        out_ += "'><Coordinate point='";
        appendVector(out_, at, 3);
        out_ += "'/></IndexedFaceSet>\n";
        shareGeometry(geometryStart, "IndexedFaceSet");
        out_ += "</Shape>\n";
    }

    // Lines as an IndexedLineSet, points as a PointSet (each vertex a point), drawn unlit as glTF's viewers draw
    // them (writeUnlitAppearance); normals and texture coordinates, which neither draws, left out. Positions
    // rounded as a triangle set's are.
    void writeUnlitShape(const Primitive& primitive) {
        out_ += "<Shape>\n";
        writeUnlitAppearance(primitive.material);
        const std::optional<int> decimals = positionDecimals(primitive, options_);
        const auto round = [&](double x) { return decimals ? roundedDecimals(x, *decimals) : x; };
        const bool lines = primitive.topology == Topology::Lines;
        const std::size_t geometryStart = out_.size();
        if (lines) {
            out_ += "<IndexedLineSet coordIndex='";
            for (const std::vector<std::uint32_t>& polyline : polylinesOf(primitive.lines)) {
                if (out_.back() != '\'') out_ += ' ';
                for (std::uint32_t v : polyline) out_ += std::to_string(v) + ' ';
                out_ += "-1";
            }
            out_ += "'>\n";
        } else {
            out_ += "<PointSet>\n";
        }
        out_ += "<Coordinate point='";
        for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
            if (v) out_ += ' ';
            appendVector(out_, primitive.positions[v], 3, round);
        }
        out_ += "'/>\n";
        if (!primitive.colors.empty()) {
            std::vector<std::uint32_t> written(primitive.positions.size());
            for (std::uint32_t v = 0; v < written.size(); ++v) written[v] = v;
            writeColors(primitive, written);
        }
        out_ += lines ? "</IndexedLineSet>\n" : "</PointSet>\n";
        shareGeometry(geometryStart, lines ? "IndexedLineSet" : "PointSet");
        out_ += "</Shape>\n";
    }

    // The geometry node just written from `start`, where an earlier Shape wrote the same text (one part drawn in
    // several materials: a family of classes), becomes a USE of that one, which gets a DEF (withDefs).
    void shareGeometry(std::size_t start, const std::string& node) {
        const std::string_view text = std::string_view(out_).substr(start);
        std::vector<WrittenGeometry>& same = geometries_[std::hash<std::string_view>()(text)];
        const auto earlier = std::find_if(same.begin(), same.end(), [&](const WrittenGeometry& g) {
            return std::string_view(out_).substr(g.start, g.length) == text;
        });
        if (earlier == same.end()) {
            // Keyed by where it starts: a key of its own.
            definable_["geometry@" + std::to_string(start)] = {out_.find_first_of(" />", start), {}};
            same.push_back({start, text.size()});
            return;
        }
        std::string& def = definable_.at("geometry@" + std::to_string(earlier->start)).def;
        if (def.empty()) def = uniqueName("geometry");
        out_.resize(start);
        out_ += "<" + node + " USE='" + def + "'/>\n";
    }

    // The text with a DEF in each node that a later node USEs.
    std::string withDefs() {
        std::vector<std::pair<std::size_t, std::string>> defs;  // where (after the node's name), what
        for (const auto& [key, node] : definable_)
            if (!node.def.empty()) defs.push_back({node.at, " DEF='" + node.def + "'"});
        if (defs.empty()) return std::move(out_);
        std::sort(defs.begin(), defs.end());
        std::string text;
        text.reserve(out_.size() + defs.size() * 24);
        std::size_t from = 0;
        for (const auto& [at, def] : defs) {
            text.append(out_, from, at - from);
            text += def;
            from = at;
        }
        text.append(out_, from);
        return text;
    }

    // glTF's COLOR_0 (linear, multiplying the base colour) as X3D's Color, or ColorRGBA where an alpha is below 1:
    // as it is for PhysicalMaterial, which multiplies it the same; for Phong's Material and UnlitMaterial, whose
    // colour it takes the place of, the base colour multiplied in and sRGB-encoded as that colour is, each value
    // the shortest that the reader's decoding and division by the base colour (vertexColorsAsGltf) give back.
    void writeColors(const Primitive& primitive, const std::vector<std::uint32_t>& written) {
        const Material* material =
            primitive.material >= 0 ? &scene_.materials[std::size_t(primitive.material)] : nullptr;
        // Lines and points are written with Phong's Material (writeUnlitAppearance).
        const bool linear =
            material && primitive.topology == Topology::Triangles && x3d::needsPhysicalMaterial(*material);
        const Eigen::Vector3d base =
            material ? Eigen::Vector3d(material->baseColorFactor.head<3>()) : Eigen::Vector3d::Ones();
        const bool rgba =
            std::any_of(written.begin(), written.end(), [&](std::uint32_t v) { return primitive.colors[v][3] != 1; });
        out_ += rgba ? "<ColorRGBA color='" : "<Color color='";
        for (std::size_t i = 0; i < written.size(); ++i) {
            if (i) out_ += ' ';
            Eigen::Vector4d color = primitive.colors[written[i]];
            if (!linear)
                for (int c = 0; c < 3; ++c) {
                    const double b = base[c], l = color[c];
                    color[c] = b > 0 ? shortestReadingBack(linearToSrgb(l * b), l,
                                                           [b](double s) { return srgbToLinear(s) / b; })
                                     : 0;
                }
            appendVector(out_, color, rgba ? 4 : 3);
        }
        out_ += "'/>\n";
    }

    const Scene& scene_;
    const WriteOptions& options_;
    fs::path file_;
    std::string out_;
    std::vector<bool> written_;
    std::set<int> materialWritten_, unlitMaterialWritten_;
    TranslucentTextures translucentTexture_{scene_.textures};
    std::set<int> blendedByColors_;  // materials AUTO blends for their vertex colours (write)
    struct WrittenGeometry {
        std::size_t start, length;  // in out_
    };
    std::unordered_map<std::size_t, std::vector<WrittenGeometry>> geometries_;  // by the hash of their text
    std::vector<int> sameImage_ = firstTextureOfSameImage(scene_.textures);
    std::set<int> textureWritten_;
    std::set<std::string> names_;
    std::map<int, std::string> nodeDef_;  // animated node -> its DEF
    struct DefinableNode {
        std::size_t at;   // in out_, just after the node's name
        std::string def;  // where a later node USEs it
    };
    std::map<std::string, DefinableNode> definable_;  // "mesh3", "material0", "texture2" (definable)
    std::vector<int> drawers_;                        // by mesh: the nodes that draw it
    std::vector<int> shapes_;                         // by mesh: shapesOf, -1 before it is counted
    std::vector<bool> namedByDrawer_;                 // by mesh: a node that draws it has its name
    bool version4_ = false;               // a material needs X3D 4.0 (x3d::needsX3d4)
};

std::string gzip(const std::string& text, const fs::path& file) {
    z_stream stream{};
    if (deflateInit2(&stream, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw FileError(file, "cannot start gzip compression");
    std::string out(deflateBound(&stream, static_cast<uLong>(text.size())), '\0');
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    stream.avail_in = static_cast<uInt>(text.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = deflate(&stream, Z_FINISH);
    deflateEnd(&stream);
    if (status != Z_STREAM_END) throw FileError(file, "gzip compression failed");
    out.resize(stream.total_out);
    return out;
}

}  // namespace

bool x3dRefersToImageFile(const std::string& uri, const std::vector<std::uint8_t>& bytes) {
    if (bytes.empty() || uri.empty() || uri.rfind("data:", 0) == 0 || uri.find("://") != std::string::npos)
        return false;
    std::error_code error;
    return fs::is_regular_file(uri, error);
}

std::uintmax_t x3dReferencedImageBytes(const Scene& scene) {
    const std::vector<int> sameImage = firstTextureOfSameImage(scene.textures);
    std::set<int> images;
    for (const Material& material : scene.materials)
        for (const x3d::TextureField& field : x3d::materialTextures(material).fields)
            images.insert(sameImage[std::size_t(field.use->texture)]);
    std::uintmax_t bytes = 0;
    for (int image : images) {
        const Texture& texture = scene.textures[std::size_t(image)];
        if (x3dRefersToImageFile(texture.uri, texture.bytes)) bytes += texture.bytes.size();
        if (texture.fallback && x3dRefersToImageFile(texture.fallback->uri, texture.fallback->bytes))
            bytes += texture.fallback->bytes.size();
    }
    return bytes;
}

std::size_t x3dMeshBytes(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.drawsNothing()) return 0;
    // The file with a node drawing the mesh, less the file with the node alone.
    Scene scene;
    scene.meshes.push_back({"", {primitive}, "", {}});
    scene.meshes[0].primitives[0].material = -1;
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    WriteOptions plain = options;
    plain.extrasJson.clear();
    const std::size_t withMesh = X3dWriter(scene, plain).write().size();
    scene.nodes[0].mesh = -1;
    return withMesh - X3dWriter(scene, plain).write().size();
}

std::size_t x3dNodeBytes(const Node& node) {
    // A file whose one mesh two nodes draw (a Group, which the second USEs), with and without `node` drawing it
    // too: the Group is the mesh's, once.
    Scene scene;
    Primitive triangle;
    triangle.positions = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    triangle.triangles = {{0, 1, 2}};
    scene.meshes.push_back({"", {triangle}, "", {}});
    scene.nodes.resize(3);
    scene.nodes[0].mesh = scene.nodes[1].mesh = 0;
    scene.nodes[2] = node;
    scene.nodes[2].mesh = 0;
    scene.nodes[2].children.clear();
    scene.roots = {0, 1, 2};
    const std::size_t withNode = X3dWriter(scene, {}).write().size();
    scene.roots = {0, 1};
    scene.nodes.pop_back();
    return withNode - X3dWriter(scene, {}).write().size();
}

void writeX3d(const Scene& scene, const fs::path& file, const WriteOptions& options) {
    std::string text = X3dWriter(scene, options, file).write();
    std::string extension = file.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    writeFileAtomically(file, extension == ".x3dz" ? gzip(text, file) : text);
}

}  // namespace symcompress
