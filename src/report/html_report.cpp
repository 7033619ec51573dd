// The HTML report: the page's data (geometry, classes, symmetry elements, charts) as one JSON object, and
// the page around it with the viewer inlined (viewer/src/report.js draws it).
#include "symcompress/html_report.hpp"

#include "common/markup_text.hpp"
#include "report/preview_geometry.hpp"
#include "report/viewer_script.hpp"
#include "symcompress/assembly.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/compression_plan.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

namespace symcompress {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

constexpr double kPi = 3.14159265358979323846;

json vectorJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

template <class T>
std::string base64Of(const std::vector<T>& values) {
    return base64(values.data(), values.size() * sizeof(T));
}

// Column-major float matrices, 16 a copy, as the viewer's InstancedMesh takes them.
std::string matricesBase64(const std::vector<Eigen::Matrix4d>& transforms) {
    std::vector<float> floats;
    floats.reserve(transforms.size() * 16);
    for (const Eigen::Matrix4d& m : transforms)
        for (int i = 0; i < 16; ++i) floats.push_back(float(m.data()[i]));
    return base64Of(floats);
}

// The distinct mirror planes and rotation axes of a group (an axis with the largest order found on it),
// and for each element the plane or axis that draws it.
struct ElementsToDraw {
    std::vector<Eigen::Vector3d> planes;
    std::vector<std::pair<Eigen::Vector3d, int>> axes;  // axis, order
    std::vector<json> drawnBy;                          // per element: {kind, index} or null
};

ElementsToDraw elementsToDraw(const SymmetryGroup& group) {
    ElementsToDraw out;
    auto find = [](const auto& list, const Eigen::Vector3d& direction, auto&& directionOf) {
        for (std::size_t i = 0; i < list.size(); ++i)
            if (std::abs(directionOf(list[i]).dot(direction)) > 1 - 1e-6) return int(i);
        return -1;
    };
    for (const Symmetry& s : group.elements) {
        json drawn = nullptr;
        if (s.kind == Symmetry::Kind::Mirror && s.axis.norm() > 0.5) {
            int index = find(out.planes, s.axis.normalized(), [](const Eigen::Vector3d& n) { return n; });
            if (index < 0) index = int(out.planes.size()), out.planes.push_back(s.axis.normalized());
            drawn = {{"kind", "plane"}, {"index", index}};
        } else if (s.kind == Symmetry::Kind::Rotation && s.axis.norm() > 0.5 && s.angle > 1e-9) {
            // The order of an axis: 2 pi over its smallest turn (a 4-fold axis has turns of 90 and 180 degrees).
            const int order = std::max(s.fold, int(std::lround(2 * kPi / s.angle)));
            int index = find(out.axes, s.axis.normalized(), [](const auto& a) { return a.first; });
            if (index < 0) index = int(out.axes.size()), out.axes.push_back({s.axis.normalized(), order});
            out.axes[std::size_t(index)].second = std::max(out.axes[std::size_t(index)].second, order);
            drawn = {{"kind", "axis"}, {"index", index}};
        }
        out.drawnBy.push_back(drawn);
    }
    return out;
}

// What the viewer draws of a group: its planes and axes about `centre`, sized to `size`.
json symmetryJson(const SymmetryGroup& group, const Eigen::Vector3d& centre, double size) {
    const ElementsToDraw drawn = elementsToDraw(group);
    json planes = json::array(), axes = json::array(), elements = json::array();
    for (const Eigen::Vector3d& n : drawn.planes) planes.push_back({{"normal", vectorJson(n)}});
    for (const auto& [axis, order] : drawn.axes) axes.push_back({{"axis", vectorJson(axis)}, {"fold", order}});
    for (std::size_t e = 0; e < group.elements.size(); ++e) {
        const Symmetry& s = group.elements[e];
        if (s.kind == Symmetry::Kind::Identity) continue;
        elements.push_back({{"id", e},
                            {"type", kindName(s.kind)},
                            {"axis", vectorJson(s.axis)},
                            {"angle", s.angle},
                            {"fold", s.fold},
                            {"deviation", s.deviation},
                            {"drawn", drawn.drawnBy[e]}});
    }
    return {{"name", group.name}, {"order", group.order()}, {"centre", vectorJson(centre)}, {"size", size},
            {"planes", planes},   {"axes", axes},           {"elements", elements}};
}

// `text` inside a <script> element: "</" could end it early; "<\/" means the same in JSON and in
// JavaScript strings and regular expressions (the only places a minified script has it).
std::string scriptSafe(std::string text) {
    for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
        text.replace(at, 2, "<\\/");
    return text;
}

const char* kStyle = R"css(
* { box-sizing: border-box; }
body { font: 14px/1.4 system-ui, sans-serif; margin: 0; color: #1f2328; background: #f6f7f9; }
header { padding: 10px 16px; background: #fff; border-bottom: 1px solid #d8dbe0; }
h1 { font-size: 18px; margin: 0 0 4px; }
h2 { font-size: 15px; margin: 8px 0; }
.summary { margin: 0; color: #444; }
.notes { margin: 4px 0 0; color: #8a4b00; }
main { display: grid; grid-template-columns: minmax(0, 3fr) minmax(340px, 2fr); gap: 12px; padding: 12px 16px; }
#view { position: relative; background: #fff; border: 1px solid #d8dbe0; border-radius: 6px; }
#scene { width: 100%; height: 62vh; min-height: 360px; display: block; border-radius: 6px; }
#legend { position: absolute; left: 8px; bottom: 8px; font-size: 12px; background: rgba(255,255,255,.85);
          padding: 4px 8px; border-radius: 4px; }
#selection { min-height: 1.4em; padding: 4px 8px; font-size: 13px; }
#side { background: #fff; border: 1px solid #d8dbe0; border-radius: 6px; padding: 6px 10px; max-height: 72vh;
        overflow: auto; }
table { border-collapse: collapse; width: 100%; font-size: 13px; }
th { text-align: left; cursor: pointer; position: sticky; top: 0; background: #eef0f3; padding: 4px 6px;
     white-space: nowrap; user-select: none; }
th[data-sorted=up]::after { content: " \25B2"; font-size: 10px; }
th[data-sorted=down]::after { content: " \25BC"; font-size: 10px; }
td { padding: 3px 6px; border-bottom: 1px solid #eceef1; }
tbody tr { cursor: pointer; }
tbody tr:hover { background: #f3f6fb; }
tbody tr.selected { background: #ffe9b3; }
.swatch { display: inline-block; width: 10px; height: 10px; border-radius: 2px; margin-right: 6px; }
.grey { background: #9a9a9a; } .dim { background: #a9b4c8; }
.region { background: linear-gradient(90deg, #8fd19e 50%, #2f7a43 50%); }
#charts { display: flex; flex-wrap: wrap; gap: 16px; padding: 0 16px 16px; }
figure { margin: 0; background: #fff; border: 1px solid #d8dbe0; border-radius: 6px; padding: 8px 12px; }
figcaption { font-weight: 600; margin-bottom: 4px; }
svg text { font-size: 12px; fill: #333; }
button { font: inherit; padding: 2px 8px; }
)css";

// The page: the data as JSON, the viewer after it.
std::string page(const std::string& title, const std::string& summary, const std::vector<std::string>& notes,
                 const std::string& side, const std::string& legend, const json& data) {
    std::string script = viewerScript();
    if (script.empty())
        throw std::runtime_error(
            "symcompress was built without the HTML report's viewer (Node.js and npm are needed when it is built)");
    std::string html =
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
        escapedMarkup(title) + "</title>\n<style>" + kStyle + "</style></head>\n<body>\n<header><h1>" +
        escapedMarkup(title) + "</h1><p class=\"summary\">" + escapedMarkup(summary) + "</p>";
    for (const std::string& note : notes) html += "<p class=\"notes\">" + escapedMarkup(note) + "</p>";
    html += "</header>\n<main><section id=\"view\"><canvas id=\"scene\"></canvas><div id=\"legend\">" + legend +
            "</div></section>\n<section id=\"side\">" + side +
            "</section></main>\n<section id=\"charts\"></section>\n<script type=\"application/json\" "
            "id=\"symcompress-data\">" +
            scriptSafe(data.dump()) + "</script>\n<script>" + scriptSafe(std::move(script)) +
            "</script>\n</body></html>\n";
    return html;
}

json boundsJson(const Eigen::AlignedBox3d& box) {
    if (box.isEmpty()) return {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}};
    return {{"min", vectorJson(box.min())}, {"max", vectorJson(box.max())}};
}

// The sources as geometries within the budget; a note when that took a preview.
json geometriesJson(const std::vector<PreviewSource>& sources, std::size_t budget, std::vector<std::string>& notes) {
    std::size_t full = 0;
    for (const PreviewSource& source : sources) full += previewTriangles(source, 0);
    const double cell = previewCell(sources, budget);
    json geometries = json::array();
    std::size_t kept = 0;
    for (const PreviewSource& source : sources) {
        const PreviewGeometry geometry = previewGeometry(source, cell);
        kept += geometry.triangles();
        json entry{{"positions", base64Of(geometry.positions)}, {"indices", base64Of(geometry.indices)}};
        if (source.vertexClasses) entry["vertexClasses"] = base64Of(geometry.vertexClasses);
        geometries.push_back(std::move(entry));
    }
    if (cell > 0)
        notes.push_back("Preview: the " + std::to_string(full) + " triangles of the stored meshes are drawn as " +
                        std::to_string(kept) + " (vertices clustered in cells of 1/" +
                        std::to_string(std::lround(1 / cell)) + " of each part's size, to keep the page under " +
                        std::to_string(budget) + " triangles).");
    return geometries;
}

// The output's bytes by kind. JSON and instances are estimates from the report where the file does not
// say: instances are bytes_per_instance times the instance nodes (they are part of the JSON), images the
// scene's textures.
json bytesByKind(const Scene& input, const CompressionReport& report) {
    double images = 0;
    for (const Texture& texture : input.textures) images += double(texture.bytes.size());
    const double instances = report.bytesPerInstance * double(report.stats.instances);
    const double total = double(report.outputBytes);
    double jsonBytes = 0;
    const FileFormat format = formatFromExtension(report.output);
    if (format == FileFormat::Glb) {
        std::ifstream in(report.output, std::ios::binary);
        char header[20] = {};
        if (in.read(header, sizeof header)) {
            std::uint32_t length = 0;
            std::memcpy(&length, header + 12, 4);
            jsonBytes = length;
        }
    } else if (format == FileFormat::Gltf) {
        std::error_code error;
        jsonBytes = double(fs::file_size(report.output, error));
        if (error) jsonBytes = 0;
    }
    json kinds = json::array();
    if (format == FileFormat::Glb || format == FileFormat::Gltf) {
        kinds.push_back({{"label", "geometry"}, {"value", std::max(0.0, total - jsonBytes - images)}});
        kinds.push_back({{"label", "images"}, {"value", images}});
        kinds.push_back({{"label", "JSON (other)"}, {"value", std::max(0.0, jsonBytes - instances)}});
    } else {
        kinds.push_back({{"label", "geometry, text"}, {"value", std::max(0.0, total - instances)}});
    }
    kinds.push_back({{"label", "instances"}, {"value", instances}, {"note", "(estimate)"}});
    return kinds;
}

json chartsJson(const Scene& input, const CompressionReport& report) {
    auto bytesOrNull = [](const std::optional<std::uintmax_t>& bytes) { return bytes ? json(*bytes) : json(nullptr); };
    const CompressionStats& stats = report.stats;
    json ablation =
        json::array({{{"label", "Draco alone"}, {"value", bytesOrNull(report.ablation.dracoAlone)}},
                     {{"label", "instancing"}, {"value", bytesOrNull(report.ablation.instancing)}},
                     {{"label", "+ regions"}, {"value", bytesOrNull(report.ablation.instancingAndRegions)}},
                     {{"label", "final"}, {"value", report.outputBytes}, {"note", "(" + report.plan + ")"}}});
    json seconds = json::array({{{"label", "read"}, {"value", report.secondsRead}},
                                {{"label", "tiles"}, {"value", stats.secondsTiles}},
                                {{"label", "classes"}, {"value", stats.secondsClasses}},
                                {{"label", "plan"}, {"value", stats.secondsPlan}},
                                {{"label", "write"}, {"value", report.secondsWrite}}});
    return {{"ablation", ablation}, {"kinds", bytesByKind(input, report)}, {"seconds", seconds}};
}

enum class Storage { AsTheyAre, Instanced, Region, Assembly, SceneSymmetry };
const char* storageName(Storage storage) {
    switch (storage) {
    case Storage::AsTheyAre: return "as they are";
    case Storage::Instanced: return "instanced";
    case Storage::Region: return "region";
    case Storage::Assembly: return "assembly";
    case Storage::SceneSymmetry: return "scene symmetry";
    }
    return "";
}
Storage storageOf(SharedPart::Mechanism mechanism) {
    switch (mechanism) {
    case SharedPart::Mechanism::SceneSymmetry: return Storage::SceneSymmetry;
    case SharedPart::Mechanism::Assembly: return Storage::Assembly;
    case SharedPart::Mechanism::Class: return Storage::Instanced;
    case SharedPart::Mechanism::Region: return Storage::Region;
    }
    return Storage::AsTheyAre;
}

// The scene's own group: from the plan's part when it used one (its nodes are the elements about the
// centre), else as the assembly stage finds it.
SymmetryGroup sceneGroupOf(const SceneAnalysis& analysis, const CompressionPlan& plan) {
    for (const SharedPart& part : plan.shared)
        if (part.mechanism == SharedPart::Mechanism::SceneSymmetry && !part.nodes.empty()) {
            SymmetryGroup group;
            group.name = part.group;
            group.centroid = part.nodes.front().transform.topRightCorner<3, 1>();
            for (const PlacedCopy& node : part.nodes)
                group.elements.push_back(describeOrthogonal(node.transform.topLeftCorner<3, 3>()));
            return group;
        }
    if (analysis.classification.classes.empty()) return {};
    return assemblySymmetries(analysis.classification);
}

}  // namespace

bool htmlReportAvailable() { return !viewerScript().empty(); }

std::string compressionReportHtml(const CompressionPicture& picture, const HtmlReportOptions& options) {
    const SceneAnalysis& analysis = picture.analysis;
    const CompressionPlan& plan = picture.plan;
    const CompressionReport& report = picture.report;
    const TileClassification& classification = analysis.classification;
    const std::vector<Tile>& tiles = analysis.tiles;
    const Eigen::AlignedBox3d bounds = sceneStatistics(picture.input).bounds;

    std::vector<std::uint32_t> classOf(tiles.size(), kNoClass);
    for (std::size_t k = 0; k < classification.classes.size(); ++k)
        for (std::size_t t : classification.classes[k].members) classOf[t] = std::uint32_t(k);
    std::vector<Storage> storage(tiles.size(), Storage::AsTheyAre);
    for (const SharedPart& part : plan.shared)
        for (std::size_t t : part.tiles) storage[t] = storageOf(part.mechanism);

    std::vector<PreviewSource> sources;
    json draws = json::array();
    // Classes stored once: their stored mesh (the tile or its fundamental region) with a matrix per node.
    std::map<std::uint32_t, double> classBytes;
    std::size_t measured = 0;
    for (const SharedPart& part : plan.shared) {
        if (part.mechanism != SharedPart::Mechanism::Class && part.mechanism != SharedPart::Mechanism::Region) continue;
        if (part.tiles.empty() || part.nodes.empty()) continue;
        const std::uint32_t k = classOf[part.tiles.front()];
        PreviewSource source;
        for (const Primitive& primitive : part.mesh.primitives)
            source.pieces.push_back({&primitive.positions, &primitive.triangles, k});
        std::vector<Eigen::Matrix4d> transforms;
        for (const PlacedCopy& node : part.nodes) transforms.push_back(node.transform);
        json draw{{"kind", part.mechanism == SharedPart::Mechanism::Region ? "region" : "class"},
                  {"geometry", sources.size()},
                  {"cls", k},
                  {"matrices", matricesBase64(transforms)}};
        if (part.mechanism == SharedPart::Mechanism::Region) {
            // Node i * copies of each member is the region itself (its group's identity comes first).
            const std::size_t copies = std::max<std::size_t>(1, part.nodes.size() / part.tiles.size());
            std::vector<std::uint8_t> roles(part.nodes.size());
            for (std::size_t i = 0; i < roles.size(); ++i) roles[i] = i % copies == 0;
            draw["roles"] = base64Of(roles);
        }
        draws.push_back(std::move(draw));
        sources.push_back(std::move(source));
        // What the class costs as written: its mesh, measured by the output's writer, and its nodes.
        constexpr std::size_t kMostMeasured = 3000;  // each is one encoding of the mesh
        if (picture.costs && picture.costs->meshBytes && k != kNoClass && measured++ < kMostMeasured) {
            double bytes = report.bytesPerInstance * double(part.nodes.size());
            for (const Primitive& primitive : part.mesh.primitives) bytes += picture.costs->meshBytes(primitive);
            classBytes[k] += bytes;
        }
    }
    // Tiles drawn by assemblies and the scene's symmetry, and the members of a class stored as they are: their
    // class's prototype placed on each (role 1: stored as it is, drawn grey), never a copy of every triangle.
    struct Placed {
        std::vector<Eigen::Matrix4d> transforms;
        std::vector<std::uint8_t> roles;
    };
    std::map<std::uint32_t, Placed> placedByClass;
    for (std::size_t k = 0; k < classification.classes.size(); ++k) {
        const CongruenceClass& c = classification.classes[k];
        for (std::size_t i = 0; i < c.members.size(); ++i) {
            const Storage s = storage[c.members[i]];
            const bool asItIs = s == Storage::AsTheyAre && c.members.size() > 1;
            if (s != Storage::Assembly && s != Storage::SceneSymmetry && !asItIs) continue;
            placedByClass[std::uint32_t(k)].transforms.push_back(c.placements[i].matrix());
            placedByClass[std::uint32_t(k)].roles.push_back(asItIs);
        }
    }
    for (const auto& [k, placed] : placedByClass) {
        const Tile& prototype = tiles[classification.classes[k].prototype];
        sources.push_back({{{&prototype.mesh.positions, &prototype.mesh.triangles, k}}, false});
        draws.push_back({{"kind", "tiles"},
                         {"geometry", sources.size() - 1},
                         {"cls", k},
                         {"matrices", matricesBase64(placed.transforms)},
                         {"roles", base64Of(placed.roles)}});
    }
    // Tiles stored as they are that are alone in their class: one geometry in world coordinates, a class per
    // vertex.
    PreviewSource merged;
    merged.vertexClasses = true;
    for (std::size_t t = 0; t < tiles.size(); ++t)
        if (storage[t] == Storage::AsTheyAre &&
            (classOf[t] == kNoClass || classification.classes[classOf[t]].members.size() == 1))
            merged.pieces.push_back({&tiles[t].mesh.positions, &tiles[t].mesh.triangles, classOf[t]});
    if (!merged.pieces.empty()) {
        draws.push_back({{"kind", "merged"}, {"geometry", sources.size()}});
        sources.push_back(std::move(merged));
    }
    // The meshes the input shares with scaled copies, kept as they are: one draw per mesh.
    std::map<int, std::vector<Eigen::Matrix4d>> keptByMesh;
    for (const KeptInstance& kept : analysis.keptInstances) keptByMesh[kept.mesh].push_back(kept.transform);
    for (const auto& [mesh, transforms] : keptByMesh) {
        PreviewSource source;
        for (const Primitive& primitive : picture.input.meshes[std::size_t(mesh)].primitives)
            source.pieces.push_back({&primitive.positions, &primitive.triangles, kNoClass});
        draws.push_back(
            {{"kind", "kept"}, {"geometry", sources.size()}, {"cls", -1}, {"matrices", matricesBase64(transforms)}});
        sources.push_back(std::move(source));
    }

    std::vector<std::string> notes;
    const json geometries = geometriesJson(sources, options.maxTriangles, notes);
    if (!analysis.animatedSubtrees.empty())
        notes.push_back(std::to_string(analysis.animatedSubtrees.size()) +
                        " animated subtrees, kept as they are, are not drawn.");

    // The classes' table, the largest first when there are more than it lists.
    std::vector<std::size_t> order(classification.classes.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const auto weight = [&](std::size_t k) {
            return classification.classes[k].members.size() *
                   classification.shapes[classification.classes[k].prototype].triangles;
        };
        return weight(a) > weight(b);
    });
    if (order.size() > options.maxTableRows) {
        notes.push_back("The table lists the " + std::to_string(options.maxTableRows) + " largest of the " +
                        std::to_string(order.size()) + " classes.");
        order.resize(options.maxTableRows);
    }
    json classes = json::array();
    for (std::size_t k : order) {
        const CongruenceClass& c = classification.classes[k];
        const TileShape& shape = classification.shapes[c.prototype];
        std::map<Storage, std::size_t> counts;
        for (std::size_t t : c.members) ++counts[storage[t]];
        std::string stored;
        for (const auto& [kind, count] : counts)
            stored += (stored.empty() ? "" : ", ") + std::string(storageName(kind)) +
                      (counts.size() > 1 ? " " + std::to_string(count) : "");
        const auto bytes = classBytes.find(std::uint32_t(k));
        json entry{{"id", k},
                   {"members", c.members.size()},
                   {"triangles", shape.triangles},
                   {"group", shape.symmetry.name},
                   {"storage", stored},
                   {"bytes", bytes == classBytes.end() ? json(nullptr) : json(bytes->second)},
                   {"symmetry", nullptr}};
        if (shape.symmetry.order() > 1)
            entry["symmetry"] = symmetryJson(shape.symmetry, shape.symmetry.centroid, shape.diagonal);
        classes.push_back(std::move(entry));
    }

    const SymmetryGroup sceneGroup = sceneGroupOf(analysis, plan);
    json data{{"kind", "compress"},
              {"bounds", boundsJson(bounds)},
              {"geometries", geometries},
              {"draws", draws},
              {"classes", classes},
              {"classCount", classification.classes.size()},
              {"sceneSymmetry", nullptr},
              {"charts", chartsJson(picture.input, report)},
              {"report", json::parse(report.json())}};
    if (sceneGroup.order() > 1)
        data["sceneSymmetry"] = symmetryJson(sceneGroup, sceneGroup.centroid, classification.sceneDiagonal);

    const CompressionStats& stats = report.stats;
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2f", report.ratio);
    const std::string summary =
        report.input.filename().string() + " (" + std::to_string(report.inputBytes) + " bytes) -> " +
        report.output.filename().string() + " (" + std::to_string(report.outputBytes) + " bytes), ratio " + ratio +
        ", plan " + report.plan + ". " + std::to_string(stats.trianglesIn) + " triangles drawn, " +
        std::to_string(stats.trianglesStored) + " stored; " + std::to_string(stats.tiles) + " tiles in " +
        std::to_string(stats.classes) + " classes; " + std::to_string(stats.instances) + " instance nodes.";
    for (const std::string& warning : report.warnings) notes.push_back("warning: " + warning);
    std::string side =
        "<h2>Classes <button id=\"clear\" title=\"show every class\">show all</button></h2>"
        "<div id=\"selection\"></div>";
    if (sceneGroup.order() > 1)
        side += "<p>The scene's symmetry: <b>" + escapedMarkup(sceneGroup.name) + "</b> (order " +
                std::to_string(sceneGroup.order()) +
                (stats.tilesInSceneSymmetry ? ", used for " + std::to_string(stats.tilesInSceneSymmetry) + " tiles"
                                            : ", not used") +
                ") <label><input type=\"checkbox\" id=\"scene-elements\" checked> draw its planes and axes</label></p>";
    side += "<table id=\"classes\"></table>";
    const std::string legend =
        "<span class=\"swatch grey\"></span>stored as they are &nbsp; <span class=\"swatch\" "
        "style=\"background:hsl(200,68%,52%)\"></span>instanced (colour of its class) &nbsp; <span class=\"swatch "
        "region\"></span>fundamental region / its copies &nbsp; <span class=\"swatch dim\"></span>kept as the input "
        "shares it";
    return page("symcompress report: " + report.input.filename().string(), summary, notes, side, legend, data);
}

std::string detectionReportHtml(const TriangleMesh& mesh, const SymmetryGroup& group, const fs::path& input,
                                double tolerance, const HtmlReportOptions& options) {
    Eigen::AlignedBox3d bounds;
    for (const Eigen::Vector3d& p : mesh.positions) bounds.extend(p);
    const double size = bounds.isEmpty() ? 1 : bounds.diagonal().norm();
    std::vector<std::string> notes;
    const std::vector<PreviewSource> sources{{{{&mesh.positions, &mesh.triangles, kNoClass}}, false}};
    const json geometries = geometriesJson(sources, options.maxTriangles, notes);
    json draws = json::array();
    draws.push_back(
        {{"kind", "shape"}, {"geometry", 0}, {"cls", -1}, {"matrices", matricesBase64({Eigen::Matrix4d::Identity()})}});
    json data{{"kind", "detect"},
              {"bounds", boundsJson(bounds)},
              {"geometries", geometries},
              {"draws", draws},
              {"classes", json::array()},
              {"symmetry", symmetryJson(group, group.centroid, group.diagonal > 0 ? group.diagonal : size)}};
    for (const std::string& warning : group.warnings) notes.push_back("warning: " + warning);
    char line[160];
    std::snprintf(line, sizeof line, "group %s, order %d; %zu triangles; tolerance %g of the diagonal %g.",
                  group.name.c_str(), group.order(), mesh.triangles.size(), tolerance, group.diagonal);
    const std::string side = "<h2>Symmetry elements of " + escapedMarkup(group.name) +
                             "</h2><div id=\"selection\"></div><p>Click an element to draw only its plane or axis.</p>"
                             "<table id=\"classes\"></table>";
    const std::string legend = "mirror planes: blue discs &nbsp; rotation axes: lines labelled with their order";
    return page("symcompress detect: " + input.filename().string(), input.filename().string() + ": " + line, notes,
                side, legend, data);
}

void writeDetectionReport(const fs::path& file, const TriangleMesh& mesh, const SymmetryGroup& group,
                          const fs::path& input, double tolerance, const HtmlReportOptions& options) {
    refuseToOverwriteInputs(file, {input});
    writeFileAtomically(file, detectionReportHtml(mesh, group, input, tolerance, options));
}

}  // namespace symcompress
