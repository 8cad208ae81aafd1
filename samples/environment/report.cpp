#include "report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "engine/error.h"

namespace environment {
namespace {

using nlohmann::json;

std::string format(const char* fmt, double a) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), fmt, a);
  return buffer;
}

// Methods in the order of the rows, and counts ascending.
std::vector<std::string> methodsOf(const std::vector<Row>& rows) {
  std::vector<std::string> out;
  for (const Row& r : rows)
    if (std::find(out.begin(), out.end(), r.method) == out.end()) out.push_back(r.method);
  return out;
}

std::vector<uint32_t> countsOf(const std::vector<Row>& rows) {
  std::vector<uint32_t> out;
  for (const Row& r : rows) out.push_back(r.count);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const Row* find(const std::vector<Row>& rows, const std::string& method, uint32_t count) {
  for (const Row& r : rows)
    if (r.method == method && r.count == count) return &r;
  return nullptr;
}

}  // namespace

void writeFile(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path partial = file.string() + ".partial";
  {
    std::ofstream out(partial);
    out << text;
    if (!out.flush()) {
      std::error_code ec;
      std::filesystem::remove(partial, ec);
      throw engine::Error(partial.string() + ": cannot write");
    }
  }
  std::filesystem::rename(partial, file);
}

std::string errorTable(const std::vector<Row>& rows) {
  const std::vector<std::string> methods = methodsOf(rows);
  const std::vector<uint32_t> counts = countsOf(rows);
  std::string md = "| N |";
  std::string rule = "|---:|";
  for (const std::string& m : methods) {
    md += " " + m + " rel. RMS | ms |";
    rule += "---:|---:|";
  }
  md += "\n" + rule + "\n";
  for (uint32_t n : counts) {
    md += "| " + std::to_string(n) + " |";
    for (const std::string& m : methods) {
      const Row* r = find(rows, m, n);
      md += r ? format(" %.4f |", r->relativeRms) + format(" %.3f |", r->ms) : " - | - |";
    }
    md += "\n";
  }
  // Ratios against the filtered mode, where it was run.
  const bool filtered = std::find(methods.begin(), methods.end(), "fis-filtered") != methods.end();
  if (!filtered || methods.size() < 2) return md;
  md +=
      "\nRatios against fis-filtered (error ratio / time ratio; > 1: fis-filtered is better / "
      "faster):\n\n| N |";
  rule = "|---:|";
  for (const std::string& m : methods) {
    if (m == "fis-filtered") continue;
    md += " " + m + " / filtered error | time |";
    rule += "---:|---:|";
  }
  md += "\n" + rule + "\n";
  for (uint32_t n : counts) {
    const Row* f = find(rows, "fis-filtered", n);
    md += "| " + std::to_string(n) + " |";
    for (const std::string& m : methods) {
      if (m == "fis-filtered") continue;
      const Row* r = find(rows, m, n);
      if (r && f && f->relativeRms > 0.0 && f->ms > 0.0)
        md += format(" %.2f |", r->relativeRms / f->relativeRms) + format(" %.2f |", r->ms / f->ms);
      else
        md += " - | - |";
    }
    md += "\n";
  }
  return md;
}

