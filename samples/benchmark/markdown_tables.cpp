#include "markdown_tables.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <vector>

#include "report.h"

namespace bench {

using nlohmann::json;

namespace {

std::string format(const char* pattern, ...) {
  char text[256];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(text, sizeof(text), pattern, args);
  va_end(args);
  return text;
}

// Three significant digits without an exponent: 7290, 35.2, 0.184.
std::string ms(double v) {
  if (v >= 100.0) return format("%.0f", v);
  if (v >= 10.0) return format("%.1f", v);
  if (v >= 1.0) return format("%.2f", v);
  return format("%.3f", v);
}

const json* pass(const json& row, const std::string& name) {
  for (const json& p : row["passes"])
    if (p["name"] == name) return &p;
  return nullptr;
}

bool isVplGather(const json& row) {
  return row["method"] == "vpl-gather";
}

// K, or a dash for k-means (its rows carry the preset's first K, which does not apply).
std::string kColumn(const json& row) {
  return !hasKernelScale(row["method"]) ? "—" : format("%g", row["k"].get<double>());
}

std::string rowsTable(const json& rows, const std::string& scene) {
  std::string t =
      "| method | N | K | frame ms (p5–p95) | VSGL stage ms | RSM → VSGLs ms | shading ms | "
      "relMSE | RMSE / mean | PSNR dB |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const json& r : rows) {
    if (r["scene"] != scene) continue;
    const json& f = *pass(r, "frame");
    const json& e = r["error"];
    const std::string error =
        format("%.4f | %.1f %% | %.1f |", e["relative_mse"].get<double>(),
               100.0 * e["rmse_of_mean"].get<double>(), e["psnr_db"].get<double>());
    if (isVplGather(r)) {  // its count is the RSM side, its time the CPU's wall time
      t += format("| VPL gather (CPU) | RSM %u² | — | %s (CPU wall) | — | — | — | ",
                  r["count"].get<uint32_t>(), ms(f["median_ms"]).c_str()) +
           error + "\n";
      continue;
    }
    t += format("| %s | %u | %s | %s (%s–%s) | %s | %s | %s | ",
                r["method"].get<std::string>().c_str(), r["count"].get<uint32_t>(),
                kColumn(r).c_str(), ms(f["median_ms"]).c_str(), ms(f["p5_ms"]).c_str(),
                ms(f["p95_ms"]).c_str(), ms(generationMs(r)).c_str(),
                ms(rsmGenerationMs(r)).c_str(), ms(shadingMs(r)).c_str()) +
         error + "\n";
  }
  return t;
}

std::string frontTable(const json& front) {
  std::string t = "| frame ms | relMSE | method | N | K |\n|---|---|---|---|---|\n";
  for (const json& f : front)
    t += format("| %s | %.4f | %s | %u | %s |\n", ms(f["frame_ms"]).c_str(),
                f["relative_mse"].get<double>(), f["method"].get<std::string>().c_str(),
                f["count"].get<uint32_t>(), kColumn(f).c_str());
  return t;
}

// Each method's passes at the scene's largest VSGL count and K = 1, one column per method.
std::string passesTable(const json& rows, const std::string& scene) {
  uint32_t count = 0;
  for (const json& r : rows)
    if (r["scene"] == scene && !isVplGather(r)) count = std::max(count, r["count"].get<uint32_t>());
  std::vector<const json*> columns;
  std::vector<std::string> names;
  for (const json& r : rows) {
    if (r["scene"] != scene || isVplGather(r) || r["count"] != count || r["k"] != 1.0) continue;
    columns.push_back(&r);
    for (const json& p : r["passes"])
      if (p["name"] != "frame" &&
          std::find(names.begin(), names.end(), p["name"].get<std::string>()) == names.end())
        names.push_back(p["name"]);
  }
  names.push_back("frame");
  std::string t = format("Passes at N = %u, K = 1 (median ms):\n\n| pass |", count);
  std::string rule = "|---|";
  for (const json* c : columns) {
    t.append(" ").append((*c)["method"].get<std::string>()).append(" |");
    rule += "---|";
  }
  t += "\n" + rule + "\n";
  for (const std::string& name : names) {
    t.append("| ").append(name == "frame" ? "**frame**" : name).append(" |");
    for (const json* c : columns) {
      const json* p = pass(*c, name);
      t.append(" ").append(p ? ms((*p)["median_ms"]) : std::string("—")).append(" |");
    }
    t += "\n";
  }
  return t;
}

std::string targetsTable(const json& targets) {
  std::string t =
      "| scene | N | faster k-means | k-means / modified: VSGL stage | RSM → VSGLs | frame | "
      "relMSE modified / k-means | modified / Tok15: VSGL stage | shading ns per pair | "
      "FMAs per pair at peak |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const json& g : targets) {
    if (!g.contains("kmeans_over_modified_generation")) continue;
    t += format(
        "| %s | %u | %s | %.1f× | %.1f× | %.2f× | %.4f / %.4f | %.2f | %.0f | %.0f |\n",
        g["scene"].get<std::string>().c_str(), g["count"].get<uint32_t>(),
        g["faster_kmeans"].get<std::string>().c_str(),
        g["kmeans_over_modified_generation"].get<double>(),
        g["kmeans_over_modified_rsm_generation"].get<double>(),
        g["kmeans_over_modified_frame"].get<double>(), g["modified_relative_mse"].get<double>(),
        g["kmeans_relative_mse"].get<double>(), g.value("modified_over_tok15_generation", 0.0),
        g["shading_ns_per_pair"].get<double>(), g["shading_peak_fmas_per_pair"].get<double>());
  }
  return t;
}

