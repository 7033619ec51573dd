// X3D geometry nodes: the face and triangle sets, and the primitives (x3d_primitives.cpp).
#include "x3d_reader.hpp"

#include "symcompress/detail/triangulate_polygon.hpp"
#include "x3d_crease_normals.hpp"
#include "x3d_faces.hpp"
#include "x3d_polygons.hpp"
#include "x3d_primitives.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

namespace symcompress {
namespace fs = std::filesystem;
namespace {

// More texture coordinate sets than a material's five textures can use are not kept (TEXCOORD_0 to _7).
constexpr std::size_t kMaxTexcoordSets = 8;
// Arc2D's and ArcClose2D's default endAngle, the SFFloat nearest a quarter turn as X3D writes it.
constexpr double kQuarterTurn = 1.570796;

// Whether a face of more than 3 corners bends: a triangle of the fan the browser cuts it into (X_ITE, convex
// faces) turns from the face's own normal (Newell's), which the browser shades all of it with where it is flat, by
// more than the writer lets a flat polygon turn (x3d_polygons.hpp).
bool anyFaceBends(const std::vector<x3d::Face>& faces, const std::vector<double>& points) {
    const std::size_t count = points.size() / 3;
    auto point = [&](std::int64_t p) { return Eigen::Vector3d(points[3 * p], points[3 * p + 1], points[3 * p + 2]); };
    for (const x3d::Face& face : faces) {
        if (face.size() <= 3 ||
            std::any_of(face.begin(), face.end(), [&](std::int64_t p) { return p < 0 || std::size_t(p) >= count; }))
            continue;
        Eigen::Vector3d newell = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < face.size(); ++k)
            newell += point(face[k]).cross(point(face[(k + 1) % face.size()]));
        if (!(newell.norm() > 0)) continue;
        newell.normalize();
        for (std::size_t k = 1; k + 1 < face.size(); ++k) {
            const Eigen::Vector3d n = (point(face[k]) - point(face[0])).cross(point(face[k + 1]) - point(face[0]));
            if (n.norm() > 0 && n.normalized().dot(newell) < std::cos(x3d::kMostTurnOfFlatPolygon)) return true;
        }
    }
    return false;
}

// The geometry nodes read as faces (readFaceSet).
const std::set<std::string> kFaceSets = {"IndexedFaceSet",
                                         "IndexedTriangleSet",
                                         "TriangleSet",
                                         "IndexedTriangleStripSet",
                                         "IndexedTriangleFanSet",
                                         "TriangleStripSet",
                                         "TriangleFanSet",
                                         "IndexedQuadSet",
                                         "QuadSet",
                                         "ElevationGrid",
                                         "Extrusion"};
// The most points an ElevationGrid or Extrusion may make (2^26, some 3 GB of primitives): more is a mistake.
constexpr std::int64_t kMostMadePoints = std::int64_t(1) << 26;
// A colour index where the line set's index lists hold none (a short colorIndex): not a colour of its Color node.
constexpr std::int64_t kMissingColor = std::numeric_limits<std::int64_t>::max();

// One corner of a polyline: a point of the Coordinate node and the index of its colour (-1: none).
struct LineCorner {
    std::int64_t point, color;
};
using Polyline = std::vector<LineCorner>;

// The vertices of a line or point set: one for each pair of point and colour it draws, added at its first use.
class LineVertices {
public:
    LineVertices(const X3dPointsAndColors& data, Primitive& out) : data_(data), out_(out) {}

