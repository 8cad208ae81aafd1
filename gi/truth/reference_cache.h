// Ground-truth images stored on disk under a key of everything that determines them (scene
// content, camera, light, settings, format version), so benchmarks and flicker captures reuse a
// reference instead of re-rendering it. One file per entry, "<dir>/<kind>-<16 hex digits>.bin":
// a header (magic, version, key, size, channel count) and the channels as doubles. Entries are
// written to a temporary name and renamed, so a crash never leaves a half entry under a key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene.h"
#include "engine/view.h"

namespace truth {

// FNV-1a over bytes, 64-bit (Fowler, Noll and Vo): the key only has to separate settings,
// not resist an adversary.
class CacheKey {
 public:
  CacheKey& add(const void* data, size_t bytes);
  template <class T>
  CacheKey& add(const T& value) {
    return add(&value, sizeof(T));
  }
  template <class T>
  CacheKey& addVector(const std::vector<T>& values) {
    add(values.size());
    return add(values.data(), values.size() * sizeof(T));
  }
  CacheKey& add(const std::string& text);
  CacheKey& add(const engine::TextureTransform& t);  // offset, rotation, scale
  CacheKey& add(const engine::Scene& scene);         // geometry, materials, textures, lights
  CacheKey& add(const engine::View& view);
  uint64_t value() const { return hash_; }
  std::string hex() const;

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

// width x height pixels of `channels` doubles each, channel-major (all of channel 0, then 1...),
// and a few scalars about the whole image (e.g. render time).
struct CachedImage {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t channels = 0;
  std::vector<double> values;
  std::vector<double> scalars;
};

class ReferenceCache {
 public:
  // Creates `directory` if needed; throws engine::Error naming it when it cannot.
  explicit ReferenceCache(std::string directory);
  std::string path(const std::string& kind, const CacheKey& key) const;
  // The entry, or nothing when absent. An entry whose header does not match its name (another
  // version, a truncated file) is reported on stderr, naming the file, and treated as absent.
  std::optional<CachedImage> load(const std::string& kind, const CacheKey& key) const;
  // Throws engine::Error naming the file when it cannot be written.
  void store(const std::string& kind, const CacheKey& key, const CachedImage& image) const;

  // An exclusive hold on one entry across processes (flock on "<entry>.lock"), for the span
  // of a load, a computation and a store: a second process that asks for the same reference
  // (tests run in parallel) waits and then loads it instead of tracing it again. Released when
  // destroyed; without a lock file (a read-only directory) it holds nothing and only costs
  // the duplicate work.
  class EntryLock {
   public:
    EntryLock(const ReferenceCache& cache, const std::string& kind, const CacheKey& key);
    ~EntryLock();
    EntryLock(const EntryLock&) = delete;
    EntryLock& operator=(const EntryLock&) = delete;

   private:
    int fd_ = -1;
  };

 private:
  std::string directory_;
};

}  // namespace truth
