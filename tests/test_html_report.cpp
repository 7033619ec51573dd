// The HTML report (symcompress --html, detect --html): one self-contained page; opened in headless
// Chromium with every request that would leave the machine blocked (tests/html_report_check.mjs).
#include "report/preview_geometry.hpp"
#include "symcompress/symcompress.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

fs::path sample(const std::string& name) { return fs::path(SYMCOMPRESS_SOURCE_DIR) / "samples" / name; }
fs::path viewerModules() { return SYMCOMPRESS_VIEWER_MODULES; }
fs::path chromium() {
    const char* chosen = std::getenv("CHROMIUM");
    return chosen ? fs::path(chosen) : fs::path("/usr/bin/chromium");
}

// Node.js, puppeteer-core (installed with the viewer, in the build folder) and Debian's chromium.
bool browserAvailable() {
    if (std::getenv("SYMCOMPRESS_SKIP_INTEROP")) return false;
    return fs::exists(viewerModules() / "puppeteer-core") && fs::exists(chromium()) &&
           runCommand("node --version").status == 0;
}

void skipUnlessBrowser() {
    if (!browserAvailable())
        WARN("skipped: needs Node.js, puppeteer-core in " << viewerModules().string() << " (npm ci when configuring)"
                                                          << " and Chromium at " << chromium().string()
                                                          << " (apt-get install chromium, or set CHROMIUM)");
}

// What html_report_check.mjs saw of the page.
nlohmann::json lookAt(const fs::path& page, const std::string& sortColumn) {
    std::string command = "node " + quoted(fs::path(SYMCOMPRESS_SOURCE_DIR) / "tests/html_report_check.mjs") +
                          " --modules " + quoted(viewerModules()) + " --page " + quoted(page);
    if (!sortColumn.empty()) command += " --sort " + sortColumn;
    return runJson(command);
}

// The checks every page passes.
void requireViewable(const nlohmann::json& seen) {
    INFO(seen.dump(1));
    CHECK(seen["blockedRequests"].empty());  // nothing asked for outside the machine
    CHECK(seen["consoleErrors"].empty());
    CHECK(seen["distinctColors"].get<int>() > 10);  // the scene is drawn, shaded: not one colour
    CHECK(seen["rows"] == seen["rowsReported"]);
    CHECK(seen["changedPixels"].get<long>() > 100);  // clicking a row changes the picture
}

TEST_CASE("html report: the compression's page is one file with the viewer and the plan inlined", "[html]") {
    if (!htmlReportAvailable()) {
        WARN("skipped: symcompress was built without Node.js and npm (no viewer to inline)");
        return;
    }
    TemporaryFolder folder;
    CompressOptions options;
    options.htmlReport = folder / "room.html";
    const CompressionReport report = compressFile(sample("room.glb"), folder / "room.glb", options);
    const std::string html = readTextFile(options.htmlReport);
    // Nothing loaded from elsewhere: one page, its scripts and styles inline.
    CHECK(html.find("<script src") == std::string::npos);
    CHECK(html.find("<link") == std::string::npos);
    CHECK(html.find("Three.js Authors") != std::string::npos);  // three.js inlined, with its licence
    const auto start = html.find("id=\"symcompress-data\">");
    REQUIRE(start != std::string::npos);
    const auto begin = start + std::strlen("id=\"symcompress-data\">");
    const nlohmann::json data = nlohmann::json::parse(html.substr(begin, html.find("</script>", begin) - begin));
    CHECK(data["kind"] == "compress");
    CHECK(data["classes"].size() == report.stats.classes);
    CHECK(data["report"]["classes"] == report.stats.classes);
    CHECK(data["charts"]["ablation"].size() == 4);
    // The room is symmetric as a whole: its group is drawn.
    CHECK(report.stats.sceneGroup != "C1");
    REQUIRE(data["sceneSymmetry"].is_object());
    CHECK(data["sceneSymmetry"]["name"] == report.stats.sceneGroup);
    CHECK(!data["sceneSymmetry"]["planes"].empty());
    // Stored meshes drawn by a matrix a copy: never more triangles embedded than stored.
    std::size_t embedded = 0;
    for (const auto& geometry : data["geometries"]) {
        const std::string indices = geometry["indices"];
        embedded += indices.size() / 4 * 3 / 12;  // base64: 4 characters for 3 bytes, 12 bytes a triangle
    }
    CHECK(embedded <= report.stats.trianglesIn);
}

TEST_CASE("html report: the report path may not be the input", "[html]") {
    if (!htmlReportAvailable()) return;
    TemporaryFolder folder;
    fs::copy_file(sample("bolts.glb"), folder / "bolts.glb");
    CompressOptions options;
    options.htmlReport = folder / "bolts.glb";
    CHECK_THROWS_AS(compressFile(folder / "bolts.glb", folder / "out.glb", options), FileError);
    CHECK(fs::file_size(folder / "bolts.glb") == fs::file_size(sample("bolts.glb")));
}