    std::uint32_t operator()(const LineCorner& corner) {
        const std::uint32_t next = std::uint32_t(out_.positions.size());
        auto [entry, inserted] = vertexOf_.try_emplace({corner.point, corner.color}, next);
        if (!inserted) return entry->second;
        const double* p = data_.points.data() + 3 * corner.point;
        out_.positions.emplace_back(p[0], p[1], p[2]);
        if (corner.color >= 0) {
            Eigen::Vector4d color(1, 1, 1, 1);
            for (int c = 0; c < data_.colorComponents; ++c)
                color[c] = data_.colors[std::size_t(data_.colorComponents * corner.color + c)];
            out_.colors.push_back(color);
        }
        return entry->second;
    }

private:
    const X3dPointsAndColors& data_;
    Primitive& out_;
    std::map<std::pair<std::int64_t, std::int64_t>, std::uint32_t> vertexOf_;
};

// An IndexedLineSet's polylines: coordIndex split at its -1s, each corner with its colour as X3D 3.3's
// IndexedLineSet indexes it: per vertex (colorPerVertex, the default) by colorIndex laid out as coordIndex is,
// else by the point; per polyline by colorIndex's i-th value, else i.
std::vector<Polyline> indexedPolylines(const std::vector<std::int64_t>& coordIndex,
                                       const std::vector<std::int64_t>& colorIndex, bool colorPerVertex, bool colored) {
    const auto indexed = [&](std::size_t i) { return i < colorIndex.size() ? colorIndex[i] : kMissingColor; };
    std::vector<Polyline> polylines(1);
    for (std::size_t k = 0; k < coordIndex.size(); ++k) {
        if (coordIndex[k] < 0) {
            polylines.emplace_back();
            continue;
        }
        std::int64_t color = -1;
        const std::size_t line = polylines.size() - 1;
        if (colored && colorPerVertex) color = colorIndex.empty() ? coordIndex[k] : indexed(k);
        if (colored && !colorPerVertex) color = colorIndex.empty() ? std::int64_t(line) : indexed(line);
        polylines.back().push_back({coordIndex[k], color});
    }
    return polylines;
}

}  // namespace

bool X3dReader::readGeometry(const pugi::xml_node& geometry, Primitive& out,
                             std::vector<std::string>& texcoordMappings) {
    const std::string type = geometry.name();
    if (kFaceSets.count(type)) {
        readFaceSet(geometry, out, texcoordMappings);
    } else if (type == "Box") {
        out = x3d::tessellateBox(vector3(geometry, "size", Eigen::Vector3d(2, 2, 2)));
    } else if (type == "Sphere") {
        out = x3d::tessellateSphere(scalar(geometry, "radius", 1));
    } else if (type == "Cylinder") {
        const double radius = scalar(geometry, "radius", 1);
        out = x3d::tessellateCylinder(radius, scalar(geometry, "height", 2), boolean(geometry, "side", true),
                                      boolean(geometry, "bottom", true), boolean(geometry, "top", true));
    } else if (type == "Cone") {
        out = x3d::tessellateCone(scalar(geometry, "bottomRadius", 1), scalar(geometry, "height", 2),
                                  boolean(geometry, "side", true), boolean(geometry, "bottom", true));
    } else if (type == "Rectangle2D") {
        const std::vector<double> size = numbers(geometry, "size");
        out = x3d::tessellateRectangle2D(size.size() == 2 ? Eigen::Vector2d(size[0], size[1]) : Eigen::Vector2d(2, 2));
    } else if (type == "Disk2D") {
        out = x3d::tessellateDisk2D(scalar(geometry, "innerRadius", 0), scalar(geometry, "outerRadius", 1));
    } else if (type == "TriangleSet2D") {
        out = x3d::triangleSet2D(points2D(geometry, "vertices"));
    } else if (type == "Circle2D") {
        out = x3d::arc2D(scalar(geometry, "radius", 1), 0, 0);
    } else if (type == "Arc2D") {
        out = x3d::arc2D(scalar(geometry, "radius", 1), scalar(geometry, "startAngle", 0),
                         scalar(geometry, "endAngle", kQuarterTurn));
    } else if (type == "ArcClose2D") {
        out = x3d::tessellateArcClose2D(scalar(geometry, "radius", 1), scalar(geometry, "startAngle", 0),
                                        scalar(geometry, "endAngle", kQuarterTurn),
                                        std::string(geometry.attribute("closureType").value()) == "CHORD");
    } else if (type == "Polyline2D") {
        out = x3d::polyline2D(points2D(geometry, "lineSegments"));
    } else if (type == "Polypoint2D") {
        out = x3d::polypoint2D(points2D(geometry, "point"));
    } else if (type == "IndexedLineSet" || type == "LineSet") {
        return readLineSet(geometry, out, type == "IndexedLineSet");
    } else if (type == "PointSet") {
        return readPointSet(geometry, out);
    } else {
        ++skippedGeometry_[type];
        return false;
    }
    return true;
}

