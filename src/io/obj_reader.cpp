// Wavefront OBJ reader with its .mtl materials. Each o/g group becomes a node with its own mesh (one
// primitive per material); vertices are split per distinct (v, vt, vn) triple; polygons are triangulated.
#include "common/color_space.hpp"
#include "image_file.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/triangulate_polygon.hpp"
#include "symcompress/io.hpp"
#include "text_scanner.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

std::string rest(std::string_view line) {
    while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    return std::string(line);
}

// The statements of an OBJ or MTL file, one a call: a line, with the lines that a '\' at its end continues it
// into, without its comment. A comment starts at a word that begins with '#' ("v 1 2 3 # note": exporters write
// them, and OBJ readers skip them); a '#' inside a word stays, as in a name ("usemtl part#2").
class Statements {
public:
    explicit Statements(TextScanner& scanner) : scanner_(scanner) {}
    bool atEnd() const { return scanner_.atEnd(); }

    std::string_view next() {
        std::string_view line = withoutComment(scanner_.nextLine());
        bool continues = cutContinuation(line);
        if (!continues || scanner_.atEnd()) return line;
        joined_.assign(line);
        while (continues && !scanner_.atEnd()) {
            line = withoutComment(scanner_.nextLine());
            continues = cutContinuation(line);
            joined_.append(" ").append(line);
        }
        return joined_;
    }

private:
    static std::string_view withoutComment(std::string_view line) {
        for (std::size_t at = line.find('#'); at != std::string_view::npos; at = line.find('#', at + 1))
            if (at == 0 || line[at - 1] == ' ' || line[at - 1] == '\t') {
                line = line.substr(0, at);
                break;
            }
        while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
        return line;
    }
    // Cuts a '\' that ends `line`; true where there was one (the statement goes on on the next line).
    static bool cutContinuation(std::string_view& line) {
        if (line.empty() || line.back() != '\\') return false;
        line.remove_suffix(1);
        return true;
    }

    TextScanner& scanner_;
    std::string joined_;
};

// Refuses an OBJ file with a NUL byte, which no text has: binary data would otherwise read as an OBJ of unknown
// statements, that is as nothing, without a word. A material library is not refused so: a broken one costs the
// materials it fails to define, each named in a warning ("material 'x' is not defined").
void checkIsText(const fs::path& file, std::string_view text) {
    const std::size_t nul = text.find('\0');
    if (nul != std::string_view::npos)
        throw FileError(file, "not an OBJ text file (a NUL byte at offset " + std::to_string(nul) + ")");
}

// OBJ's statements that the reader skips without a word: smoothing groups, merging groups, render attributes,
// and the free-form geometry that goes with the curves and surfaces it counts (see readObj).
bool isSkippedObjStatement(std::string_view keyword) {
    static const std::set<std::string_view> skipped = {
        "s",         "mg",    "vp",    "deg",  "bmat",  "step",     "parm",     "trim", "hole",
        "scrv",      "sp",    "end",   "con",  "bevel", "c_interp", "d_interp", "lod",  "shadow_obj",
        "trace_obj", "ctech", "stech", "call", "csh",   "maplib",   "usemap"};
    return skipped.count(keyword) > 0;
}

// How many words `line` has.
std::size_t wordCount(std::string_view line) {
    std::size_t count = 0;
    while (!nextWord(line).empty()) ++count;
    return count;
}

// The statements whose keyword OBJ does not have, for one warning: real OBJ readers skip them (some exporters
// add their own), but a file of nothing else is no OBJ file.
class UnknownStatements {
public:
    void add(std::string_view keyword) {
        ++count_;
        // The first few keywords are named; a text file that is no OBJ file could have thousands.
        if (keywords_.size() < kNamed || keywords_.count(std::string(keyword)))
            ++keywords_[std::string(keyword)];
        else
            unnamed_ = true;
    }
    std::size_t count() const { return count_; }
    // "3 statements of keywords OBJ does not have ('foo' 2, 'bar' 1)".
    std::string describe() const {
        std::string list;
        for (const auto& [keyword, times] : keywords_)
            list += (list.empty() ? "'" : ", '") + keyword + "' " + std::to_string(times);
        if (unnamed_) list += ", ...";
        return std::to_string(count_) + " statements of keywords OBJ does not have (" + list + ")";
    }

private:
    static constexpr std::size_t kNamed = 8;
    std::size_t count_ = 0;
    std::map<std::string, std::size_t> keywords_;
    bool unnamed_ = false;
};

