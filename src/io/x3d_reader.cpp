// X3D reader (XML encoding, X3D 3.x and 4.0). Keeps the node hierarchy with local transforms; a USE of
// a Shape or geometry reuses the same symcompress Mesh, so that the file's instancing survives.
#include "x3d_reader.hpp"
#include "common/color_space.hpp"
#include "common/mime_type.hpp"
#include "file_metadata.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/triangulate_polygon.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "x3d_fields.hpp"
#include "x3d_primitives.hpp"
#include "x3d_prototypes.hpp"

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
const std::set<std::string> kGroupingNodes = {"Group",   "Transform",   "Switch",    "LOD",         "Collision",
                                              "Anchor",  "StaticGroup", "Billboard", "CADAssembly", "CADLayer",
                                              "CADPart", "CADFace",     "Scene",     "LayerSet",    "Layer"};
// Bindable nodes of the scene's environment with no place in the scene model, kept as their XML text.
const std::set<std::string> kEnvironment = {"NavigationInfo", "Background", "Fog", "WorldInfo"};
// Nodes read where they are used (animations from their ROUTEs) or that hold nothing of the scene's.
const std::set<std::string> kReadElsewhere = {
    "ROUTE",  "TimeSensor", "PositionInterpolator", "OrientationInterpolator", "ProtoDeclare", "ExternProtoDeclare",
    "IMPORT", "EXPORT"};
// Geometry nodes that draw something we do not read: reported once per type.
const std::set<std::string> kUnsupportedGeometry = {"Text",
                                                    "NurbsPatchSurface",
                                                    "NurbsTrimmedSurface",
                                                    "NurbsCurve",
                                                    "NurbsSweptSurface",
                                                    "NurbsSwungSurface",
                                                    "GeoElevationGrid"};
// The Geometry2D surfaces, which X3D draws from both sides unless `solid` says otherwise.
const std::set<std::string> kSurfaces2D = {"Rectangle2D", "Disk2D", "TriangleSet2D", "ArcClose2D"};
// Geometry nodes that make their points from a few numbers: X3D output writes them again (X3dGeometrySource).
const std::set<std::string> kMadeGeometry = {"Box",       "Sphere",      "Cylinder", "Cone",      "ElevationGrid",
                                             "Extrusion", "Rectangle2D", "Disk2D",   "ArcClose2D"};

// How deep XML elements may nest in an X3D file (readNode's limit for the scene graph, 256, and room for
// the X3D and Scene elements and a node's fields).
constexpr int kMaxXmlDepth = 300;

// How much XML an .x3dz file may inflate to. Deflate expands at most about 1032:1, so the format alone lets a
// 2 MB gzip bomb ask for 2 GB; beyond this the file is refused before more is held.
constexpr std::size_t kMaxInflatedBytes = std::size_t(2) << 30;

// The XML of a gzip stream, at most kMaxInflatedBytes of it.
std::vector<unsigned char> inflateGzip(const std::vector<unsigned char>& bytes, const fs::path& file) {
    z_stream stream{};
    if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) throw FileError(file, "cannot start gzip decompression");
    std::vector<unsigned char> text;
    std::size_t consumed = 0;
    unsigned char buffer[1 << 16];
    int status;
    do {
        // avail_in is 32 bits: a larger file is handed over in pieces.
        if (stream.avail_in == 0 && consumed < bytes.size()) {
            const std::size_t piece = std::min<std::size_t>(bytes.size() - consumed, 1u << 30);
            stream.next_in = const_cast<unsigned char*>(bytes.data() + consumed);
            stream.avail_in = static_cast<uInt>(piece);
            consumed += piece;
        }
        stream.next_out = buffer;
        stream.avail_out = sizeof buffer;
        status = inflate(&stream, Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END) {
            inflateEnd(&stream);
            throw FileError(file, "broken gzip data");
        }
        const std::size_t produced = sizeof buffer - stream.avail_out;
        if (produced > kMaxInflatedBytes - text.size()) {
            inflateEnd(&stream);
            throw FileError(file, "the gzip data inflates to more than " + std::to_string(kMaxInflatedBytes >> 30) +
                                      " GiB of XML (a broken stream or a gzip bomb; an .x3dz may hold at most that)");
        }
        // Grown by doubling, but never past the limit, so that a bomb holds at most the limit at its end.
        if (text.size() + produced > text.capacity())
            text.reserve(std::min(kMaxInflatedBytes, std::max(text.size() + produced, 2 * text.capacity())));
        text.insert(text.end(), buffer, buffer + produced);
    } while (status != Z_STREAM_END);
    inflateEnd(&stream);
    return text;
}

}  // namespace

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

Eigen::Vector2d X3dReader::vector2(const pugi::xml_node& node, const char* field,
                                   const Eigen::Vector2d& fallback) const {
    const std::vector<double> values = numbers(node, field);
    if (values.empty()) return fallback;
    if (values.size() != 2) fail(node, std::string(field) + " needs 2 numbers");
    return {values[0], values[1]};
}

