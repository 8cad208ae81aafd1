// benchmark.md: a run's results as the Markdown tables of docs/benchmarks.md, so that the page
// is pasted from a run rather than typed. Per scene: every row (time beside error), the Pareto
// front, and the passes of each method at the largest VSGL count, laid out like [S3] Table 1;
// then the targets.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace bench {

// `targets` and `fronts` as benchmark.json holds them.
std::string markdownTables(const nlohmann::json& machine, const nlohmann::json& targets,
                           const nlohmann::json& fronts, const nlohmann::json& rows);

}  // namespace bench