TEST_CASE("html report: the compression's page offline in headless Chromium", "[html][interop]") {
    if (!browserAvailable()) return skipUnlessBrowser();
    TemporaryFolder folder;
    const CommandResult run = runCommand(
        std::string(SYMCOMPRESS_CLI) + " " + quoted(sample("bolts.glb")) + " -o " + quoted(folder / "bolts_out.glb") +
        " --report " + quoted(folder / "report.json") + " --html " + quoted(folder / "bolts.html") + " -q");
    INFO(run.output);
    REQUIRE(run.status == 0);
    const auto report = nlohmann::json::parse(readTextFile(folder / "report.json"));
    const nlohmann::json seen = lookAt(folder / "bolts.html", "members");
    requireViewable(seen);
    CHECK(seen["rows"] == report["classes"]);  // every class listed
    CHECK(seen["sortColumnFound"] == true);
    CHECK(seen["sortedDescending"] == true);  // members: largest first
    CHECK(seen["firstRowAfterSort"].get<int>() > 1);
    CHECK(std::string(seen["selection"]).find("class ") == 0);
}

TEST_CASE("html report: the room's page with its scene symmetry in headless Chromium", "[html][interop]") {
    if (!browserAvailable()) return skipUnlessBrowser();
    TemporaryFolder folder;
    CompressOptions options;
    options.htmlReport = folder / "room.html";
    const CompressionReport report = compressFile(sample("room.glb"), folder / "room.glb", options);
    const nlohmann::json seen = lookAt(folder / "room.html", "members");
    requireViewable(seen);
    CHECK(seen["rows"] == report.stats.classes);
}

TEST_CASE("html report: the detect page in headless Chromium shows every element", "[html][interop]") {
    if (!browserAvailable()) return skipUnlessBrowser();
    TemporaryFolder folder;
    const fs::path page = folder / "detect.html";
    const nlohmann::json group = runJson(std::string(SYMCOMPRESS_CLI) + " detect " + quoted(sample("icosahedral.glb")) +
                                         " --json --html " + quoted(page));
    const nlohmann::json seen = lookAt(page, "");
    requireViewable(seen);
    CHECK(seen["rows"] == group["symmetries"].size());  // every element but the identity
    const std::string html = readTextFile(page);
    CHECK(html.find(group["group"].get<std::string>()) != std::string::npos);
}

TEST_CASE("html report: a big shape is embedded as a preview within the triangle budget", "[html]") {
    if (!htmlReportAvailable()) return;
    // A fine sphere: many more triangles than the budget.
    TriangleMesh sphere;
    const int rings = 300, segments = 600;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double theta = 3.14159265358979 * i / rings, phi = 2 * 3.14159265358979 * j / segments;
            sphere.positions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                          std::cos(theta));
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const auto at = [&](int r, int s) { return std::uint32_t(r * segments + (s % segments)); };
            sphere.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            sphere.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    PreviewSource source;
    source.pieces.push_back({&sphere.positions, &sphere.triangles, kNoClass});
    const std::size_t budget = 20000;
    const double cell = previewCell({source}, budget);
    REQUIRE(cell > 0);
    const PreviewGeometry preview = previewGeometry(source, cell);
    CHECK(preview.triangles() <= budget);
    CHECK(preview.triangles() > budget / 4);  // the cell is not much coarser than it needs to be
    CHECK(preview.triangles() == previewTriangles(source, cell));
    for (std::uint32_t index : preview.indices) REQUIRE(index < preview.positions.size() / 3);

    SymmetryGroup group;
    group.name = "C1";
    HtmlReportOptions options;
    options.maxTriangles = budget;
    const std::string html = detectionReportHtml(sphere, group, "sphere.glb", 1e-5, options);
    CHECK(html.find("Preview: the 360000 triangles of the stored meshes are drawn as") != std::string::npos);
    CHECK(html.size() < 2'000'000);
}

TEST_CASE("html report: base64 as the page decodes it", "[html]") {
    CHECK(base64("", 0).empty());
    CHECK(base64("f", 1) == "Zg==");
    CHECK(base64("fo", 2) == "Zm8=");
    CHECK(base64("foo", 3) == "Zm9v");
    CHECK(base64("foobar", 6) == "Zm9vYmFy");
}

TEST_CASE("html report: --help lists --html for compress and detect", "[html][cli]") {
    const CommandResult compress = runCommand(std::string(SYMCOMPRESS_CLI) + " compress --help");
    CHECK(compress.output.find("--html") != std::string::npos);
    const CommandResult detect = runCommand(std::string(SYMCOMPRESS_CLI) + " detect --help");
    CHECK(detect.output.find("--html") != std::string::npos);
}

}  // namespace