// Clamps `color`'s components to [0, 1], the range of display values; false where one was outside it.
bool clampedToUnit(Eigen::Ref<Eigen::Vector3d> color) {
    const Eigen::Vector3d inside = color.cwiseMax(0.0).cwiseMin(1.0);
    const bool was = inside == color;
    color = inside;
    return was;
}

// A map statement's -bm option (its bump multiplier), 1 where it has none or it is no finite number.
double bumpMultiplier(std::string_view statement) {
    const std::size_t at = statement.find("-bm");
    if (at == std::string_view::npos) return 1;
    std::string_view after = statement.substr(at + 3);
    while (!after.empty() && (after.front() == ' ' || after.front() == '\t')) after.remove_prefix(1);
    double value = 1;
    const auto [end, error] = std::from_chars(after.data(), after.data() + after.size(), value);
    return error == std::errc() && std::isfinite(value) ? value : 1;
}

// Reads a .mtl library into `scene`; returns the material index of every name.
std::map<std::string, int> readMaterialLibrary(const fs::path& library, Scene& scene) {
    std::map<std::string, int> byName;
    std::error_code error;
    if (!fs::is_regular_file(library, error)) {
        scene.warnings.push_back(library.filename().string() + ": material library not found; default material used");
        return byName;
    }
    const std::vector<unsigned char> bytes = readFileBytes(library);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    TextScanner scanner(library, text);
    Statements statements(scanner);
    Material* current = nullptr;
    std::map<std::string, int> textureOfFile;
    bool clamped = false;              // a colour component outside [0, 1]
    std::set<std::string> notCarried;  // texture statements without a glTF slot
    // The texture a map statement names: its file is the last word (options such as -s or -o precede it).
    const auto texture = [&](std::string_view statement) {
        std::string name = rest(statement);
        const std::size_t space = name.find_last_of(" \t");
        if (space != std::string::npos && name[0] == '-') name = name.substr(space + 1);
        auto [entry, inserted] = textureOfFile.try_emplace(name, static_cast<int>(scene.textures.size()));
        if (inserted) {
            bool found = false;
            scene.textures.push_back(textureOfImageFile(library.parent_path(), name, found));
            if (!found)
                scene.warnings.push_back(library.filename().string() + ": texture '" + name +
                                         "' not found; its reference is kept");
        }
        return entry->second;
    };
    while (!statements.atEnd()) {
        std::string_view line = statements.next();
        const std::string_view keyword = nextWord(line);
        if (keyword == "newmtl") {
            const std::string name = rest(line);
            scene.materials.emplace_back();
            current = &scene.materials.back();
            current->name = name;
            current->metallicFactor = 0;  // OBJ materials are not metals
            current->roughnessFactor = 1;
            current->phong = PhongMaterial();
            byName[name] = static_cast<int>(scene.materials.size()) - 1;
            continue;
        }
        if (!current || keyword.empty()) continue;
        auto readColor = [&]() {
            Eigen::Vector3d color;
            for (int c = 0; c < 3; ++c) color[c] = nextFiniteNumber<double>(line, scanner, "colour component");
            clamped = !clampedToUnit(color) || clamped;
            return color;
        };
        // Colours are display values (sRGB-encoded), as in X3D's Phong Material and as three.js's MTLLoader
        // reads them: glTF's factors are their linear values, the Phong fields keep them as they are.
        if (keyword == "Kd") {
            current->phong->diffuseColor = readColor();
            current->baseColorFactor.head<3>() = srgbToLinear(current->phong->diffuseColor);
        } else if (keyword == "Ks") {
            current->phong->specularColor = readColor();
        } else if (keyword == "Ke") {
            current->phong->emissiveColor = readColor();
            current->emissiveFactor = srgbToLinear(current->phong->emissiveColor);
        } else if (keyword == "Ns") {
            current->phong->shininess = std::clamp(nextFiniteNumber<double>(line, scanner, "Ns") / 1000.0, 0.0, 1.0);
        } else if (keyword == "d" || keyword == "Tr") {
            const double value = nextFiniteNumber<double>(line, scanner, "transparency");
            const double opacity = keyword == "d" ? value : 1 - value;
            current->baseColorFactor[3] = opacity;
            current->phong->transparency = 1 - opacity;
            if (opacity < 1) current->alphaMode = Material::AlphaMode::Blend;
        } else if (keyword == "map_Kd") {
            current->baseColorTexture.texture = texture(line);
        } else if (keyword == "map_Ke") {
            // As three.js's MTLLoader draws it: the texture times Ke (black where the material gives none).
            current->emissiveTexture.texture = texture(line);
        } else if (keyword == "norm") {
            // A normal map (three.js's MTLLoader: normalMap), its -bm the normal scale.
            current->normalTexture.texture = texture(line);
            current->normalTexture.scale = bumpMultiplier(line);
        } else if ((keyword.size() > 4 && keyword.substr(0, 4) == "map_") || keyword == "bump" || keyword == "disp" ||
                   keyword == "decal" || keyword == "refl") {
            // map_Ks, map_Ns, map_d, map_Bump (a height map or, from Blender, a normal map: the file does not
            // say which), ...: glTF's material has no slot that draws them so.
            notCarried.insert(std::string(keyword));
        }
    }
    const std::string name = library.filename().string();
    if (clamped) scene.warnings.push_back(name + ": colour components outside [0, 1] clamped");
    if (!notCarried.empty()) {
        std::string list;
        for (const std::string& keyword : notCarried) list += (list.empty() ? "" : ", ") + keyword;
        scene.warnings.push_back(name + ": " + list +
                                 " left out (glTF's material has no slot that draws them as an OBJ viewer does)");
    }
    return byName;
}