void writeReport(const std::filesystem::path& dir, const RunInfo& info,
                 const std::vector<Row>& rows) {
  json j;
  j["program"] = "vsgl_environment";
  j["device"] = info.device;
  j["driver"] = info.driver;
  j["environment"] = info.environment;
  j["brdf"] = info.brdf;
  j["scene"] = info.scene;
  j["width"] = info.width;
  j["height"] = info.height;
  j["map_size"] = info.mapSize;
  j["frames"] = info.frames;
  j["warmup"] = info.warmup;
  j["conversion_ms"] = info.conversionMs;
  j["reference"] = {{"sphere_pixels", info.spherePixels},
                    {"pixels", info.referencePixels},
                    {"stride", info.stride},
                    {"glossy_strata", info.glossyStrata},
                    {"diffuse_strata", info.diffuseStrata},
                    {"relative_std_error", info.referenceRelativeStdError},
                    {"glossy_relative_std_error", info.referenceGlossyRelativeStdError},
                    {"seconds", info.referenceSeconds},
                    {"threads", info.referenceThreads},
                    {"cached", info.referenceCached},
                    {"file", info.referenceFile}};
  j["picture"] = {
      {"file", info.picture}, {"count", info.pictureCount}, {"panels", info.pictureOrder}};
  json out = json::array();
  std::string csv =
      "method,count,ms,ms_min,ms_max,rmse,relative_rms,relative_mse,glossy_relative_rms,setup_ms\n";
  for (const Row& r : rows) {
    out.push_back({{"method", r.method},
                   {"count", r.count},
                   {"ms", r.ms},
                   {"ms_min", r.msMin},
                   {"ms_max", r.msMax},
                   {"rmse", r.rmse},
                   {"rms", r.relativeRms},
                   {"relative_mse", r.relativeMse},
                   {"glossy_rms", r.glossyRelativeRms},
                   {"setup_ms", r.setupMs}});
    char line[256];
    std::snprintf(line, sizeof(line), "%s,%u,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                  r.method.c_str(), r.count, r.ms, r.msMin, r.msMax, r.rmse, r.relativeRms,
                  r.relativeMse, r.glossyRelativeRms, r.setupMs);
    csv += line;
  }
  j["rows"] = out;

  std::string md = "# vsgl_environment: environment FIS, error against samples\n\n";
  md += "Spheres (" + info.scene + ") lit by `" + info.environment + "`, BRDF " + info.brdf + ", " +
        std::to_string(info.width) + "x" + std::to_string(info.height) + ", map " +
        std::to_string(info.mapSize) + "^2 per layer, on " + info.device + " (" + info.driver +
        ").\n\n";
  md +=
      "Error: relative RMS of diffuse + glossy (RMS over the evaluated sphere pixels and "
      "channels / mean of the reference there); background pixels are ignored. Time: median "
      "GPU time of the shading pass (FIS, or the SG lights' shading; their generation in the "
      "JSON's setup_ms) over " +
      std::to_string(info.frames) + " frames after " + std::to_string(info.warmup) +
      " warm-up frames. Conversion, mips and SH (once per environment; timed warm): " +
      format("%.3f ms.\n\n", info.conversionMs);
  md += errorTable(rows);
  md +=
      "\nrelMSE and the glossy term alone (relative RMS):\n\n| method | N | relMSE | glossy "
      "rel. RMS |\n|---|---:|---:|---:|\n";
  for (const Row& r : rows)
    md += "| " + r.method + " | " + std::to_string(r.count) + " |" +
          format(" %.5f |", r.relativeMse) + format(" %.4f |\n", r.glossyRelativeRms);
  md += "\nReference: gi::envMonteCarloReference against the source equirect image (bilinear), " +
        std::to_string(info.glossyStrata) + "^2 glossy and " + std::to_string(info.diffuseStrata) +
        "^2 diffuse stratified samples per pixel, " + std::to_string(info.referencePixels) +
        " of " + std::to_string(info.spherePixels) + " sphere pixels";
  md += info.stride > 1 ? " (every k-th pixel in x and in y, k = " + std::to_string(info.stride) +
                              "; the errors are over those pixels; the picture's reference "
                              "panel fills the others from the nearest one)"
                        : " (every pixel)";
  md +=
      format("; its relative standard error (conservative) %.5f", info.referenceRelativeStdError) +
      format(", glossy %.5f", info.referenceGlossyRelativeStdError) + "; " +
      (info.referenceCached ? std::string("read from the cache ")
                            : format("computed in %.1f s", info.referenceSeconds) + " on " +
                                  std::to_string(info.referenceThreads) + " threads, cached in ") +
      "`" + info.referenceFile + "`.\n\n";
  md += "Picture: `" + info.picture + "`, top to bottom: ";
  for (size_t i = 0; i < info.pictureOrder.size(); ++i)
    md += (i ? ", " : "") + info.pictureOrder[i];
  md += " at N = " + std::to_string(info.pictureCount) +
        " (one exposure for all; background: the environment).\n";

  writeFile(dir / "environment.json", j.dump(2) + "\n");
  writeFile(dir / "environment.csv", csv);
  writeFile(dir / "environment.md", md);
}

}  // namespace environment