Eigen::Vector3d X3dReader::vector3(const pugi::xml_node& node, const char* field,
                                   const Eigen::Vector3d& fallback) const {
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
    m.translate(translation)
        .translate(center)
        .rotate(rotation)
        .rotate(scaleOrientation)
        .scale(scale)
        .rotate(scaleOrientation.inverse())
        .translate(-center);
    return m.matrix();
}

void X3dReader::expandPrototypes() {
    const x3d::DocumentLoader load = [](const fs::path& file, pugi::xml_document& into) {
        std::error_code error;
        if (!fs::is_regular_file(file, error)) return false;
        const std::vector<unsigned char> bytes = readFileBytes(file);
        const bool gzipped = bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b;
        const std::vector<unsigned char> text = gzipped ? inflateGzip(bytes, file) : bytes;
        return bool(into.load_buffer(text.data(), text.size()));
    };
    try {
        const x3d::PrototypeExpansion expansion =
            x3d::expandPrototypes(document_.child("X3D").child("Scene"), file_.parent_path(), load);
        notes_.insert(expansion.notes.begin(), expansion.notes.end());
    } catch (const std::length_error& error) {
        throw FileError(file_, error.what());
    }
}

std::vector<int> X3dReader::read() {
    const std::vector<unsigned char> bytes = readFileBytes(file_);
    if (bytes.empty()) throw FileError(file_, "the file is empty");
    // .x3dz: gzip-compressed XML.
    const bool gzipped = bytes.size() >= 2 && bytes[0] == 0x1f && bytes[1] == 0x8b;
    const std::vector<unsigned char> text = gzipped ? inflateGzip(bytes, file_) : bytes;
    const pugi::xml_parse_result parsed = document_.load_buffer(text.data(), text.size());
    if (!parsed)
        throw FileError(
            file_, std::string("malformed XML at byte ") + std::to_string(parsed.offset) + ": " + parsed.description());
    // Nesting is bounded once for the whole document, without recursion (pugixml's traverse is a loop), so that
    // no code after this that recurses over elements (the environment nodes' copy, pugixml's own) can exhaust
    // the stack; the nodes of the scene graph have their tighter limit in readNode.
    struct DepthLimit : pugi::xml_tree_walker {
        bool tooDeep = false;
        bool for_each(pugi::xml_node&) override { return !(tooDeep = depth() > kMaxXmlDepth); }
    } limit;
    document_.traverse(limit);
    if (limit.tooDeep)
        throw FileError(file_, "XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels");
    expandPrototypes();
    document_.traverse(limit);
    if (limit.tooDeep)
        throw FileError(
            file_, "prototypes expand to XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels");
    // What the file says about itself (file_metadata.hpp), and symcompress's digest of the original, for
    // symdecompress (see the X3D writer); the generator is the writer's to say.
    nlohmann::json extras;
    for (pugi::xml_node meta : document_.child("X3D").child("head").children("meta")) {
        const std::string name = meta.attribute("name").value(), content = meta.attribute("content").value();
        if (name == kDigestMember) {
            if (nlohmann::json digest = digestFromMetaContent(content); !digest.is_null())
                extras[kDigestMember] = std::move(digest);
        } else if (name == "symcompress") {  // the digest's tag before 2026-12-07: its JSON
            const nlohmann::json digest = nlohmann::json::parse(content, nullptr, false);
            if (digest.is_object() && digest.contains(kDigestMember)) extras[kDigestMember] = digest[kDigestMember];
        } else if (name == "copyright" && scene_.copyright.empty()) {
            scene_.copyright = content;
        } else if (!name.empty() && name != "generator") {
            addMetaTag(extras, name, content);
        }
    }
    // Names and contents are XML text, which need not be UTF-8: a byte that is not is written as U+FFFD.
    if (!extras.is_null()) scene_.extrasJson = extras.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
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
        for (const auto& [type, count] : notKept_)
            list += (list.empty() ? "" : ", ") + std::to_string(count) + " " + type;
        scene_.warnings.push_back(name +
                                  ": not kept (symcompress keeps geometry, materials, animations of transforms, " +
                                  "viewpoints and lights): " + list);
    }
    for (const std::string& note : notes_) scene_.warnings.push_back(name + ": " + note);
    if (degenerateFaces_)
        scene_.warnings.push_back(name + ": " + std::to_string(degenerateFaces_) +
                                  " faces with fewer than 3 corners or no area skipped");
    return roots;
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
        if (kUnsupportedGeometry.count(type))
            ++skippedGeometry_[type];
        else if (type == "ProtoInstance")
            ++skippedGeometry_["ProtoInstance (its prototype not found, or nested too deep)"];
        else if (!kReadElsewhere.count(type) && type.compare(0, 8, "Metadata") != 0)
            ++notKept_[type];
        return -1;
    }
    Node out;
    out.name = node.attribute("DEF").value();
    if (type == "Transform" || type == "CADPart") out.transform = transformOf(node);
    if (type == "Billboard")
        notes_.insert("Billboard nodes read as groups (they turn towards the viewer in a browser)");
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
        inlined.usedMaterials_ = usedMaterials_;  // the scene's materials, which its shapes may share
        Node group;
        group.name = node.attribute("DEF").value();
        group.children = inlined.read();
        usedMaterials_ = inlined.usedMaterials_;
        inlineStack_.erase(target);
        scene_.nodes.push_back(group);
        into.push_back(static_cast<int>(scene_.nodes.size()) - 1);
        return;
    }
    notes_.insert("an Inline whose url names no readable local file was skipped: " +
                  std::string(node.attribute("url").value()));
}