std::string X3dReader::selfContainedXml(const pugi::xml_node& geometry) const {
    pugi::xml_document document;
    const pugi::xml_node copy = document.append_copy(geometry);
    // Depth first: a USE becomes a copy of its DEF's node, whose own USEs are replaced in turn; a USE that names
    // nothing known, or a node it is inside of, is left out.
    std::set<std::string> inside;
    auto inlineUses = [&](pugi::xml_node node, auto& self) -> void {
        const std::string def = node.attribute("DEF").value();
        node.remove_attribute("DEF");
        if (!def.empty()) inside.insert(def);
        for (pugi::xml_node child = node.first_child(); child;) {
            const pugi::xml_node next = child.next_sibling();
            if (child.type() == pugi::node_element) {
                if (const pugi::xml_attribute use = child.attribute("USE")) {
                    const auto named = definitions_.find(use.value());
                    if (named != definitions_.end() && !inside.count(use.value()))
                        self(node.insert_copy_before(named->second, child), self);
                    node.remove_child(child);
                } else {
                    self(child, self);
                }
            }
            child = next;
        }
        if (!def.empty()) inside.erase(def);
    };
    inlineUses(copy, inlineUses);
    std::ostringstream text;
    copy.print(text, "", pugi::format_raw);
    return text.str();
}

std::vector<Eigen::Vector2d> X3dReader::points2D(const pugi::xml_node& geometry, const char* field) const {
    const std::vector<double> values = numbers(geometry, field);
    if (values.size() % 2) fail(geometry, std::string(field) + ": not a multiple of 2");
    std::vector<Eigen::Vector2d> points;
    for (std::size_t i = 0; i + 1 < values.size(); i += 2) points.emplace_back(values[i], values[i + 1]);
    return points;
}

pugi::xml_node X3dReader::geometryChild(const pugi::xml_node& geometry, std::initializer_list<const char*> types) {
    for (const char* type : types)
        if (pugi::xml_node node = geometry.child(type)) {
            if (const pugi::xml_attribute def = node.attribute("DEF")) definitions_[def.value()] = node;
            return resolve(node);
        }
    return {};
}

void X3dReader::noteAbout(const pugi::xml_node& node, const std::string& problem) {
    const std::string def = node.attribute("DEF").value();
    notes_.insert(std::string(node.name()) + (def.empty() ? "" : " '" + def + "'") + ": " + problem);
}

bool X3dReader::readPointsAndColors(const pugi::xml_node& geometry, X3dPointsAndColors& out) {
    const pugi::xml_node coordinate = geometryChild(geometry, {"Coordinate", "CoordinateDouble"});
    if (!coordinate) {
        noteAbout(geometry, "no Coordinate; left out");
        return false;
    }
    out.points = numbers(coordinate, "point");
    if (out.points.size() % 3) {
        noteAbout(geometry, "its Coordinate's point values are not a multiple of 3; the last left out");
        out.points.resize(out.points.size() / 3 * 3);
    }
    if (const pugi::xml_node color = geometryChild(geometry, {"Color", "ColorRGBA"})) {
        out.colorComponents = std::strcmp(color.name(), "ColorRGBA") == 0 ? 4 : 3;
        out.colors = numbers(color, "color");
        if (out.colors.size() % std::size_t(out.colorComponents)) {
            noteAbout(geometry, std::string("its ") + color.name() + "'s values are not a multiple of " +
                                    std::to_string(out.colorComponents) + "; the last left out");
            out.colors.resize(out.colorCount() * std::size_t(out.colorComponents));
        }
    }
    return true;
}

