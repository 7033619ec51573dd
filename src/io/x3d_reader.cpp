// X3D reader (XML encoding, X3D 3.x and 4.0). Keeps the node hierarchy with local transforms; a USE of
// a Shape or geometry reuses the same symcompress Mesh, so that the file's instancing survives.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/detail/triangulate_polygon.hpp"
#include "x3d_fields.hpp"
#include "x3d_primitives.hpp"
#include "common/mime_type.hpp"

#include <Eigen/Geometry>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// X3D nodes that group children, with or without a transform of their own.
const std::set<std::string> kGroupingNodes = {"Group", "Transform", "Switch", "LOD", "Collision", "Anchor",
                                              "StaticGroup", "Billboard", "CADAssembly", "CADLayer", "CADPart",
                                              "CADFace", "Scene", "LayerSet", "Layer"};
// Bindable nodes of the scene's environment with no place in the scene model, kept as their XML text.
const std::set<std::string> kEnvironment = {"NavigationInfo", "Background", "Fog", "WorldInfo"};
// Nodes read where they are used (animations from their ROUTEs) or that hold nothing of the scene's.
const std::set<std::string> kReadElsewhere = {"ROUTE", "TimeSensor", "PositionInterpolator", "OrientationInterpolator",
                                              "ProtoDeclare", "ExternProtoDeclare", "IMPORT", "EXPORT"};
// Geometry nodes that draw something we do not read: reported once per type.
const std::set<std::string> kUnsupportedGeometry = {
    "Extrusion", "ElevationGrid", "Text", "PointSet", "LineSet", "IndexedLineSet", "NurbsPatchSurface",
    "NurbsTrimmedSurface", "NurbsCurve", "NurbsSweptSurface", "NurbsSwungSurface", "GeoElevationGrid",
    "Arc2D", "ArcClose2D", "Circle2D", "Disk2D", "Polyline2D", "Polypoint2D", "Rectangle2D", "TriangleSet2D",
    "QuadSet", "IndexedQuadSet", "IndexedTriangleFanSet", "IndexedTriangleStripSet", "TriangleFanSet",
    "TriangleStripSet"};

// How deep XML elements may nest in an X3D file (readNode's limit for the scene graph, 256, and room for
// the X3D and Scene elements and a node's fields).
constexpr int kMaxXmlDepth = 300;

class X3dReader {
public:
    X3dReader(const fs::path& file, Scene& scene, std::set<fs::path>& inlineStack)
        : file_(file), scene_(scene), inlineStack_(inlineStack) {}

    // Reads the file's Scene element into new nodes; returns the root nodes.
    std::vector<int> read();

private:
    [[noreturn]] void fail(const pugi::xml_node& node, const std::string& problem) const {
        throw FileError(file_, "<" + std::string(node.name()) + (node.attribute("DEF") ? " DEF='" + std::string(node.attribute("DEF").value()) + "'" : "") +
                                   ">: " + problem);
    }
    pugi::xml_node resolve(const pugi::xml_node& node) const;
    std::vector<double> numbers(const pugi::xml_node& node, const char* field) const;
    std::vector<std::int64_t> integers(const pugi::xml_node& node, const char* field) const;
    Eigen::Vector3d vector3(const pugi::xml_node& node, const char* field, const Eigen::Vector3d& fallback) const;
    double scalar(const pugi::xml_node& node, const char* field, double fallback) const;
    bool boolean(const pugi::xml_node& node, const char* field, bool fallback) const;
    Eigen::Matrix4d transformOf(const pugi::xml_node& node) const;

    void readChildren(const pugi::xml_node& parent, std::vector<int>& into, int depth);
    int readNode(const pugi::xml_node& node, int depth);
    int readShape(const pugi::xml_node& shape);
    int readMaterial(const pugi::xml_node& appearance);
    int readTexture(const pugi::xml_node& appearance);
    int addTexture(int& index, Texture texture);  // sets `index` (the ImageTexture's) and returns it
    bool readGeometry(const pugi::xml_node& geometry, Primitive& out);
    void readFaceSet(const pugi::xml_node& geometry, Primitive& out, bool indexedFaces);
    void readInline(const pugi::xml_node& node, std::vector<int>& into);
    void readAnimations();
    int readViewpoint(const pugi::xml_node& viewpoint);
    int readLight(const pugi::xml_node& light, int depth);
    void keepEnvironment(const pugi::xml_node& node);
    int addPlacedNode(const pugi::xml_node& source, const Eigen::Affine3d& placement, int camera, int light);

    fs::path file_;
    Scene& scene_;
    std::set<fs::path>& inlineStack_;
    pugi::xml_document document_;
    std::map<std::string, pugi::xml_node> definitions_;
    std::map<std::string, std::vector<int>> nodesOfTransform_;  // a DEF'd Transform's scene nodes (one per USE)
    std::map<const void*, int> meshOfShape_, materialOfAppearance_, textureOfNode_;
    std::map<std::string, int> skippedGeometry_;
    std::map<std::string, int> notKept_;  // other nodes with nothing to carry them in the scene model
    std::set<std::string> useStack_;
    std::set<std::string> notes_;
    std::size_t degenerateFaces_ = 0;  // faces with fewer than 3 distinct corners or no area
};

pugi::xml_node X3dReader::resolve(const pugi::xml_node& node) const {
    const pugi::xml_attribute use = node.attribute("USE");
    if (!use) return node;
    auto found = definitions_.find(use.value());
    if (found == definitions_.end())
        throw FileError(file_, "USE='" + std::string(use.value()) + "' refers to no DEF before it");
    return found->second;
}

