// What vsgl_benchmark writes once every row is in (docs/benchmarks.md): benchmark.json with
// the machine, the targets, each scene's Pareto front and the rows; benchmark.csv (one
// line per row), benchmark_passes.csv (one line per row and pass) and benchmark.md (the tables
// of docs/benchmarks.md); and the targets and fronts printed.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace bench {

// Whether a method is one of the k-means baselines, which have no K.
bool isKmeans(const std::string& method);
// Whether a method reads K (the filtered ones; not k-means, not the VPL baseline).
bool hasKernelScale(const std::string& method);
// The median time of pass `name` in a row (0 when it has none).
double passMedian(const nlohmann::json& row, const std::string& name);
// The VSGL stage of a row: filtered sampling (VPL sampling for the VPL baseline), or every
// k-means pass.
double generationMs(const nlohmann::json& row);
// The shading pass: VSGL shading, or the VPL baseline's.
double shadingMs(const nlohmann::json& row);
// Every pass that turns the RSM into VSGLs, [S3] Table 1's lower half: the attributes, their
// pyramids and the PDF's, and filtered sampling; or the attributes and every k-means pass.
// k-means reads only the pyramids' level 0 (and the PDF pyramid only to seed), so the
// mipmapping this pipeline still runs for it is not charged to it.
double rsmGenerationMs(const nlohmann::json& row);
// The rows of `scene` that no other row beats on both the module's frame time and relMSE,
// fastest first (the CPU's VPL gather rows left out): which setting to pick for a time or an
// error budget.
nlohmann::json paretoFront(const nlohmann::json& rows, const std::string& scene);
// Writes `text` to `file` whole or not at all (through a temporary name), so an interrupted or
// failed write leaves the previous file as it was.
void writeFile(const std::filesystem::path& file, const std::string& text);
void writeReport(const std::filesystem::path& dir, const nlohmann::json& machine,
                 const nlohmann::json& rows);

}  // namespace bench
