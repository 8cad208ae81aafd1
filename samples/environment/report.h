// The outputs of vsgl_environment, written only once every figure exists, each file atomically
// (to "<file>.partial", then renamed): environment.json, environment.csv, environment.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace environment {

// One method at one sample count.
struct Row {
  std::string method;  // --methods word: fis-filtered, fis-unfiltered, fis-randomised, sg
  uint32_t count = 0;  // N, samples per pixel
  double ms = 0.0;     // median GPU time of the shading pass over the timed frames
  double msMin = 0.0, msMax = 0.0;
  // sg only: the median GPU time of generating the N lights (once per environment), else 0.
  double setupMs = 0.0;
  // Against the reference, over the evaluated sphere pixels and their three channels, of
  // diffuse + glossy: the RMS error, its ratio to the reference's mean ("relative RMS"), and
  // relMSE (engine::compareImages: mean of (t - r)^2 / (r^2 + eps)). The glossy term alone as
  // relative RMS (the part the mode changes; the SH diffuse term is the same in every row).
  double rmse = 0.0;
  double relativeRms = 0.0;
  double relativeMse = 0.0;
  double glossyRelativeRms = 0.0;
};

// What the report states besides the rows.
struct RunInfo {
  std::string device, driver;
  std::string environment;  // name or file
  std::string brdf;
  std::string scene;  // the materials
  uint32_t width = 0, height = 0, mapSize = 0, frames = 0, warmup = 0;
  double conversionMs = 0.0;  // conversion + mips + SH, once
  // The reference.
  uint32_t referencePixels = 0, spherePixels = 0, stride = 1, glossyStrata = 0, diffuseStrata = 0;
  double referenceRelativeStdError = 0.0;  // sqrt(mean se^2) / mean reference, diffuse + glossy
  double referenceGlossyRelativeStdError = 0.0;
  double referenceSeconds = 0.0;
  unsigned referenceThreads = 0;
  bool referenceCached = false;
  std::string referenceFile;
  // The picture.
  std::string picture;  // file name of the side-by-side PNG
  uint32_t pictureCount = 0;
  std::vector<std::string> pictureOrder;  // panel names top to bottom
};

// Writes dir/environment.{json,csv,md}.
void writeReport(const std::filesystem::path& dir, const RunInfo& info,
                 const std::vector<Row>& rows);

// The markdown table of error against N (one line per N, per method the relative RMS with its
// time beside it), then the ratios against fis-filtered, as printed to stdout too.
std::string errorTable(const std::vector<Row>& rows);

// Writes text to file atomically.
void writeFile(const std::filesystem::path& file, const std::string& text);

}  // namespace environment