std::vector<double> X3dReader::numbers(const pugi::xml_node& node, const char* field) const {
    std::vector<double> values;
    const pugi::xml_attribute attribute = node.attribute(field);
    if (!attribute) return values;
    if (!x3d::parseNumbers(attribute.value(), values)) fail(node, std::string("cannot read the numbers of ") + field);
    for (double v : values)
        if (!std::isfinite(v)) fail(node, std::string(field) + " contains NaN or infinite values");
    return values;
}

// An SFInt32 or MFInt32 field (indices, whichChoice): whole numbers that fit 32 bits, checked before they
// are converted.
std::vector<std::int64_t> X3dReader::integers(const pugi::xml_node& node, const char* field) const {
    const std::vector<double> values = numbers(node, field);
    std::vector<std::int64_t> out;
    out.reserve(values.size());
    for (double v : values) {
        if (!(v >= std::numeric_limits<std::int32_t>::min() && v <= std::numeric_limits<std::int32_t>::max()) ||
            v != std::floor(v))
            fail(node, std::string(field) + " holds " + std::to_string(v) + ", not a 32-bit integer");
        out.push_back(static_cast<std::int64_t>(v));
    }
    return out;
}

Eigen::Vector3d X3dReader::vector3(const pugi::xml_node& node, const char* field, const Eigen::Vector3d& fallback) const {
    const std::vector<double> values = numbers(node, field);
    if (values.empty()) return fallback;
    if (values.size() != 3) fail(node, std::string(field) + " needs 3 numbers");
    return {values[0], values[1], values[2]};
}

double X3dReader::scalar(const pugi::xml_node& node, const char* field, double fallback) const {
    const std::vector<double> values = numbers(node, field);
    return values.empty() ? fallback : values[0];
}

bool X3dReader::boolean(const pugi::xml_node& node, const char* field, bool fallback) const {
    const pugi::xml_attribute attribute = node.attribute(field);
    if (!attribute) return fallback;
    const std::string value = attribute.value();
    return value == "true" || value == "TRUE";
}

// RFC 4648 base64 (whitespace skipped, padding optional); false on any other character.
bool decodeBase64(const std::string& text, std::vector<std::uint8_t>& bytes) {
    bytes.clear();
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        int value;
        if (c >= 'A' && c <= 'Z') value = c - 'A';
        else if (c >= 'a' && c <= 'z') value = c - 'a' + 26;
        else if (c >= '0' && c <= '9') value = c - '0' + 52;
        else if (c == '+') value = 62;
        else if (c == '/') value = 63;
        else if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
        else return false;
        bits = (bits << 6) | std::uint32_t(value);
        if (++count == 4) {
            bytes.insert(bytes.end(), {std::uint8_t(bits >> 16), std::uint8_t(bits >> 8), std::uint8_t(bits)});
            bits = 0;
            count = 0;
        }
    }
    if (count == 1) return false;
    if (count == 2) bytes.push_back(std::uint8_t(bits >> 4));
    if (count == 3) bytes.insert(bytes.end(), {std::uint8_t(bits >> 10), std::uint8_t(bits >> 2)});
    return !bytes.empty();
}

Eigen::AngleAxisd rotationField(const std::vector<double>& values) {
    if (values.size() != 4) return Eigen::AngleAxisd::Identity();
    Eigen::Vector3d axis(values[0], values[1], values[2]);
    if (axis.norm() == 0) return Eigen::AngleAxisd::Identity();
    return Eigen::AngleAxisd(values[3], axis.normalized());
}

// X3D Transform (and CADPart): P' = T * C * R * SR * S * -SR * -C * P.
Eigen::Matrix4d X3dReader::transformOf(const pugi::xml_node& node) const {
    Eigen::Affine3d m = Eigen::Affine3d::Identity();
    const Eigen::Vector3d translation = vector3(node, "translation", Eigen::Vector3d::Zero());
    const Eigen::Vector3d center = vector3(node, "center", Eigen::Vector3d::Zero());
    const Eigen::Vector3d scale = vector3(node, "scale", Eigen::Vector3d::Ones());
    const Eigen::AngleAxisd rotation = rotationField(numbers(node, "rotation"));
    const Eigen::AngleAxisd scaleOrientation = rotationField(numbers(node, "scaleOrientation"));
    m.translate(translation).translate(center).rotate(rotation).rotate(scaleOrientation).scale(scale)
        .rotate(scaleOrientation.inverse()).translate(-center);
    return m.matrix();
}