// Modified FIS with adaptive shading against the same VSGLs shaded at every pixel.
std::string adaptiveTable(const json& targets) {
  std::string t =
      "| scene | N | frame: full → adaptive | frame speed-up | shading speed-up | texels shaded "
      "/ surface pixels | light from L0 / L1 / L2 / L3 | relMSE: full → adaptive | relMSE "
      "adaptive against full |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const json& g : targets) {
    if (!g.contains("adaptive_frame_speedup")) continue;
    const json& from = g["light_from_level"];
    t += format(
        "| %s | %u | %.0f → %.0f ms | %.2f× | %.2f× | %.1f %% | %.0f / %.0f / %.0f / %.0f %% | "
        "%.4f → "
        "%.4f (%+.1f %%) | %s |\n",
        g["scene"].get<std::string>().c_str(), g["count"].get<uint32_t>(),
        g["full_frame_ms"].get<double>(), g["adaptive_frame_ms"].get<double>(),
        g["adaptive_frame_speedup"].get<double>(), g["adaptive_shading_speedup"].get<double>(),
        100.0 * g["shaded_fraction"].get<double>(), 100.0 * from[0].get<double>(),
        100.0 * from[1].get<double>(), 100.0 * from[2].get<double>(), 100.0 * from[3].get<double>(),
        g["full_relative_mse"].get<double>(), g["adaptive_relative_mse"].get<double>(),
        100.0 * g["adaptive_relative_mse_rise"].get<double>(),
        g.contains("adaptive_relative_mse_against_full")
            ? format("%.2g", g["adaptive_relative_mse_against_full"].get<double>()).c_str()
            : "—");
  }
  return t;
}

// VSGL culling against the same shading without it: over adaptive shading (modified-culled) and
// at full rate (modified-full-culled).
std::string cullingTable(const json& targets) {
  std::string t =
      "| scene | N | shading | frame speed-up | shading speed-up | VSGLs skipped | relMSE rise | "
      "relMSE against unculled |\n|---|---|---|---|---|---|---|---|\n";
  for (const json& g : targets)
    for (const std::string key : {"culling", "full_culling"}) {
      if (!g.contains(key + "_frame_speedup")) continue;
      t += format(
          "| %s | %u | %s | %.3f× | %.3f× | %.1f %% | %+.2f %% | %s |\n",
          g["scene"].get<std::string>().c_str(), g["count"].get<uint32_t>(),
          key == "culling" ? "adaptive" : "full rate", g[key + "_frame_speedup"].get<double>(),
          g[key + "_shading_speedup"].get<double>(),
          100.0 * g[key + "_skipped_fraction"].get<double>(),
          100.0 * g[key + "_relative_mse_rise"].get<double>(),
          g.contains(key + "_relative_mse_against_unculled")
              ? format("%.2g", g[key + "_relative_mse_against_unculled"].get<double>()).c_str()
              : "—");
    }
  return t;
}

