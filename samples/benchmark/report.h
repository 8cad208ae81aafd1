// What vsgl_benchmark writes once every row is in (docs/benchmarks.md): benchmark.json with
// the machine, the targets and the rows; benchmark.csv (one line per row) and
// benchmark_passes.csv (one line per row and pass); and the targets printed.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace bench {

// The median time of pass `name` in a row (0 when it has none).
double passMedian(const nlohmann::json& row, const std::string& name);
// The VSGL stage of a row: filtered sampling, or every k-means pass.
double generationMs(const nlohmann::json& row);
void writeReport(const std::filesystem::path& dir, const nlohmann::json& machine,
                 const nlohmann::json& rows);

}  // namespace bench