std::vector<int> X3dReader::read() {
    const std::vector<unsigned char> bytes = readFileBytes(file_);
    if (bytes.empty()) throw FileError(file_, "the file is empty");
    std::vector<unsigned char> text = bytes;
    if (bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b) {
        // .x3dz: gzip-compressed XML.
        z_stream stream{};
        if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) throw FileError(file_, "cannot start gzip decompression");
        stream.next_in = const_cast<unsigned char*>(bytes.data());
        stream.avail_in = static_cast<uInt>(bytes.size());
        text.clear();
        unsigned char buffer[1 << 16];
        int status;
        do {
            stream.next_out = buffer;
            stream.avail_out = sizeof buffer;
            status = inflate(&stream, Z_NO_FLUSH);
            if (status != Z_OK && status != Z_STREAM_END) {
                inflateEnd(&stream);
                throw FileError(file_, "broken gzip data");
            }
            text.insert(text.end(), buffer, buffer + (sizeof buffer - stream.avail_out));
        } while (status != Z_STREAM_END);
        inflateEnd(&stream);
    }
    const pugi::xml_parse_result parsed = document_.load_buffer(text.data(), text.size());
    if (!parsed)
        throw FileError(file_, std::string("malformed XML at byte ") + std::to_string(parsed.offset) + ": " +
                                   parsed.description());
    // Nesting is bounded once for the whole document, without recursion (pugixml's traverse is a loop), so that
    // no code after this that recurses over elements (the environment nodes' copy, pugixml's own) can exhaust
    // the stack; the nodes of the scene graph have their tighter limit in readNode.
    struct DepthLimit : pugi::xml_tree_walker {
        bool tooDeep = false;
        bool for_each(pugi::xml_node&) override { return !(tooDeep = depth() > kMaxXmlDepth); }
    } limit;
    document_.traverse(limit);
    if (limit.tooDeep) throw FileError(file_, "XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels");
    // symcompress's digest of the original, for symdecompress (see the X3D writer).
    for (pugi::xml_node meta : document_.child("X3D").child("head").children("meta"))
        if (std::string(meta.attribute("name").value()) == "symcompress") scene_.extrasJson = meta.attribute("content").value();
    pugi::xml_node scene = document_.child("X3D").child("Scene");
    if (!scene) throw FileError(file_, "no <X3D><Scene> element (only the XML encoding of X3D is read)");
    std::vector<int> roots;
    readChildren(scene, roots, 0);
    readAnimations();
    const std::string name = file_.filename().string();
    for (const auto& [type, count] : skippedGeometry_)
        scene_.warnings.push_back(name + ": " + std::to_string(count) + " " + type + " node" + (count > 1 ? "s" : "") +
                                  " skipped (not supported)");
    if (!notKept_.empty()) {
        std::string list;
        for (const auto& [type, count] : notKept_) list += (list.empty() ? "" : ", ") + std::to_string(count) + " " + type;
        scene_.warnings.push_back(name + ": not kept (symcompress keeps geometry, materials, animations of transforms, " +
                                  "viewpoints and lights): " + list);
    }
    for (const std::string& note : notes_) scene_.warnings.push_back(name + ": " + note);
    if (degenerateFaces_)
        scene_.warnings.push_back(name + ": " + std::to_string(degenerateFaces_) +
                                  " faces with fewer than 3 distinct corners or no area skipped");
    return roots;
}

// A ROUTE from a Position- or OrientationInterpolator's value to a Transform's translation, rotation or
// scale, the interpolator driven by a TimeSensor's fraction, becomes a channel of that TimeSensor's
// animation: key times the cycleInterval (nudged to increase strictly where keys repeat, as glTF asks),
// axis-angle values as quaternions. Routes that do not fit (other interpolators, a Transform with a
// center or scaleOrientation, which glTF's translation-rotation-scale cannot hold) are left out with a note.
void X3dReader::readAnimations() {
    std::map<std::string, pugi::xml_node> byDef;
    for (const pugi::xpath_node& found : document_.select_nodes("//*[@DEF]")) byDef[found.node().attribute("DEF").value()] = found.node();
    const pugi::xpath_node_set routes = document_.select_nodes("//ROUTE");
    auto attribute = [](const pugi::xml_node& node, const char* name) { return std::string(node.attribute(name).value()); };
    // "set_rotation", "rotation" and "rotation_changed" name one field.
    auto field = [&](const pugi::xml_node& route, const char* name) {
        std::string value = attribute(route, name);
        if (value.rfind("set_", 0) == 0) value.erase(0, 4);
        if (value.size() > 8 && value.compare(value.size() - 8, 8, "_changed") == 0) value.erase(value.size() - 8);
        return value;
    };
    auto defined = [&](const std::string& def, const char* type) {
        const auto found = byDef.find(def);
        return found != byDef.end() && std::strcmp(found->second.name(), type) == 0 ? found->second : pugi::xml_node();
    };
    std::map<std::string, std::size_t> animationOf;  // TimeSensor DEF -> index into Scene::animations
    std::size_t leftOut = 0;
    for (const pugi::xpath_node& found : routes) {
        const pugi::xml_node route = found.node();
        const std::string to = field(route, "toField");
        if (field(route, "fromField") != "value" || (to != "translation" && to != "rotation" && to != "scale")) continue;
        const std::string source = attribute(route, "fromNode");
        const pugi::xml_node interpolator = defined(source, to == "rotation" ? "OrientationInterpolator" : "PositionInterpolator");
        const pugi::xml_node transform = defined(attribute(route, "toNode"), "Transform");
        const auto targets = nodesOfTransform_.find(attribute(route, "toNode"));
        pugi::xml_node clock;
        for (const pugi::xpath_node& other : routes)
            if (attribute(other.node(), "toNode") == source && field(other.node(), "toField") == "fraction" &&
                field(other.node(), "fromField") == "fraction")
                clock = defined(attribute(other.node(), "fromNode"), "TimeSensor");
        if (!interpolator || !transform || targets == nodesOfTransform_.end() || !clock ||
            !vector3(transform, "center", Eigen::Vector3d::Zero()).isZero() ||
            rotationField(numbers(transform, "scaleOrientation")).angle() != 0) {
            ++leftOut;
            continue;
        }
        const bool rotation = to == "rotation";
        const std::vector<double> keys = numbers(interpolator, "key"), values = numbers(interpolator, "keyValue");
        const std::size_t components = rotation ? 4 : 3;
        if (keys.empty() || values.size() != keys.size() * components || !std::is_sorted(keys.begin(), keys.end())) {
            ++leftOut;
            continue;
        }
        AnimationChannel channel;
        channel.path = rotation ? AnimationChannel::Path::Rotation
                                : to == "scale" ? AnimationChannel::Path::Scale : AnimationChannel::Path::Translation;
        const double cycle = scalar(clock, "cycleInterval", 1);
        // Times are nudged as floats below: each must be one (a cycle of 1e300 makes none).
        const bool timesFit = std::all_of(keys.begin(), keys.end(), [cycle](double key) {
            return std::abs(key * cycle) < std::numeric_limits<float>::max();
        });
        if (!timesFit) {
            ++leftOut;
            continue;
        }
        for (std::size_t k = 0; k < keys.size(); ++k) {
            double time = keys[k] * cycle;
            if (k > 0 && !(time > channel.times.back()))
                time = std::nextafter(static_cast<float>(channel.times.back()), std::numeric_limits<float>::infinity());
            channel.times.push_back(time);
            const double* value = values.data() + k * components;
            if (rotation) {
                const Eigen::Quaterniond q(rotationField({value[0], value[1], value[2], value[3]}));
                channel.values.insert(channel.values.end(), {q.x(), q.y(), q.z(), q.w()});
            } else {
                channel.values.insert(channel.values.end(), value, value + 3);
            }
        }
        auto [entry, added] = animationOf.emplace(attribute(clock, "DEF"), scene_.animations.size());
        if (added) scene_.animations.push_back({attribute(clock, "DEF"), {}});
        for (int node : targets->second) {
            channel.node = node;
            scene_.animations[entry->second].channels.push_back(channel);
        }
    }
    if (leftOut)
        notes_.insert(std::to_string(leftOut) + " animation ROUTEs left out (read: Position and Orientation interpolators " +
                      "driven by a TimeSensor, on Transforms without center or scaleOrientation)");
}

