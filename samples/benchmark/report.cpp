#include "report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>
#include <vector>

#include "engine/error.h"
#include "markdown_tables.h"

namespace bench {

using nlohmann::json;

bool isKmeans(const std::string& method) {
  return method.rfind("kmeans", 0) == 0;
}

bool hasKernelScale(const std::string& method) {
  return !isKmeans(method) && method != "vpl";
}

double passMedian(const json& row, const std::string& name) {
  for (const json& pass : row["passes"])
    if (pass["name"] == name) return pass["median_ms"];
  return 0.0;
}

// The VSGL stage: filtered sampling (VPL sampling for the VPL baseline), or every k-means pass.
double generationMs(const json& row) {
  double ms = passMedian(row, "filtered sampling") + passMedian(row, "vpl sampling");
  for (const json& pass : row["passes"])
    if (pass["name"].get<std::string>().rfind("k-means", 0) == 0)
      ms += pass["median_ms"].get<double>();
  return ms;
}

double shadingMs(const json& row) {
  return passMedian(row, "vsgl shading") + passMedian(row, "vpl shading");
}

double rsmGenerationMs(const json& row) {
  double ms = generationMs(row) + passMedian(row, "vsgl attributes");
  if (!isKmeans(row["method"]))
    ms += passMedian(row, "attribute mipmapping") + passMedian(row, "brsm pdf mipmapping");
  return ms;
}

json paretoFront(const json& rows, const std::string& scene) {
  std::vector<const json*> candidates;
  for (const json& r : rows)
    if (r["scene"] == scene && r["method"] != "vpl-gather") candidates.push_back(&r);
  auto relMse = [](const json* r) { return (*r)["error"]["relative_mse"].get<double>(); };
  std::sort(candidates.begin(), candidates.end(), [&](const json* a, const json* b) {
    const double fa = passMedian(*a, "frame"), fb = passMedian(*b, "frame");
    return fa != fb ? fa < fb : relMse(a) < relMse(b);
  });
  json front = json::array();
  double best = std::numeric_limits<double>::infinity();
  for (const json* r : candidates)
    if (relMse(r) < best) {
      best = relMse(r);
      front.push_back({{"method", (*r)["method"]},
                       {"count", (*r)["count"]},
                       {"k", (*r)["k"]},
                       {"frame_ms", passMedian(*r, "frame")},
                       {"relative_mse", best}});
    }
  return front;
}

namespace {

// The targets per scene and VSGL count, from the K = 1 rows: modified FIS against the
// faster k-means variant (generation time and relMSE) and against Tok15 (generation overhead),
// and the shading cost per pixel-VSGL pair, also as FMAs at the measured peak.
json targets(const json& machine, const json& rows) {
  auto find = [&](const std::string& scene, const std::string& method,
                  uint32_t count) -> const json* {
    for (const json& r : rows)
      if (r["scene"] == scene && r["method"] == method && r["count"] == count && r["k"] == 1.0)
        return &r;
    return nullptr;
  };
  json out = json::array();
  for (const json& r : rows) {
    if (r["method"] != "modified" || r["k"] != 1.0) continue;
    const std::string scene = r["scene"];
    const uint32_t n = r["count"];
    json t = {{"scene", scene}, {"count", n}};
    const double modified = generationMs(r);
    const double pixels = double(r["width"].get<uint32_t>()) * double(r["height"].get<uint32_t>());
    // The cost of a pixel-VSGL pair from the row that shades every pixel, when there is one.
    const json* full = find(scene, "modified-full", n);
    const double nsPerPair = passMedian(full ? *full : r, "vsgl shading") * 1e6 / (n * pixels);
    t["shading_ns_per_pair"] = nsPerPair;
    t["shading_peak_fmas_per_pair"] = nsPerPair * machine["fma_peak_gflops"].get<double>() / 2.0;
    if (full && passMedian(r, "frame") > 0.0 && passMedian(r, "vsgl shading") > 0.0) {
      const json& c = r["shading_counts"];
      uint32_t shaded = 0;
      for (const json& level : c["shaded"]) shaded += level.get<uint32_t>();
      const double surface = pixels - c["sky_pixels"].get<double>();
      json from = json::array();
      for (const json& level : c["pixels_from"]) from.push_back(level.get<double>() / surface);
      t["full_frame_ms"] = passMedian(*full, "frame");
      t["adaptive_frame_ms"] = passMedian(r, "frame");
      t["adaptive_frame_speedup"] = passMedian(*full, "frame") / passMedian(r, "frame");
      t["adaptive_shading_speedup"] =
          passMedian(*full, "vsgl shading") / passMedian(r, "vsgl shading");
      t["full_relative_mse"] = (*full)["error"]["relative_mse"];
      t["adaptive_relative_mse"] = r["error"]["relative_mse"];
      t["adaptive_relative_mse_rise"] = r["error"]["relative_mse"].get<double>() /
                                            (*full)["error"]["relative_mse"].get<double>() -
                                        1.0;
      t["shaded_fraction"] = shaded / surface;
      t["light_from_level"] = from;
      if (r.contains("error_against_full_shading"))
        t["adaptive_relative_mse_against_full"] = r["error_against_full_shading"];
    }
    // VSGL culling over the same shading, adaptive and at full rate, when their rows are here.
    const std::tuple<const json*, const char*, std::string> cullings[] = {
        {&r, "modified-culled", "culling"}, {full, "modified-full-culled", "full_culling"}};
    for (const auto& [base, name, key] : cullings) {
      const json* culled = find(scene, name, n);
      if (!base || !culled || passMedian(*culled, "frame") <= 0.0) continue;
      const json& c = (*culled)["shading_counts"];
      double tests = 0.0, skipped = 0.0;
      for (const json& level : c["vsgl_tests"]) tests += level.get<double>();
      for (const json& level : c["vsgls_skipped"]) skipped += level.get<double>();
      t[key + "_frame_ms"] = passMedian(*culled, "frame");
      t[key + "_frame_speedup"] = passMedian(*base, "frame") / passMedian(*culled, "frame");
      t[key + "_shading_speedup"] =
          passMedian(*base, "vsgl shading") / passMedian(*culled, "vsgl shading");
      t[key + "_skipped_fraction"] = tests > 0.0 ? skipped / tests : 0.0;
      t[key + "_relative_mse_rise"] = (*culled)["error"]["relative_mse"].get<double>() /
                                          (*base)["error"]["relative_mse"].get<double>() -
                                      1.0;
      if (culled->contains("error_against_unculled"))
        t[key + "_relative_mse_against_unculled"] = (*culled)["error_against_unculled"];
    }
    // Planar emitters against the SG emitter, both at full rate (the same pixel-VSGL pairs).
    if (const json* sg = find(scene, "modified-full-sg-emitter", n);
        full && sg && passMedian(*sg, "vsgl shading") > 0.0) {
      t["planar_shading_cost"] =
          passMedian(*full, "vsgl shading") / passMedian(*sg, "vsgl shading");
      t["planar_relative_mse"] = (*full)["error"]["relative_mse"];
      t["sg_emitter_relative_mse"] = (*sg)["error"]["relative_mse"];
    }
    // The VPL baseline at the same N: its error, frame, and its cost per pixel-VPL pair (every
    // pixel shaded) beside the VSGLs' at full rate.
    if (const json* vpl = find(scene, "vpl", n); vpl && passMedian(*vpl, "frame") > 0.0) {
      t["vpl_relative_mse"] = (*vpl)["error"]["relative_mse"];
      t["vpl_frame_ms"] = passMedian(*vpl, "frame");
      t["vpl_shading_ns_per_pair"] = passMedian(*vpl, "vpl shading") * 1e6 / (n * pixels);
    }
    if (const json* tok15 = find(scene, "tok15", n); tok15 && generationMs(*tok15) > 0.0)
      t["modified_over_tok15_generation"] = modified / generationMs(*tok15);
    const json* best = nullptr;
    for (const char* m : {"kmeans-2d", "kmeans-3d"})
      if (const json* k = find(scene, m, n); k && (!best || generationMs(*k) < generationMs(*best)))
        best = k;
    if (best && modified > 0.0) {
      t["faster_kmeans"] = (*best)["method"];
      t["kmeans_over_modified_generation"] = generationMs(*best) / modified;
      t["kmeans_over_modified_rsm_generation"] = rsmGenerationMs(*best) / rsmGenerationMs(r);
      t["kmeans_over_modified_frame"] = passMedian(*best, "frame") / passMedian(r, "frame");
      t["modified_relative_mse"] = r["error"]["relative_mse"];
      t["kmeans_relative_mse"] = (*best)["error"]["relative_mse"];
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace

void writeFile(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path partial = file.string() + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    if (!out.flush()) throw engine::Error(partial.string() + ": cannot write");
  }
  std::filesystem::rename(partial, file);
}

void writeReport(const std::filesystem::path& dir, const json& machine, const json& rows) {
  const json summary = targets(machine, rows);
  json fronts = json::object();
  for (const json& r : rows)
    if (!fronts.contains(r["scene"].get<std::string>()))
      fronts[r["scene"].get<std::string>()] = paretoFront(rows, r["scene"]);
  for (const json& t : summary)
    if (t.contains("kmeans_over_modified_generation"))
      std::printf(
          "%s N=%u: %s / modified FIS generation %.1fx (frame %.2fx), relMSE %.4f vs %.4f; "
          "modified / Tok15 generation %.2f; shading %.0f ns per pair (%.0f FMAs at peak)\n",
          t["scene"].get<std::string>().c_str(), t["count"].get<uint32_t>(),
          t["faster_kmeans"].get<std::string>().c_str(),
          t["kmeans_over_modified_generation"].get<double>(),
          t["kmeans_over_modified_frame"].get<double>(), t["kmeans_relative_mse"].get<double>(),
          t["modified_relative_mse"].get<double>(), t.value("modified_over_tok15_generation", 0.0),
          t["shading_ns_per_pair"].get<double>(), t["shading_peak_fmas_per_pair"].get<double>());
  for (const json& t : summary)
    if (t.contains("adaptive_frame_speedup"))
      std::printf(
          "%s N=%u: adaptive shading %.2fx faster frame (shading %.2fx), %.1f %% of the surface "
          "pixels shaded; relMSE %.5f -> %.5f (%+.1f %%)\n",
          t["scene"].get<std::string>().c_str(), t["count"].get<uint32_t>(),
          t["adaptive_frame_speedup"].get<double>(), t["adaptive_shading_speedup"].get<double>(),
          100.0 * t["shaded_fraction"].get<double>(), t["full_relative_mse"].get<double>(),
          t["adaptive_relative_mse"].get<double>(),
          100.0 * t["adaptive_relative_mse_rise"].get<double>());
  for (const auto& [scene, front] : fronts.items()) {
    std::printf("%s Pareto front (frame ms, relMSE):", scene.c_str());
    for (const json& f : front)
      std::printf(" %s N=%u K=%g (%.0f, %.4f)", f["method"].get<std::string>().c_str(),
                  f["count"].get<uint32_t>(), f["k"].get<double>(), f["frame_ms"].get<double>(),
                  f["relative_mse"].get<double>());
    std::printf("\n");
  }
  writeFile(
      dir / "benchmark.json",
      json{{"machine", machine}, {"targets", summary}, {"pareto", fronts}, {"rows", rows}}.dump(2) +
          "\n");
  std::ostringstream csv;
  csv << "scene,method,count,k,frame_median_ms,frame_p5_ms,frame_p95_ms,generation_ms,"
         "shading_ms,rmse_of_mean,relative_mse,psnr_db,peak_resident_mb,rsm_generation_ms\n";
  for (const json& r : rows) {
    double p5 = 0.0, p95 = 0.0;
    for (const json& pass : r["passes"])
      if (pass["name"] == "frame") {
        p5 = pass["p5_ms"];
        p95 = pass["p95_ms"];
      }
    csv << r["scene"].get<std::string>() << "," << r["method"].get<std::string>() << ","
        << r["count"] << "," << r["k"] << "," << passMedian(r, "frame") << "," << p5 << "," << p95
        << "," << generationMs(r) << "," << shadingMs(r) << "," << r["error"]["rmse_of_mean"] << ","
        << r["error"]["relative_mse"] << "," << r["error"]["psnr_db"] << ","
        << r["peak_resident_mb"] << "," << rsmGenerationMs(r) << "\n";
  }
  writeFile(dir / "benchmark.csv", csv.str());
  // Long format, one line per row and pass (the frame total left out): the stacked bars' input.
  std::ostringstream passes;
  passes << "scene,method,count,k,pass,median_ms,p5_ms,p95_ms,dispatches\n";
  for (const json& r : rows)
    for (const json& pass : r["passes"])
      if (pass["name"] != "frame")
        passes << r["scene"].get<std::string>() << "," << r["method"].get<std::string>() << ","
               << r["count"] << "," << r["k"] << "," << pass["name"].get<std::string>() << ","
               << pass["median_ms"] << "," << pass["p5_ms"] << "," << pass["p95_ms"] << ","
               << pass["dispatches"] << "\n";
  writeFile(dir / "benchmark_passes.csv", passes.str());
  writeFile(dir / "benchmark.md", markdownTables(machine, summary, fronts, rows));
}

}  // namespace bench