// Lines as segments between the corners of each polyline. A corner naming no point splits its polyline; a corner
// without a colour of the Color node leaves every colour out (a primitive has colours on every vertex or none).
bool X3dReader::readLineSet(const pugi::xml_node& geometry, Primitive& out, bool indexed) {
    X3dPointsAndColors data;
    if (!readPointsAndColors(geometry, data)) return false;
    const bool colored = !data.colors.empty();
    std::vector<Polyline> polylines;
    if (indexed) {
        polylines = indexedPolylines(integers(geometry, "coordIndex"), integers(geometry, "colorIndex"),
                                     boolean(geometry, "colorPerVertex", true), colored);
    } else {
        // LineSet: polylines of vertexCount points each, taken in order; its colours go with its points.
        const std::int64_t points = std::int64_t(data.pointCount());
        std::int64_t next = 0;
        for (std::int64_t count : integers(geometry, "vertexCount")) {
            if (count < 2) noteAbout(geometry, "a vertexCount below 2 draws nothing");
            if (count > points - next)
                noteAbout(geometry, "vertexCount counts more than its " + std::to_string(points) + " points");
            Polyline& polyline = polylines.emplace_back();
            for (std::int64_t k = 0; k < count && next < points; ++k, ++next)
                polyline.push_back({next, colored ? next : -1});
        }
    }
    std::vector<Polyline> valid;
    bool colorsKept = colored;
    for (const Polyline& polyline : polylines) {
        valid.emplace_back();
        for (const LineCorner& corner : polyline) {
            if (corner.point >= std::int64_t(data.pointCount())) {
                noteAbout(geometry, "a point index beyond its " + std::to_string(data.pointCount()) +
                                        " points (the polyline is broken there)");
                valid.emplace_back();
                continue;
            }
            if (colored && (corner.color < 0 || corner.color >= std::int64_t(data.colorCount()))) colorsKept = false;
            valid.back().push_back(corner);
        }
    }
    if (colored && !colorsKept) noteAbout(geometry, "a colour index beyond its colours; the colours left out");
    out.topology = Topology::Lines;
    LineVertices vertex(data, out);
    for (Polyline& polyline : valid) {
        if (!colorsKept)
            for (LineCorner& corner : polyline) corner.color = -1;
        for (std::size_t k = 1; k < polyline.size(); ++k) {
            const Segment segment{vertex(polyline[k - 1]), vertex(polyline[k])};
            if (segment[0] != segment[1]) out.lines.push_back(segment);
        }
    }
    return true;
}

// Every point drawn, with the colour of the same index where the Color node has one for each.
bool X3dReader::readPointSet(const pugi::xml_node& geometry, Primitive& out) {
    X3dPointsAndColors data;
    if (!readPointsAndColors(geometry, data)) return false;
    const bool colored = !data.colors.empty() && data.colorCount() >= data.pointCount();
    if (!data.colors.empty() && !colored) noteAbout(geometry, "fewer colours than points; the colours left out");
    out.topology = Topology::Points;
    LineVertices vertex(data, out);
    for (std::int64_t p = 0; p < std::int64_t(data.pointCount()); ++p) vertex({p, colored ? p : -1});
    return true;
}