void X3dReader::readChildren(const pugi::xml_node& parent, std::vector<int>& into, int depth) {
    for (pugi::xml_node child : parent.children()) {
        if (child.type() != pugi::node_element) continue;
        if (std::strcmp(child.name(), "Inline") == 0) {
            readInline(child, into);
            continue;
        }
        const int node = readNode(child, depth + 1);
        if (node >= 0) into.push_back(node);
    }
}

int X3dReader::readNode(const pugi::xml_node& source, int depth) {
    if (depth > 256) fail(source, "nesting deeper than 256 levels");
    if (const pugi::xml_attribute def = source.attribute("DEF")) definitions_[def.value()] = source;
    const std::string use = source.attribute("USE").value();
    if (!use.empty() && !useStack_.insert(use).second) fail(source, "USE of '" + use + "' inside itself");
    const pugi::xml_node node = resolve(source);
    struct PopUse {
        std::set<std::string>& stack;
        std::string name;
        ~PopUse() {
            if (!name.empty()) stack.erase(name);
        }
    } popUse{useStack_, use};
    const std::string type = node.name();

    if (type == "Shape") {
        const int mesh = readShape(node);
        if (mesh < 0) return -1;
        Node out;
        out.name = node.attribute("DEF").value();
        out.mesh = mesh;
        scene_.nodes.push_back(out);
        return static_cast<int>(scene_.nodes.size()) - 1;
    }
    if (kEnvironment.count(type)) {
        if (!source.attribute("USE")) keepEnvironment(node);
        return -1;
    }
    if (type == "Viewpoint" || type == "OrthoViewpoint") return readViewpoint(node);
    if (type == "DirectionalLight" || type == "PointLight" || type == "SpotLight") return readLight(node, depth);
    if (!kGroupingNodes.count(type)) {
        if (kUnsupportedGeometry.count(type)) ++skippedGeometry_[type];
        else if (type == "ProtoInstance") ++skippedGeometry_["ProtoInstance (prototypes are not supported)"];
        else if (!kReadElsewhere.count(type) && type.compare(0, 8, "Metadata") != 0) ++notKept_[type];
        return -1;
    }
    Node out;
    out.name = node.attribute("DEF").value();
    if (type == "Transform" || type == "CADPart") out.transform = transformOf(node);
    if (type == "Billboard") notes_.insert("Billboard nodes read as groups (they turn towards the viewer in a browser)");
    std::vector<int> children;
    if (type == "Switch") {
        const std::vector<std::int64_t> chosen = integers(node, "whichChoice");
        const std::int64_t choice = chosen.empty() ? -1 : chosen[0];
        int index = 0;
        for (pugi::xml_node child : node.children()) {
            if (child.type() != pugi::node_element || std::strncmp(child.name(), "Metadata", 8) == 0) continue;
            if (index++ == choice) {
                const int read = readNode(child, depth + 1);
                if (read >= 0) children.push_back(read);
            }
        }
    } else if (type == "LOD") {
        // The most detailed level (the first child) is the one kept.
        for (pugi::xml_node child : node.children()) {
            if (child.type() != pugi::node_element || std::strncmp(child.name(), "Metadata", 8) == 0) continue;
            const int read = readNode(child, depth + 1);
            if (read >= 0) children.push_back(read);
            notes_.insert("LOD nodes: only the first (most detailed) level is kept");
            break;
        }
    } else {
        readChildren(node, children, depth);
    }
    const int index = static_cast<int>(scene_.nodes.size());
    out.children = children;
    if (type == "Transform" && !out.name.empty()) nodesOfTransform_[out.name].push_back(index);
    scene_.nodes.push_back(out);
    return index;
}