struct CornerKey {
    int position, texcoord, normal;
    bool operator<(const CornerKey& other) const {
        return std::tie(position, texcoord, normal) < std::tie(other.position, other.texcoord, other.normal);
    }
};

// The group being read: its mesh, and per topology (faces, lines, points) and material a primitive with its
// corner index.
struct Group {
    std::string name;
    Mesh mesh;
    std::map<std::pair<Topology, int>, std::size_t> primitiveOf;
    std::vector<std::map<CornerKey, std::uint32_t>> cornerIndex;
};

}  // namespace

Scene readObj(const fs::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    if (bytes.empty()) throw FileError(file, "the file is empty");
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    checkIsText(file, text);
    TextScanner scanner(file, text);
    Statements statements(scanner);
    Scene scene;
    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<Eigen::Vector4d> vertexColors;
    std::vector<Eigen::Vector2d> texcoords;
    std::map<std::string, int> materials;
    int currentMaterial = -1;
    std::vector<Group> groups(1);
    groups[0].name = file.stem().string();
    std::size_t curves = 0, degenerateFaces = 0, weighted = 0, beyondColor = 0;
    bool anyColors = false, clampedColors = false;
    std::size_t statementCount = 0;
    UnknownStatements unknown;

    auto resolve = [&](std::string_view word, std::size_t count, const char* what) -> int {
        long long index;
        if (!parseNumber(word, index) || index == 0) scanner.fail(std::string("invalid ") + what + " index '" + std::string(word) + "'");
        const long long resolved = index < 0 ? static_cast<long long>(count) + index : index - 1;  // negative: relative
        if (resolved < 0 || resolved >= static_cast<long long>(count))
            scanner.fail(std::string(what) + " index " + std::string(word) + " out of range (" + std::to_string(count) + " defined)");
        return static_cast<int>(resolved);
    };

    while (!statements.atEnd()) {
        std::string_view line = statements.next();
        const std::string_view keyword = nextWord(line);
        if (keyword.empty()) continue;
        ++statementCount;
        if (keyword == "v") {
            Eigen::Vector3d p;
            for (int c = 0; c < 3; ++c) p[c] = nextFiniteNumber<double>(line, scanner, "vertex coordinate");
            positions.push_back(p);
            // What follows x y z: w (one number), the weight of rational curves and surfaces, which polygons have
            // no use for (ignored, with a warning where it is not 1); r g b, a vertex colour; or r g b and more, as
            // where a writer adds an alpha ("x y z r g b a"), read as three.js's OBJLoader reads them: the colour,
            // the rest ignored (with a warning). Five numbers make no vertex.
            const std::size_t extra = wordCount(line);
            if (extra == 1) {
                weighted += nextFiniteNumber<double>(line, scanner, "vertex weight w") != 1;
            } else if (extra == 2) {
                scanner.fail("a vertex of 5 numbers (x y z, x y z w or x y z r g b expected)");
            } else if (extra >= 3) {
                beyondColor += extra > 3;
                // Display values (sRGB-encoded, as three.js's OBJLoader reads them); COLOR_0 is linear.
                Eigen::Vector4d color(1, 1, 1, 1);
                for (int c = 0; c < 3; ++c) color[c] = nextFiniteNumber<double>(line, scanner, "vertex colour");
                clampedColors = !clampedToUnit(color.head<3>()) || clampedColors;
                vertexColors.resize(positions.size(), Eigen::Vector4d(1, 1, 1, 1));
                vertexColors.back() = linearFromSrgbColor(color);
                anyColors = true;
            }
        } else if (keyword == "vn") {
            Eigen::Vector3d n;
            for (int c = 0; c < 3; ++c) n[c] = nextNumber<double>(line, scanner, "a normal component");
            normals.push_back(n.allFinite() ? n : Eigen::Vector3d::Zero());
        } else if (keyword == "vt") {
            const double u = nextFiniteNumber<double>(line, scanner, "texture coordinate");
            std::string_view vText = line;
            const double v =
                nextWord(vText).empty() ? 0.0 : nextFiniteNumber<double>(line, scanner, "texture coordinate");
            texcoords.emplace_back(u, 1 - v);  // OBJ's v points up, glTF's down
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            const Topology topology = keyword == "f"   ? Topology::Triangles
                                      : keyword == "l" ? Topology::Lines
                                                       : Topology::Points;
            std::vector<CornerKey> corners;
            for (std::string_view word = nextWord(line); !word.empty(); word = nextWord(line)) {
                CornerKey key{-1, -1, -1};
                const std::size_t slash1 = word.find('/');
                key.position = resolve(word.substr(0, slash1), positions.size(), "vertex");
                if (slash1 != std::string_view::npos) {
                    const std::string_view afterFirst = word.substr(slash1 + 1);
                    const std::size_t slash2 = afterFirst.find('/');
                    const std::string_view vt = afterFirst.substr(0, slash2);
                    if (!vt.empty()) key.texcoord = resolve(vt, texcoords.size(), "texture coordinate");
                    if (slash2 != std::string_view::npos && slash2 + 1 < afterFirst.size())
                        key.normal = resolve(afterFirst.substr(slash2 + 1), normals.size(), "normal");
                }
                corners.push_back(key);
            }
            if (topology == Topology::Triangles && corners.size() < 3)
                scanner.fail("a face with fewer than 3 vertices");
            if (topology == Topology::Lines && corners.size() < 2) scanner.fail("a line with fewer than 2 vertices");
            Group& group = groups.back();
            auto [entry, inserted] =
                group.primitiveOf.try_emplace({topology, currentMaterial}, group.mesh.primitives.size());
            if (inserted) {
                group.mesh.primitives.emplace_back();
                group.mesh.primitives.back().material = currentMaterial;
                group.mesh.primitives.back().topology = topology;
                group.cornerIndex.emplace_back();
            }
            Primitive& primitive = group.mesh.primitives[entry->second];
            auto& cornerIndex = group.cornerIndex[entry->second];
            std::vector<std::uint32_t> local;
            std::vector<Eigen::Vector3d> polygon;
            for (const CornerKey& key : corners) {
                auto [corner, isNew] = cornerIndex.try_emplace(key, static_cast<std::uint32_t>(primitive.positions.size()));
                if (isNew) {
                    primitive.positions.push_back(positions[key.position]);
                    // Attributes are filled per vertex; a vertex without one gets a neutral value, and the
                    // attribute is dropped at the end when no vertex of the primitive had it.
                    primitive.normals.push_back(key.normal >= 0 ? normals[key.normal] : Eigen::Vector3d::Zero());
                    primitive.texcoords.push_back(key.texcoord >= 0 ? texcoords[key.texcoord] : Eigen::Vector2d::Zero());
                    primitive.colors.push_back(key.position < static_cast<int>(vertexColors.size())
                                                   ? vertexColors[key.position]
                                                   : Eigen::Vector4d(1, 1, 1, 1));
                }
                local.push_back(corner->second);
                polygon.push_back(positions[key.position]);
            }
            if (topology == Topology::Lines)
                for (std::size_t k = 0; k + 1 < local.size(); ++k) primitive.lines.push_back({local[k], local[k + 1]});
            if (topology != Topology::Triangles) continue;  // a point is its vertex
            const auto triangles = triangulateFace(polygon);
            if (triangles.empty()) ++degenerateFaces;
            for (const Triangle& t : triangles) primitive.triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
        } else if (keyword == "o" || keyword == "g") {
            const std::string name = rest(line);
            if (!groups.back().mesh.primitives.empty()) groups.emplace_back();
            groups.back().name = name;
        } else if (keyword == "usemtl") {
            const std::string name = rest(line);
            auto found = materials.find(name);
            if (found == materials.end()) {
                // An unknown material still gets its own (default-looking) entry, so that parts stay apart.
                scene.materials.emplace_back();
                scene.materials.back().name = name;
                found = materials.emplace(name, static_cast<int>(scene.materials.size()) - 1).first;
                scene.warnings.push_back(file.filename().string() + ": material '" + name + "' is not defined");
            }
            currentMaterial = found->second;
        } else if (keyword == "mtllib") {
            const std::string name = rest(line);
            for (const auto& [materialName, index] : readMaterialLibrary(file.parent_path() / name, scene))
                materials[materialName] = index;
        } else if (keyword == "curv" || keyword == "curv2" || keyword == "surf" || keyword == "cstype") {
            ++curves;
        } else if (!isSkippedObjStatement(keyword)) {
            unknown.add(keyword);
        }
    }
    if (statementCount > 0 && unknown.count() == statementCount)
        throw FileError(file, "not an OBJ file (none of its " + std::to_string(statementCount) +
                                  " statements is one of OBJ's, such as v, f, o or g)");

    // Vertices and nothing drawn from them: a point cloud (a scan), drawn as points, as three.js's OBJLoader
    // gives it.
    const bool pointCloud =
        std::all_of(groups.begin(), groups.end(), [](const Group& g) { return g.mesh.primitives.empty(); });
    if (pointCloud && !positions.empty()) {
        Primitive& cloud = groups.back().mesh.primitives.emplace_back();
        cloud.topology = Topology::Points;
        cloud.positions = positions;
        cloud.colors = vertexColors;
        cloud.colors.resize(anyColors ? positions.size() : 0, Eigen::Vector4d(1, 1, 1, 1));
        groups.back().cornerIndex.emplace_back();
    }
    // Which attributes the file really had: a primitive keeps one only if every face corner named it.
    for (Group& group : groups) {
        if (group.mesh.primitives.empty()) continue;
        for (std::size_t p = 0; p < group.mesh.primitives.size(); ++p) {
            Primitive& primitive = group.mesh.primitives[p];
            bool allNormals = true, allTexcoords = true;
            for (const auto& [key, index] : group.cornerIndex[p]) {
                allNormals = allNormals && key.normal >= 0;
                allTexcoords = allTexcoords && key.texcoord >= 0;
            }
            if (!allNormals) primitive.normals.clear();
            if (!allTexcoords) primitive.texcoords.clear();
            if (!anyColors) primitive.colors.clear();
        }
        group.mesh.name = group.name;
        Node node;
        node.name = group.name;
        node.mesh = static_cast<int>(scene.meshes.size());
        scene.meshes.push_back(std::move(group.mesh));
        scene.roots.push_back(static_cast<int>(scene.nodes.size()));
        scene.nodes.push_back(std::move(node));
    }
    const std::string name = file.filename().string();
    if (clampedColors) scene.warnings.push_back(name + ": vertex colour components outside [0, 1] clamped");
    if (curves) scene.warnings.push_back(name + ": " + std::to_string(curves) + " curve and surface statements skipped");
    if (weighted)
        scene.warnings.push_back(name + ": " + std::to_string(weighted) +
                                 " vertex weights w other than 1 ignored (they weigh rational curves and surfaces, "
                                 "not polygons)");
    if (beyondColor)
        scene.warnings.push_back(name + ": " + std::to_string(beyondColor) +
                                 " vertices' numbers after x y z r g b ignored (as three.js's OBJLoader ignores them)");
    if (unknown.count()) scene.warnings.push_back(name + ": " + unknown.describe() + " ignored");
    if (degenerateFaces)
        scene.warnings.push_back(name + ": " + std::to_string(degenerateFaces) +
                                 " faces with fewer than 3 corners or no area skipped");
    return scene;
}

}  // namespace symcompress
