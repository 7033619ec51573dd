// The HTML report (symcompress --html, symcompress detect --html): one self-contained page, viewable
// offline, that shows what the job found. For a compression: the scene with every tile coloured by its
// class and by how it is stored, a sortable table of the classes (clicking one highlights its members and
// draws its prototype's mirror planes and rotation axes), the scene's own symmetry group, and the size
// report as charts. For detect: the shape with its planes and axes and the table of elements. The viewer
// (three.js with OrbitControls, bundled when symcompress is built) is inlined into the page, and the
// geometry is embedded: stored meshes with a matrix per copy, never a copy of every triangle, and at most
// HtmlReportOptions::maxTriangles of them (a vertex-clustered preview beyond that, which the page says).
#pragma once

#include "symcompress/compress.hpp"
#include "symcompress/scene.hpp"
#include "symcompress/symmetry.hpp"

#include <cstddef>
#include <filesystem>
#include <string>

namespace symcompress {

struct SceneAnalysis;
struct CompressionPlan;
struct StorageCostModel;

struct HtmlReportOptions {
    std::size_t maxTriangles = 200000;  // embedded in the page; beyond that a preview with fewer
    std::size_t maxTableRows = 5000;    // classes listed (the largest first); the page says when more exist
};

// What a compression's page shows, as the job has it after choosing the plan it kept.
struct CompressionPicture {
    const Scene& input;
    const SceneAnalysis& analysis;
    const CompressionPlan& plan;  // the plan whose file is the output
    const CompressionReport& report;
    // The output's cost model, to measure each shared mesh as written; null: the bytes are left unknown.
    const StorageCostModel* costs = nullptr;
};

// False when symcompress was built without Node.js and npm (no viewer to inline): the functions below
// then throw std::runtime_error.
bool htmlReportAvailable();

std::string compressionReportHtml(const CompressionPicture& picture, const HtmlReportOptions& options = {});

// `mesh` with the group detectSymmetries found on it; `input` and `tolerance` are shown as given.
std::string detectionReportHtml(const TriangleMesh& mesh, const SymmetryGroup& group,
                                const std::filesystem::path& input, double tolerance,
                                const HtmlReportOptions& options = {});

// detectionReportHtml written atomically to `file` (FileError when it cannot be written).
void writeDetectionReport(const std::filesystem::path& file, const TriangleMesh& mesh, const SymmetryGroup& group,
                          const std::filesystem::path& input, double tolerance, const HtmlReportOptions& options = {});

}  // namespace symcompress