// A NavigationInfo, Background, Fog or WorldInfo as XML text for Scene::x3dEnvironment, without its DEF
// names (the writer makes its own; the ROUTEs that bind such nodes are not kept) and without a
// Background's image URLs, which are relative to the input's folder.
void X3dReader::keepEnvironment(const pugi::xml_node& node) {
    pugi::xml_document copy;
    pugi::xml_node kept = copy.append_copy(node);
    std::size_t images = 0;
    auto clean = [&](auto&& self, pugi::xml_node element) -> void {
        element.remove_attribute("DEF");
        std::vector<std::string> urls;
        for (const pugi::xml_attribute attribute : element.attributes()) {
            const std::string name = attribute.name();
            if (name.size() > 3 && name.compare(name.size() - 3, 3, "Url") == 0) urls.push_back(name);
        }
        for (const std::string& url : urls) element.remove_attribute(url.c_str());
        images += urls.size();
        for (pugi::xml_node child = element.first_child(); child;) {
            const pugi::xml_node next = child.next_sibling();
            if (child.type() == pugi::node_element && child.attribute("USE")) element.remove_child(child);
            else if (child.type() == pugi::node_element) self(self, child);
            child = next;
        }
    };
    clean(clean, kept);
    if (images) notes_.insert("Background images are not kept (their URLs are relative to the input's folder)");
    std::ostringstream text;
    kept.print(text, "", pugi::format_raw);
    scene_.x3dEnvironment.push_back(text.str());
}

// A Viewpoint (or OrthoViewpoint) as a node placed at its position and orientation holding a camera: both
// look down -z with +y up. fieldOfView becomes the vertical one (X3D's is the smaller of the two, the
// vertical one in a landscape window); the near and far planes come from the NavigationInfo (avatarSize[0] / 2
// and visibilityLimit), as an X3D browser sets them.
int X3dReader::readViewpoint(const pugi::xml_node& viewpoint) {
    const bool orthographic = std::strcmp(viewpoint.name(), "OrthoViewpoint") == 0;
    Camera camera;
    camera.name = viewpoint.attribute("description").value();
    const pugi::xml_node navigation = document_.select_node("//NavigationInfo").node();
    const std::vector<double> avatar = navigation ? numbers(navigation, "avatarSize") : std::vector<double>();
    camera.znear = !avatar.empty() && avatar[0] > 0 ? avatar[0] / 2 : 0.125;
    camera.zfar = navigation ? scalar(navigation, "visibilityLimit", 0) : 0;
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    placement.translate(vector3(viewpoint, "position", Eigen::Vector3d(0, 0, 10)))
        .rotate(rotationField(numbers(viewpoint, "orientation")));
    if (orthographic) {
        // fieldOfView: minimum x, minimum y, maximum x, maximum y of the view; glTF's is centred.
        std::vector<double> field = numbers(viewpoint, "fieldOfView");
        if (field.size() != 4) field = {-1, -1, 1, 1};
        camera.projection = Camera::Projection::Orthographic;
        camera.xmag = (field[2] - field[0]) / 2;
        camera.ymag = (field[3] - field[1]) / 2;
        placement.translate(Eigen::Vector3d((field[0] + field[2]) / 2, (field[1] + field[3]) / 2, 0));
        if (!(camera.zfar > camera.znear)) camera.zfar = 1e4;  // glTF needs a far plane; X3D's may be infinite
    } else {
        camera.yfov = scalar(viewpoint, "fieldOfView", 0.7853981633974483);
    }
    if (const std::string problem = cameraProblem(camera); !problem.empty()) {
        notes_.insert("a " + std::string(viewpoint.name()) + " was left out: " + problem);
        return -1;
    }
    scene_.cameras.push_back(camera);
    return addPlacedNode(viewpoint, placement, int(scene_.cameras.size()) - 1, -1);
}

// A node of its own at `placement`, named by the X3D node's DEF, carrying a camera or a light.
int X3dReader::addPlacedNode(const pugi::xml_node& source, const Eigen::Affine3d& placement, int camera, int light) {
    Node out;
    out.name = source.attribute("DEF").value();
    out.transform = placement.matrix();
    out.camera = camera;
    out.light = light;
    scene_.nodes.push_back(out);
    return int(scene_.nodes.size()) - 1;
}

// A light as a node at its location, turned so that its direction is -z (glTF's frame). What glTF's
// KHR_lights_punctual cannot hold is said in a note: attenuation (glTF lights fall off with the inverse
// square of the distance), ambient intensity, a light scoped to its group, a light that is off.
int X3dReader::readLight(const pugi::xml_node& source, int depth) {
    const std::string type = source.name();
    if (!boolean(source, "on", true)) {
        notes_.insert("lights that are off (on='false') left out");
        return -1;
    }
    Light light;
    light.type = type == "DirectionalLight" ? Light::Type::Directional : type == "SpotLight" ? Light::Type::Spot : Light::Type::Point;
    light.color = vector3(source, "color", Eigen::Vector3d::Ones());
    light.intensity = scalar(source, "intensity", 1);
    if (light.type != Light::Type::Directional) {
        light.range = scalar(source, "radius", 100);
        if (light.range >= std::numeric_limits<float>::max()) light.range = 0;  // how the writer says "no limit"
    }
    if (light.type == Light::Type::Spot) {
        light.outerConeAngle = std::min(scalar(source, "cutOffAngle", 0.7853981633974483), std::acos(0.0));
        light.innerConeAngle = std::min(scalar(source, "beamWidth", std::acos(0.0)), std::nextafter(light.outerConeAngle, 0.0));
    }
    if (light.type != Light::Type::Directional && vector3(source, "attenuation", Eigen::Vector3d(1, 0, 0)) != Eigen::Vector3d(0, 0, 1))
        notes_.insert("the attenuation of point and spot lights is not kept: glTF's lights fall off with the inverse square of the distance");
    if (scalar(source, "ambientIntensity", 0) != 0) notes_.insert("the ambientIntensity of lights is not kept (glTF's lights have none)");
    if (!boolean(source, "global", light.type != Light::Type::Directional) && depth > 1)
        notes_.insert("lights scoped to their group (global='false') light the whole scene once written");
    if (const std::string problem = lightProblem(light); !problem.empty()) {
        notes_.insert("a " + type + " was left out: " + problem);
        return -1;
    }
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    if (light.type != Light::Type::Directional) placement.translate(vector3(source, "location", Eigen::Vector3d::Zero()));
    if (light.type != Light::Type::Point) {
        const Eigen::Vector3d direction = vector3(source, "direction", Eigen::Vector3d(0, 0, -1));
        if (direction.norm() > 0) placement.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(0, 0, -1), direction));
    }
    scene_.lights.push_back(light);
    return addPlacedNode(source, placement, -1, int(scene_.lights.size()) - 1);
}

