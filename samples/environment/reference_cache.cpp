#include "reference_cache.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <thread>

#include "engine/error.h"
#include "reference/env_map_reference.h"
#include "reference/env_paraboloid.h"

namespace environment {
namespace {

// The file's first bytes; bump the digit when the layout or the estimator's use changes.
constexpr char kMagic[8] = {'V', 'S', 'G', 'L', 'E', 'R', 'F', '1'};

// FNV-1a, 64 bits, over the bytes of the reference's inputs.
class Hash {
 public:
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) value_ = (value_ ^ p[i]) * 1099511628211ull;
  }
  template <class T>
  void add(const T& v) {
    bytes(&v, sizeof(v));
  }
  uint64_t value() const { return value_; }

 private:
  uint64_t value_ = 14695981039346656037ull;
};

uint64_t inputHash(const engine::ImageRgba32f& equirect, const std::vector<ReferencePixel>& pixels,
                   const ReferenceSettings& s) {
  Hash h;
  h.bytes(kMagic, sizeof(kMagic));
  h.add(equirect.width);
  h.add(equirect.height);
  h.bytes(equirect.pixels.data(), equirect.pixels.size() * sizeof(float));
  h.add(s.glossyStrata);
  h.add(s.diffuseStrata);
  for (const ReferencePixel& p : pixels) {
    const gi::EnvFisReceiver& r = p.receiver;
    h.add(p.pixel);
    h.add(r.normal);
    h.add(r.view);
    h.add(r.albedo);
    h.add(r.f0);
    h.add(r.f90);
    h.add(r.brdf);
    h.add(r.roughness);
    h.add(r.phongExponent);
    h.add(r.wardAlphaX);
    h.add(r.wardAlphaY);
    h.add(r.tangent);
  }
  return h.value();
}

// Per pixel: diffuse, glossy, their standard errors (4 x 3 doubles).
constexpr size_t kDoublesPerPixel = 12;

bool readCache(const std::filesystem::path& file, uint64_t hash, size_t count,
               std::vector<gi::EnvReferenceShading>& out) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  char magic[sizeof(kMagic)];
  uint64_t storedHash = 0, storedCount = 0;
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&storedHash), sizeof(storedHash));
  in.read(reinterpret_cast<char*>(&storedCount), sizeof(storedCount));
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0 || storedHash != hash ||
      storedCount != count)
    return false;
  std::vector<double> values(count * kDoublesPerPixel);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(double)));
  if (!in || in.peek() != std::char_traits<char>::eof()) return false;
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const double* v = &values[i * kDoublesPerPixel];
    gi::EnvReferenceShading& s = out[i];
    s.value.diffuse = {v[0], v[1], v[2]};
    s.value.glossy = {v[3], v[4], v[5]};
    s.diffuseStdError = {v[6], v[7], v[8]};
    s.glossyStdError = {v[9], v[10], v[11]};
  }
  return true;
}

void writeCache(const std::filesystem::path& file, uint64_t hash,
                const std::vector<gi::EnvReferenceShading>& shading) {
  std::vector<double> values;
  values.reserve(shading.size() * kDoublesPerPixel);
  for (const gi::EnvReferenceShading& s : shading)
    for (const glm::dvec3& v :
         {s.value.diffuse, s.value.glossy, s.diffuseStdError, s.glossyStdError})
      values.insert(values.end(), {v.x, v.y, v.z});
  const std::filesystem::path partial =
      file.string() + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(partial, std::ios::binary);
    const uint64_t count = shading.size();
    out.write(kMagic, sizeof(kMagic));
    out.write(reinterpret_cast<const char*>(&hash), sizeof(hash));
    out.write(reinterpret_cast<const char*>(&count), sizeof(count));
    out.write(reinterpret_cast<const char*>(values.data()),
              std::streamsize(values.size() * sizeof(double)));
    if (!out.flush()) {
      std::error_code ec;
      std::filesystem::remove(partial, ec);
      throw engine::Error(partial.string() + ": cannot write");
    }
  }
  std::filesystem::rename(partial, file);
}

}  // namespace

Reference loadOrComputeReference(const std::filesystem::path& cacheDir, const std::string& stem,
                                 const engine::ImageRgba32f& equirect,
                                 const std::vector<ReferencePixel>& pixels,
                                 const ReferenceSettings& settings) {
  const uint64_t hash = inputHash(equirect, pixels, settings);
  char suffix[32];
  std::snprintf(suffix, sizeof(suffix), "_%016llx.bin", static_cast<unsigned long long>(hash));
  Reference out;
  out.file = cacheDir / (stem + suffix);
  if (readCache(out.file, hash, pixels.size(), out.shading)) {
    out.cached = true;
    return out;
  }

  // The true environment: the source image, bilinear, at the direction's (u, v).
  const gi::EnvRadianceFunction radiance = [&equirect](glm::dvec3 w) {
    return gi::equirectBilinear(equirect, gi::equirectFromDirection(w));
  };
  const auto start = std::chrono::steady_clock::now();
  out.shading.resize(pixels.size());
  const unsigned threads =
      std::max(1u, settings.threads ? settings.threads : std::thread::hardware_concurrency());
  std::atomic<size_t> next{0};
  constexpr size_t kChunk = 8;  // pixels per work item
  auto work = [&] {
    for (size_t begin; (begin = next.fetch_add(kChunk)) < pixels.size();)
      for (size_t i = begin; i < std::min(begin + kChunk, pixels.size()); ++i) {
        const glm::uvec2 p = pixels[i].pixel;
        out.shading[i] =
            gi::envMonteCarloReference(pixels[i].receiver, radiance, settings.glossyStrata,
                                       settings.diffuseStrata, 1 + uint64_t{p.y} * 65536 + p.x);
      }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeCache(out.file, hash, out.shading);
  // Earlier references of the same stem (other inputs) are stale: remove them.
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(cacheDir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.path() != out.file && name.size() == out.file.filename().string().size() &&
        name.starts_with(stem + "_") && name.ends_with(".bin"))
      std::filesystem::remove(entry.path(), ec);
  }
  return out;
}

}  // namespace environment