std::vector<x3d::Face> X3dReader::listedFaces(const pugi::xml_node& geometry, std::size_t pointCount) {
    const std::string type = geometry.name();
    auto consecutive = [&] {  // the points in their order (TriangleSet, QuadSet)
        std::vector<std::int64_t> all(pointCount);
        for (std::size_t p = 0; p < pointCount; ++p) all[p] = std::int64_t(p);
        return all;
    };
    if (type == "IndexedFaceSet") {
        std::vector<x3d::Face> faces(1);
        for (std::int64_t value : integers(geometry, "coordIndex")) {
            if (value >= 0)
                faces.back().push_back(value);
            else if (!faces.back().empty())
                faces.emplace_back();
        }
        if (faces.back().empty()) faces.pop_back();  // the last -1 is optional
        return faces;
    }
    if (type == "IndexedTriangleSet" || type == "TriangleSet") {
        const std::vector<std::int64_t> index = type == "TriangleSet" ? consecutive() : integers(geometry, "index");
        std::vector<x3d::Face> faces;
        for (std::size_t i = 0; i + 2 < index.size(); i += 3) faces.push_back({index[i], index[i + 1], index[i + 2]});
        return faces;
    }
    if (type == "IndexedTriangleStripSet") return x3d::indexedStrips(integers(geometry, "index"));
    if (type == "IndexedTriangleFanSet") return x3d::indexedFans(integers(geometry, "index"));
    if (type == "IndexedQuadSet") return x3d::quads(integers(geometry, "index"));
    if (type == "QuadSet") return x3d::quads(consecutive());
    const bool strips = type == "TriangleStripSet";
    const std::vector<std::int64_t> counts = integers(geometry, strips ? "stripCount" : "fanCount");
    std::int64_t named = 0;
    for (std::int64_t count : counts) named += std::max<std::int64_t>(count, 0);
    if (named > std::int64_t(pointCount))
        noteAbout(geometry, std::string(strips ? "stripCount" : "fanCount") + " names " + std::to_string(named) +
                                " points, its Coordinate has " + std::to_string(pointCount) + "; the rest left out");
    return strips ? x3d::countedStrips(counts, std::int64_t(pointCount))
                  : x3d::countedFans(counts, std::int64_t(pointCount));
}

x3d::Faces X3dReader::madeFaces(const pugi::xml_node& geometry) {
    if (std::strcmp(geometry.name(), "ElevationGrid") == 0) {
        const std::vector<std::int64_t> x = integers(geometry, "xDimension"), z = integers(geometry, "zDimension");
        const std::int64_t xDimension = x.empty() ? 0 : x[0], zDimension = z.empty() ? 0 : z[0];
        const std::vector<double> height = numbers(geometry, "height");
        if (xDimension >= 2 && zDimension >= 2) {
            if (xDimension * zDimension > kMostMadePoints)
                fail(geometry, std::to_string(xDimension) + " by " + std::to_string(zDimension) + " points: too many");
            if (height.size() < std::size_t(xDimension * zDimension))
                noteAbout(geometry, std::to_string(height.size()) + " heights for " +
                                        std::to_string(xDimension * zDimension) + " points: the others at 0");
        }
        return x3d::elevationGrid(xDimension, zDimension, scalar(geometry, "xSpacing", 1),
                                  scalar(geometry, "zSpacing", 1), height);
    }
    x3d::ExtrusionFields fields;
    // A field of vectors of `size` numbers each, made by `make`; X3D's default (as `out` holds) where it is absent.
    auto vectors = [&](const char* field, std::size_t size, auto& out, auto make) {
        if (!geometry.attribute(field)) return;
        const std::vector<double> values = numbers(geometry, field);
        if (values.size() % size) fail(geometry, std::string(field) + ": not a multiple of " + std::to_string(size));
        out.clear();
        for (std::size_t i = 0; i < values.size(); i += size) out.push_back(make(values.data() + i));
    };
    vectors("spine", 3, fields.spine, [](const double* v) { return Eigen::Vector3d(v[0], v[1], v[2]); });
    vectors("crossSection", 2, fields.crossSection, [](const double* v) { return Eigen::Vector2d(v[0], v[1]); });
    vectors("scale", 2, fields.scale, [](const double* v) { return Eigen::Vector2d(v[0], v[1]); });
    vectors("orientation", 4, fields.orientation,
            [](const double* v) { return rotationField({v[0], v[1], v[2], v[3]}); });
    if (std::int64_t(fields.spine.size() * fields.crossSection.size()) > kMostMadePoints)
        fail(geometry, std::to_string(fields.spine.size()) + " spine points by " +
                           std::to_string(fields.crossSection.size()) + " cross-section points: too many");
    fields.beginCap = boolean(geometry, "beginCap", true);
    fields.endCap = boolean(geometry, "endCap", true);
    return x3d::extrusion(fields);
}