void X3dReader::readInline(const pugi::xml_node& source, std::vector<int>& into) {
    const pugi::xml_node node = resolve(source);
    if (!boolean(node, "load", true)) return;
    for (const std::string& url : x3d::parseStrings(node.attribute("url").value())) {
        if (url.find("://") != std::string::npos) continue;  // only local files
        const fs::path target = fs::weakly_canonical(file_.parent_path() / url);
        std::error_code error;
        if (!fs::is_regular_file(target, error)) continue;
        if (inlineStack_.count(target)) fail(node, "Inline of '" + url + "' includes itself");
        inlineStack_.insert(target);
        X3dReader inlined(target, scene_, inlineStack_);
        Node group;
        group.name = node.attribute("DEF").value();
        group.children = inlined.read();
        inlineStack_.erase(target);
        scene_.nodes.push_back(group);
        into.push_back(static_cast<int>(scene_.nodes.size()) - 1);
        return;
    }
    notes_.insert("an Inline whose url names no readable local file was skipped: " +
                  std::string(node.attribute("url").value()));
}

int X3dReader::readTexture(const pugi::xml_node& appearance) {
    pugi::xml_node texture = appearance.child("ImageTexture");
    if (!texture) {
        for (pugi::xml_node child : appearance.children())
            if (std::strstr(child.name(), "Texture")) notes_.insert(std::string(child.name()) + " not carried through");
        return -1;
    }
    if (const pugi::xml_attribute def = texture.attribute("DEF")) definitions_[def.value()] = texture;
    texture = resolve(texture);
    auto [entry, inserted] = textureOfNode_.try_emplace(texture.internal_object(), -1);
    if (!inserted) return entry->second;
    Texture out;
    for (const std::string& url : x3d::parseStrings(texture.attribute("url").value())) {
        if (url.compare(0, 5, "data:") == 0) {
            // An image inside the file (how the X3D writer embeds them): data:[mime type][;base64],bytes.
            const std::size_t comma = url.find(',');
            const std::string header = url.substr(5, comma == std::string::npos ? 0 : comma - 5);
            const std::size_t base64At = header.rfind(";base64");
            if (comma == std::string::npos || base64At == std::string::npos || base64At + 7 != header.size() ||
                !decodeBase64(url.substr(comma + 1), out.bytes)) {
                notes_.insert("an ImageTexture's data: URL that is not valid base64 was skipped");
                continue;
            }
            out.uri.clear();
            out.mimeType = header.substr(0, base64At);
            return addTexture(entry->second, std::move(out));
        }
        if (out.uri.empty()) out.uri = url;
        const fs::path image = file_.parent_path() / url;
        std::error_code error;
        if (url.find("://") == std::string::npos && fs::is_regular_file(image, error)) {
            out.uri = url;
            out.bytes = readFileBytes(image);
            break;
        }
    }
    if (out.uri.empty()) return -1;
    if (out.bytes.empty()) notes_.insert("texture '" + out.uri + "' not found; materials using it are written without it");
    out.mimeType = imageMimeType(out.uri);
    return addTexture(entry->second, std::move(out));
}

int X3dReader::addTexture(int& index, Texture texture) {
    scene_.textures.push_back(std::move(texture));
    index = static_cast<int>(scene_.textures.size()) - 1;
    return index;
}

int X3dReader::readMaterial(const pugi::xml_node& shape) {
    pugi::xml_node appearance = shape.child("Appearance");
    if (!appearance) return -1;
    if (const pugi::xml_attribute def = appearance.attribute("DEF")) definitions_[def.value()] = appearance;
    appearance = resolve(appearance);
    auto [entry, inserted] = materialOfAppearance_.try_emplace(appearance.internal_object(), -1);
    if (!inserted) return entry->second;
    Material material;
    material.name = appearance.attribute("DEF").value();
    pugi::xml_node phong = appearance.child("Material");
    pugi::xml_node physical = appearance.child("PhysicalMaterial");
    pugi::xml_node twoSided = appearance.child("TwoSidedMaterial");
    if (twoSided) {
        phong = twoSided;
        material.doubleSided = true;
    }
    for (pugi::xml_node* node : {&phong, &physical})
        if (*node) {
            if (const pugi::xml_attribute def = node->attribute("DEF")) definitions_[def.value()] = *node;
            *node = resolve(*node);
        }
    if (phong) {
        PhongMaterial fields;
        fields.diffuseColor = vector3(phong, "diffuseColor", fields.diffuseColor);
        fields.specularColor = vector3(phong, "specularColor", fields.specularColor);
        fields.emissiveColor = vector3(phong, "emissiveColor", fields.emissiveColor);
        fields.ambientIntensity = scalar(phong, "ambientIntensity", fields.ambientIntensity);
        fields.shininess = scalar(phong, "shininess", fields.shininess);
        fields.transparency = scalar(phong, "transparency", fields.transparency);
        material.baseColorFactor << fields.diffuseColor, 1 - fields.transparency;
        material.emissiveFactor = fields.emissiveColor;
        material.metallicFactor = 0;
        material.roughnessFactor = 1 - fields.shininess;
        material.phong = fields;
        if (material.name.empty()) material.name = phong.attribute("DEF").value();
    } else if (physical) {
        const double transparency = scalar(physical, "transparency", 0);
        material.baseColorFactor << vector3(physical, "baseColor", Eigen::Vector3d::Ones()), 1 - transparency;
        material.metallicFactor = scalar(physical, "metallic", 1);
        material.roughnessFactor = scalar(physical, "roughness", 1);
        material.emissiveFactor = vector3(physical, "emissiveColor", Eigen::Vector3d::Zero());
        if (material.name.empty()) material.name = physical.attribute("DEF").value();
    } else {
        // An Appearance without a material is unlit white in X3D.
        material.metallicFactor = 0;
    }
    if (material.baseColorFactor[3] < 1) material.alphaMode = Material::AlphaMode::Blend;
    material.baseColorTexture = readTexture(appearance);
    // Appearances written out one per Shape, with the same Material and texture USEd in each, are one
    // material (else every Shape would look like its own part). Double-sidedness comes from the geometry
    // (solid="false" makes the material double-sided, below in readShape), so it is not compared.
    const auto same = std::find_if(scene_.materials.begin(), scene_.materials.end(), [&](const Material& existing) {
        Material candidate = material;
        candidate.doubleSided = existing.doubleSided;
        return candidate == existing;
    });
    if (same != scene_.materials.end()) return entry->second = static_cast<int>(same - scene_.materials.begin());
    scene_.materials.push_back(material);
    entry->second = static_cast<int>(scene_.materials.size()) - 1;
    return entry->second;
}