// Planar emitters against the SG emitter, both shading every pixel.
std::string planarTable(const json& targets) {
  std::string t =
      "| scene | N | shading time: planar / SG emitter | relMSE: SG emitter → planar |\n"
      "|---|---|---|---|\n";
  for (const json& g : targets) {
    if (!g.contains("planar_shading_cost")) continue;
    t += format("| %s | %u | %.3f× | %.4f → %.4f |\n", g["scene"].get<std::string>().c_str(),
                g["count"].get<uint32_t>(), g["planar_shading_cost"].get<double>(),
                g["sg_emitter_relative_mse"].get<double>(), g["planar_relative_mse"].get<double>());
  }
  return t;
}

// The VPL baseline against modified FIS at the same N: error, frame, cost per pair.
std::string vplTable(const json& targets) {
  std::string t =
      "| scene | N | relMSE: modified / VPL | frame: modified / VPL | shading ns per pair: "
      "VSGL (full rate) / VPL |\n"
      "|---|---|---|---|---|\n";
  for (const json& g : targets) {
    if (!g.contains("vpl_relative_mse") || !g.contains("adaptive_relative_mse")) continue;
    t += format("| %s | %u | %.4f / %.4f | %s / %s ms | %.0f / %.0f |\n",
                g["scene"].get<std::string>().c_str(), g["count"].get<uint32_t>(),
                g["adaptive_relative_mse"].get<double>(), g["vpl_relative_mse"].get<double>(),
                ms(g["adaptive_frame_ms"]).c_str(), ms(g["vpl_frame_ms"]).c_str(),
                g["shading_ns_per_pair"].get<double>(), g["vpl_shading_ns_per_pair"].get<double>());
  }
  return t;
}

}  // namespace

std::string markdownTables(const json& machine, const json& targets, const json& fronts,
                           const json& rows) {
  if (rows.empty()) return "No rows.\n";
  const json& first = rows.front();
  std::string md = format(
      "Preset `%s`: %u×%u, RSM %u², %u measured frames after %u warm-up; GPU medians in ms. "
      "Error: the indirect light against the path tracer at a %.0f %% noise target.\n\n",
      first["preset"].get<std::string>().c_str(), first["width"].get<uint32_t>(),
      first["height"].get<uint32_t>(), first["rsm"].get<uint32_t>(),
      first["frames"].get<uint32_t>(), first["warmup"].get<uint32_t>(),
      100.0 * first["reference_noise"].get<double>());
  md += format(
      "Machine: %s (%s), revision `%s`; FMA peak %.1f GFLOP/s, copy bandwidth %.1f GB/s, "
      "measured in the same run.\n",
      machine["device"].get<std::string>().c_str(), machine["driver"].get<std::string>().c_str(),
      machine["revision"].get<std::string>().c_str(), machine["fma_peak_gflops"].get<double>(),
      machine["copy_bandwidth_gbs"].get<double>());
  for (const auto& [scene, front] : fronts.items()) {
    md += "\n### " + scene + "\n\n" + rowsTable(rows, scene) +
          "\nPareto front, fastest first:\n\n" + frontTable(front) + "\n" +
          passesTable(rows, scene);
  }
  md += "\n### Targets (K = 1)\n\n" + targetsTable(targets);
  md += "\n### Adaptive shading (modified FIS, K = 1)\n\n" + adaptiveTable(targets);
  md += "\n### VSGL culling (modified FIS, K = 1)\n\n" + cullingTable(targets);
  md += "\n### Planar emitters (modified FIS at full rate, K = 1)\n\n" + planarTable(targets);
  md += "\n### The VPL baseline (modified FIS, K = 1)\n\n" + vplTable(targets);
  return md;
}

}  // namespace bench