void X3dReader::readFaceSet(const pugi::xml_node& geometry, Primitive& out,
                            std::vector<std::string>& texcoordMappings) {
    const std::string type = geometry.name();
    const bool indexLists = type == "IndexedFaceSet";  // its own normalIndex, colorIndex and texCoordIndex
    auto child = [&](std::initializer_list<const char*> types) { return geometryChild(geometry, types); };
    x3d::Faces made;
    if (type == "ElevationGrid" || type == "Extrusion") {
        made = madeFaces(geometry);
    } else {
        const pugi::xml_node coordinate = child({"Coordinate", "CoordinateDouble"});
        if (!coordinate) fail(geometry, "no Coordinate");
        made.points = numbers(coordinate, "point");
        if (made.points.size() % 3) fail(coordinate, "the number of point values is not a multiple of 3");
        made.faces = listedFaces(geometry, made.points.size() / 3);
    }
    const std::vector<double>& points = made.points;
    const std::vector<x3d::Face>& faces = made.faces;
    const std::size_t pointCount = points.size() / 3;
    const pugi::xml_node normalNode = child({"Normal"});
    const pugi::xml_node colorNode = child({"Color", "ColorRGBA"});
    // X3D 4's Tangent (xyz and the handedness w, as glTF's TANGENT), indexed as the normals are.
    const pugi::xml_node tangentNode = child({"Tangent"});
    // Texture coordinate sets: one TextureCoordinate, or a MultiTextureCoordinate's (X3D 4 materials pick theirs
    // by mapping); the first is TEXCOORD_0, the others TEXCOORD_1, ... All are indexed as the first is.
    std::vector<std::vector<double>> texcoordSets;
    if (const pugi::xml_node single = child({"TextureCoordinate"})) {
        texcoordSets.push_back(numbers(single, "point"));
        texcoordMappings.push_back(single.attribute("mapping").value());
    } else if (const pugi::xml_node multi = child({"MultiTextureCoordinate"})) {
        for (pugi::xml_node set : multi.children()) {
            if (set.type() != pugi::node_element || std::strncmp(set.name(), "Metadata", 8) == 0) continue;
            if (!knownUse(set, "a MultiTextureCoordinate")) continue;
            if (const pugi::xml_attribute def = set.attribute("DEF")) definitions_[def.value()] = set;
            const pugi::xml_node resolved = resolve(set);
            if (std::strcmp(resolved.name(), "TextureCoordinate") != 0) {
                notes_.insert(std::string("a MultiTextureCoordinate's ") + resolved.name() + " not carried through");
                continue;
            }
            if (texcoordSets.size() == kMaxTexcoordSets) {
                notes_.insert("texture coordinate sets beyond the first " + std::to_string(kMaxTexcoordSets) +
                              " left out");
                break;
            }
            texcoordSets.push_back(numbers(resolved, "point"));
            texcoordMappings.push_back(resolved.attribute("mapping").value());
        }
    }
    const bool ownTexcoords = texcoordSets.empty() && !made.texcoords.empty();  // the node's own
    if (ownTexcoords) {
        texcoordSets.push_back(made.texcoords);
        texcoordMappings.emplace_back();
    }
    // A further set of another size than the first cannot be indexed as it is: left out, and its mapping with it.
    for (std::size_t set = texcoordSets.size(); set-- > 1;)
        if (texcoordSets[set].size() != texcoordSets[0].size()) {
            notes_.insert("a MultiTextureCoordinate's TextureCoordinate '" + texcoordMappings[set] + "' has " +
                          std::to_string(texcoordSets[set].size() / 2) + " points, the first " +
                          std::to_string(texcoordSets[0].size() / 2) + "; left out");
            texcoordSets.erase(texcoordSets.begin() + long(set));
            texcoordMappings.erase(texcoordMappings.begin() + long(set));
        }
    std::vector<double> normalValues = normalNode ? numbers(normalNode, "vector") : std::vector<double>();
    const std::vector<double> colorValues = colorNode ? numbers(colorNode, "color") : std::vector<double>();
    const std::vector<double> tangentValues = tangentNode ? numbers(tangentNode, "vector") : std::vector<double>();
    const int colorComponents = colorNode && std::strcmp(colorNode.name(), "ColorRGBA") == 0 ? 4 : 3;
    const std::vector<double> texcoordValues = texcoordSets.empty() ? std::vector<double>() : texcoordSets[0];
    if (!texcoordValues.empty())
        for (std::size_t set = 1; set < texcoordSets.size(); ++set)
            out.attributes.push_back({"TEXCOORD_" + std::to_string(set), 2, {}});
    const bool ccw = boolean(geometry, "ccw", true);
    // Only an IndexedFaceSet's faces and an Extrusion's caps may be concave.
    const bool convex = !(indexLists || type == "Extrusion") || boolean(geometry, "convex", true);
    const bool normalPerVertex = boolean(geometry, "normalPerVertex", true);
    const bool colorPerVertex = boolean(geometry, "colorPerVertex", true);

    // Which entry of an attribute a corner uses: IndexedFaceSet has optional per-corner or per-face index
    // lists; the other nodes index attributes like the coordinates, or by face.
    auto indexList = [&](const char* field) {
        return indexLists ? integers(geometry, field) : std::vector<std::int64_t>();
    };
    const std::vector<std::int64_t> normalIndex = indexList("normalIndex"), colorIndex = indexList("colorIndex"),
                                    texcoordIndex = indexList("texCoordIndex");
    auto attributeIndex = [&](const std::vector<std::int64_t>& ownIndex, bool perVertex, std::size_t face,
                              std::size_t cornerInCoordIndex, std::int64_t point) -> std::int64_t {
        if (!indexLists) {
            if (perVertex) return point;
            return made.attributeFace.empty() ? std::int64_t(face) : made.attributeFace[face];
        }
        if (perVertex) {
            if (!ownIndex.empty()) return cornerInCoordIndex < ownIndex.size() ? ownIndex[cornerInCoordIndex] : -1;
            return point;
        }
        if (!ownIndex.empty()) return face < ownIndex.size() ? ownIndex[face] : -1;
        return static_cast<std::int64_t>(face);
    };

    struct CornerKey {
        std::int64_t point, normal, color, texcoord, tangent;
        bool operator<(const CornerKey& o) const {
            return std::tie(point, normal, color, texcoord, tangent) <
                   std::tie(o.point, o.normal, o.color, o.texcoord, o.tangent);
        }
    };
    std::map<CornerKey, std::uint32_t> vertexOf;
    // Without a Normal node, the normals the browser would make: flat (none, as glTF draws a mesh without
    // normals) unless normalPerVertex and, for an IndexedFaceSet, a creaseAngle above 0 ask for smoothing
    // (the triangle sets smooth across every shared point). A flat face of more than 3 corners has one normal
    // (X_ITE's: Newell's), which its triangles do not have where it bends: made for every face then.
    std::vector<std::int64_t> madeNormalOfCorner;
    if (!normalNode) {
        // The triangle, strip, fan and quad sets smooth across every shared point (a QuadSet's quad has its
        // own, as X_ITE's normal of a quad: Newell's).
        const bool creased = indexLists || type == "ElevationGrid" || type == "Extrusion";
        const double creaseAngle = !normalPerVertex ? 0 : creased ? scalar(geometry, "creaseAngle", 0) : M_PI;
        if (creaseAngle > 0 || anyFaceBends(faces, points))
            std::tie(normalValues, madeNormalOfCorner) = creasedNormals(faces, points, creaseAngle, ccw);
    }
    const bool hasNormals = !normalValues.empty(), hasColors = !colorValues.empty(),
               hasTexcoords = !texcoordValues.empty(), hasTangents = !tangentValues.empty();
    const std::size_t tangentAttribute = out.attributes.size();
    if (hasTangents) {
        if (tangentValues.size() % 4) fail(tangentNode, "the number of vector values is not a multiple of 4");
        out.attributes.push_back({"TANGENT", 4, {}});
    }
    std::size_t cornerInCoordIndex = 0, corner = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        std::vector<std::uint32_t> local;
        std::vector<Eigen::Vector3d> polygon;
        for (std::size_t k = 0; k < face.size(); ++k, ++cornerInCoordIndex, ++corner) {
            const std::int64_t point = face[k];
            if (point < 0 || static_cast<std::size_t>(point) >= pointCount)
                fail(geometry, "coordinate index " + std::to_string(point) + " out of range (" +
                                   std::to_string(pointCount) + " points)");
            CornerKey key{point, -1, -1, -1, -1};
            if (hasNormals)
                key.normal = !madeNormalOfCorner.empty()
                                 ? madeNormalOfCorner[corner]
                                 : attributeIndex(normalIndex, normalPerVertex, f, cornerInCoordIndex, point);
            if (hasColors) key.color = attributeIndex(colorIndex, colorPerVertex, f, cornerInCoordIndex, point);
            if (hasTexcoords)
                key.texcoord = ownTexcoords && !made.texcoordOfCorner.empty()
                                   ? made.texcoordOfCorner[corner]
                                   : attributeIndex(texcoordIndex, true, f, cornerInCoordIndex, point);
            if (hasTangents) key.tangent = attributeIndex(normalIndex, normalPerVertex, f, cornerInCoordIndex, point);
            auto check = [&](std::int64_t index, std::size_t available, const char* what) {
                if (index < 0 || static_cast<std::size_t>(index) >= available)
                    fail(geometry, std::string(what) + " index " + std::to_string(index) + " out of range");
            };
            if (hasNormals) check(key.normal, normalValues.size() / 3, "normal");
            if (hasColors) check(key.color, colorValues.size() / colorComponents, "colour");
            if (hasTangents) check(key.tangent, tangentValues.size() / 4, "tangent");
            if (hasTexcoords)
                for (const std::vector<double>& set : texcoordSets)
                    check(key.texcoord, set.size() / 2, "texture coordinate");
            auto [entry, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(out.positions.size()));
            if (inserted) {
                out.positions.emplace_back(points[3 * point], points[3 * point + 1], points[3 * point + 2]);
                if (hasNormals)
                    out.normals.emplace_back(normalValues[3 * key.normal], normalValues[3 * key.normal + 1],
                                             normalValues[3 * key.normal + 2]);
                if (hasTangents)
                    out.attributes[tangentAttribute].values.insert(out.attributes[tangentAttribute].values.end(),
                                                                   tangentValues.begin() + 4 * key.tangent,
                                                                   tangentValues.begin() + 4 * key.tangent + 4);
                if (hasColors) {
                    Eigen::Vector4d color(1, 1, 1, 1);
                    for (int c = 0; c < colorComponents; ++c) color[c] = colorValues[colorComponents * key.color + c];
                    out.colors.push_back(color);
                }
                if (hasTexcoords) {  // X3D's v points up, glTF's down
                    out.texcoords.emplace_back(texcoordValues[2 * key.texcoord],
                                               1 - texcoordValues[2 * key.texcoord + 1]);
                    for (std::size_t set = 1; set < texcoordSets.size(); ++set)
                        out.attributes[set - 1].values.insert(
                            out.attributes[set - 1].values.end(),
                            {texcoordSets[set][2 * key.texcoord], 1 - texcoordSets[set][2 * key.texcoord + 1]});
                }
            }
            local.push_back(entry->second);
            polygon.push_back(out.positions[entry->second]);
        }
        ++cornerInCoordIndex;  // the -1 that ended the face
        // A face of an IndexedFaceSet or an Extrusion's cap whose `convex` is TRUE (the default), or of another
        // node, as the browser cuts it: a fan from its first corner (X_ITE's triangulateConvexPolygon), triangles of
        // zero area too. Where a diagonal lies matters: a non-planar quad bends along it, and the texture of a small
        // alpha-blended card is sampled otherwise along it (the grass's cards: 1.5% of their pixels).
        const std::vector<Triangle> triangles = convex ? triangulateFace(polygon) : triangulatePolygon(polygon);
        if (triangles.empty()) ++degenerateFaces_;
        for (const Triangle& t : triangles)
            out.triangles.push_back(ccw ? Triangle{local[t[0]], local[t[1]], local[t[2]]}
                                        : Triangle{local[t[0]], local[t[2]], local[t[1]]});
    }
}

}  // namespace symcompress