int X3dReader::readShape(const pugi::xml_node& shape) {
    auto [entry, inserted] = meshOfShape_.try_emplace(shape.internal_object(), -1);
    if (!inserted) return entry->second;
    const int material = readMaterial(shape);
    pugi::xml_node geometry;
    for (pugi::xml_node child : shape.children()) {
        if (child.type() != pugi::node_element) continue;
        const std::string name = child.name();
        if (name != "Appearance" && name.rfind("Metadata", 0) != 0) {
            geometry = child;
            break;
        }
    }
    if (!geometry) return -1;
    if (const pugi::xml_attribute def = geometry.attribute("DEF")) definitions_[def.value()] = geometry;
    geometry = resolve(geometry);
    Primitive primitive;
    if (!readGeometry(geometry, primitive)) return -1;
    primitive.material = material;
    if (material >= 0 && !boolean(geometry, "solid", true)) scene_.materials[material].doubleSided = true;
    Mesh mesh;
    mesh.name = shape.attribute("DEF").value();
    mesh.primitives.push_back(std::move(primitive));
    scene_.meshes.push_back(std::move(mesh));
    entry->second = static_cast<int>(scene_.meshes.size()) - 1;
    return entry->second;
}

bool X3dReader::readGeometry(const pugi::xml_node& geometry, Primitive& out) {
    const std::string type = geometry.name();
    if (type == "IndexedFaceSet") {
        readFaceSet(geometry, out, true);
    } else if (type == "IndexedTriangleSet" || type == "TriangleSet") {
        readFaceSet(geometry, out, false);
    } else if (type == "Box") {
        out = x3d::tessellateBox(vector3(geometry, "size", Eigen::Vector3d(2, 2, 2)));
    } else if (type == "Sphere") {
        out = x3d::tessellateSphere(scalar(geometry, "radius", 1));
    } else if (type == "Cylinder") {
        const double radius = scalar(geometry, "radius", 1);
        out = x3d::tessellateCylinder(radius, radius, scalar(geometry, "height", 2), boolean(geometry, "side", true),
                                      boolean(geometry, "bottom", true), boolean(geometry, "top", true));
    } else if (type == "Cone") {
        out = x3d::tessellateCylinder(scalar(geometry, "bottomRadius", 1), 0, scalar(geometry, "height", 2),
                                      boolean(geometry, "side", true), boolean(geometry, "bottom", true), false);
    } else {
        ++skippedGeometry_[type];
        return false;
    }
    return true;
}