int X3dReader::readShape(const pugi::xml_node& shape) {
    auto [entry, inserted] = meshOfShape_.try_emplace(shape.internal_object(), -1);
    if (!inserted) return entry->second;
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
    std::vector<std::string> texcoordMappings;
    if (!readGeometry(geometry, primitive, texcoordMappings)) return -1;
    // After the geometry: an X3D 4 material's textures name its texture coordinate sets by their mapping.
    int material = readMaterial(shape, texcoordMappings, primitive);
    // Double-sidedness is the geometry's (solid='false'): a material shared with shapes of the other kind is
    // drawn from a copy that differs in it alone, so that a solid shape's back faces stay culled (the Chevy's
    // roof rails, drawn with a material that a box with solid='false' also uses).
    if (material >= 0)
        material = withSidedness(material, !boolean(geometry, "solid", !kSurfaces2D.count(geometry.name())));
    primitive.material = material;
    if (!primitive.colors.empty()) vertexColorsAsGltf(primitive);
    // A node written again as it was would draw its own texture coordinates, not the transformed ones.
    const bool transformed = applyTextureTransform(shape, texcoordMappings, primitive);
    if (kMadeGeometry.count(geometry.name()) && !primitive.triangles.empty() && !transformed)
        primitive.x3dSource = std::make_shared<X3dGeometrySource>(
            X3dGeometrySource{selfContainedXml(geometry), trianglePositionsHash(primitive)});
    Mesh mesh;
    mesh.name = shape.attribute("DEF").value();
    mesh.primitives.push_back(std::move(primitive));
    scene_.meshes.push_back(std::move(mesh));
    entry->second = static_cast<int>(scene_.meshes.size()) - 1;
    return entry->second;
}

int X3dReader::withSidedness(int material, bool doubleSided) {
    // A material no shape draws yet takes the sidedness of the first that does.
    if (usedMaterials_.insert(material).second) scene_.materials[std::size_t(material)].doubleSided = doubleSided;
    if (scene_.materials[std::size_t(material)].doubleSided == doubleSided) return material;
    Material wanted = scene_.materials[std::size_t(material)];
    wanted.doubleSided = doubleSided;
    const auto same = std::find(scene_.materials.begin(), scene_.materials.end(), wanted);
    const int index = static_cast<int>(same - scene_.materials.begin());
    if (same == scene_.materials.end()) scene_.materials.push_back(wanted);
    if (physicalMaterials_.count(material)) physicalMaterials_.insert(index);
    usedMaterials_.insert(index);
    return index;
}

// X3D's Color takes the place of Phong's diffuse colour (and of UnlitMaterial's emissive colour, and is drawn as
// it is without a material), sRGB-encoded as that colour is; glTF's COLOR_0 is linear and multiplies the base
// colour. So each value is decoded and divided by the base colour (where a channel of it is 0, glTF cannot draw
// the colour: decoded only, with a note). With PhysicalMaterial, Color is glTF's COLOR_0: linear, multiplying.
void X3dReader::vertexColorsAsGltf(Primitive& primitive) {
    if (physicalMaterials_.count(primitive.material)) return;
    const Eigen::Vector3d base =
        primitive.material >= 0
            ? Eigen::Vector3d(scene_.materials[std::size_t(primitive.material)].baseColorFactor.head<3>())
            : Eigen::Vector3d::Ones();
    bool lost = false;
    for (Eigen::Vector4d& color : primitive.colors)
        for (int c = 0; c < 3; ++c) {
            color[c] = srgbToLinear(color[c]);
            if (base[c] > 0)
                color[c] /= base[c];
            else
                lost = lost || color[c] > 0;
        }
    if (lost)
        notes_.insert(
            "vertex colours on a Material whose diffuseColor has a channel at 0: glTF multiplies its "
            "COLOR_0 by that channel, which draws it black");
}

Scene readX3d(const fs::path& file) {
    Scene scene;
    std::set<fs::path> inlineStack = {fs::weakly_canonical(file)};
    X3dReader reader(file, scene, inlineStack);
    scene.roots = reader.read();
    return scene;
}

}  // namespace symcompress