void X3dReader::readFaceSet(const pugi::xml_node& geometry, Primitive& out, bool indexedFaces) {
    auto child = [&](std::initializer_list<const char*> types) -> pugi::xml_node {
        for (const char* type : types)
            if (pugi::xml_node node = geometry.child(type)) {
                if (const pugi::xml_attribute def = node.attribute("DEF")) definitions_[def.value()] = node;
                return resolve(node);
            }
        return {};
    };
    const pugi::xml_node coordinate = child({"Coordinate", "CoordinateDouble"});
    if (!coordinate) fail(geometry, "no Coordinate");
    const std::vector<double> points = numbers(coordinate, "point");
    if (points.size() % 3) fail(coordinate, "the number of point values is not a multiple of 3");
    const std::size_t pointCount = points.size() / 3;
    const pugi::xml_node normalNode = child({"Normal"});
    const pugi::xml_node colorNode = child({"Color", "ColorRGBA"});
    const pugi::xml_node texcoordNode = child({"TextureCoordinate"});
    const std::vector<double> normalValues = normalNode ? numbers(normalNode, "vector") : std::vector<double>();
    const std::vector<double> colorValues = colorNode ? numbers(colorNode, "color") : std::vector<double>();
    const int colorComponents = colorNode && std::strcmp(colorNode.name(), "ColorRGBA") == 0 ? 4 : 3;
    const std::vector<double> texcoordValues = texcoordNode ? numbers(texcoordNode, "point") : std::vector<double>();
    const bool ccw = boolean(geometry, "ccw", true);
    const bool normalPerVertex = boolean(geometry, "normalPerVertex", true);
    const bool colorPerVertex = boolean(geometry, "colorPerVertex", true);

    // Faces as lists of corner positions in the Coordinate node.
    std::vector<std::vector<std::int64_t>> faces;
    if (indexedFaces) {
        std::vector<std::int64_t> face;
        for (std::int64_t value : integers(geometry, "coordIndex")) {
            if (value < 0) {
                if (!face.empty()) faces.push_back(face);
                face.clear();
            } else {
                face.push_back(value);
            }
        }
        if (!face.empty()) faces.push_back(face);  // the last -1 is optional
    } else if (std::strcmp(geometry.name(), "IndexedTriangleSet") == 0) {
        const std::vector<std::int64_t> index = integers(geometry, "index");
        for (std::size_t i = 0; i + 2 < index.size(); i += 3) faces.push_back({index[i], index[i + 1], index[i + 2]});
    } else {
        for (std::size_t i = 0; i + 2 < pointCount; i += 3)
            faces.push_back({static_cast<std::int64_t>(i), static_cast<std::int64_t>(i + 1), static_cast<std::int64_t>(i + 2)});
    }

    // Which entry of an attribute a corner uses: IndexedFaceSet has optional per-corner or per-face index
    // lists; the triangle sets index attributes like the coordinates.
    auto indexList = [&](const char* field) { return indexedFaces ? integers(geometry, field) : std::vector<std::int64_t>(); };
    const std::vector<std::int64_t> normalIndex = indexList("normalIndex"), colorIndex = indexList("colorIndex"),
                                    texcoordIndex = indexList("texCoordIndex");
    auto attributeIndex = [&](const std::vector<std::int64_t>& ownIndex, bool perVertex, std::size_t face,
                              std::size_t cornerInCoordIndex, std::int64_t point) -> std::int64_t {
        if (!indexedFaces) return perVertex ? point : static_cast<std::int64_t>(face);
        if (perVertex) {
            if (!ownIndex.empty()) return cornerInCoordIndex < ownIndex.size() ? ownIndex[cornerInCoordIndex] : -1;
            return point;
        }
        if (!ownIndex.empty()) return face < ownIndex.size() ? ownIndex[face] : -1;
        return static_cast<std::int64_t>(face);
    };

    struct CornerKey {
        std::int64_t point, normal, color, texcoord;
        bool operator<(const CornerKey& o) const {
            return std::tie(point, normal, color, texcoord) < std::tie(o.point, o.normal, o.color, o.texcoord);
        }
    };
    std::map<CornerKey, std::uint32_t> vertexOf;
    const bool hasNormals = !normalValues.empty(), hasColors = !colorValues.empty(), hasTexcoords = !texcoordValues.empty();
    std::size_t cornerInCoordIndex = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        std::vector<std::uint32_t> local;
        std::vector<Eigen::Vector3d> polygon;
        for (std::size_t k = 0; k < face.size(); ++k, ++cornerInCoordIndex) {
            const std::int64_t point = face[k];
            if (point < 0 || static_cast<std::size_t>(point) >= pointCount)
                fail(geometry, "coordinate index " + std::to_string(point) + " out of range (" + std::to_string(pointCount) +
                                   " points)");
            CornerKey key{point, -1, -1, -1};
            if (hasNormals) key.normal = attributeIndex(normalIndex, normalPerVertex, f, cornerInCoordIndex, point);
            if (hasColors) key.color = attributeIndex(colorIndex, colorPerVertex, f, cornerInCoordIndex, point);
            if (hasTexcoords) key.texcoord = attributeIndex(texcoordIndex, true, f, cornerInCoordIndex, point);
            auto check = [&](std::int64_t index, std::size_t available, const char* what) {
                if (index < 0 || static_cast<std::size_t>(index) >= available)
                    fail(geometry, std::string(what) + " index " + std::to_string(index) + " out of range");
            };
            if (hasNormals) check(key.normal, normalValues.size() / 3, "normal");
            if (hasColors) check(key.color, colorValues.size() / colorComponents, "colour");
            if (hasTexcoords) check(key.texcoord, texcoordValues.size() / 2, "texture coordinate");
            auto [entry, inserted] = vertexOf.try_emplace(key, static_cast<std::uint32_t>(out.positions.size()));
            if (inserted) {
                out.positions.emplace_back(points[3 * point], points[3 * point + 1], points[3 * point + 2]);
                if (hasNormals)
                    out.normals.emplace_back(normalValues[3 * key.normal], normalValues[3 * key.normal + 1],
                                             normalValues[3 * key.normal + 2]);
                if (hasColors) {
                    Eigen::Vector4d color(1, 1, 1, 1);
                    for (int c = 0; c < colorComponents; ++c) color[c] = colorValues[colorComponents * key.color + c];
                    out.colors.push_back(color);
                }
                if (hasTexcoords)  // X3D's v points up, glTF's down
                    out.texcoords.emplace_back(texcoordValues[2 * key.texcoord], 1 - texcoordValues[2 * key.texcoord + 1]);
            }
            local.push_back(entry->second);
            polygon.push_back(out.positions[entry->second]);
        }
        ++cornerInCoordIndex;  // the -1 that ended the face
        const auto triangles = triangulatePolygon(polygon);
        if (triangles.empty()) ++degenerateFaces_;
        for (const Triangle& t : triangles)
            out.triangles.push_back(ccw ? Triangle{local[t[0]], local[t[1]], local[t[2]]}
                                        : Triangle{local[t[0]], local[t[2]], local[t[1]]});
    }
}

}  // namespace

Scene readX3d(const fs::path& file) {
    Scene scene;
    std::set<fs::path> inlineStack = {fs::weakly_canonical(file)};
    X3dReader reader(file, scene, inlineStack);
    scene.roots = reader.read();
    return scene;
}

}  // namespace symcompress
