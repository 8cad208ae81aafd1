// The reference cache: entries come back bit for bit, any change of input misses, a damaged
// entry is reported and rendered again, and cachedPathTrace renders once.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include "analytic_scene.h"
#include "path_tracer.h"
#include "reference_cache.h"

namespace {

// An empty directory under the system's temporary one, removed with the test.
struct TempDirectory {
  std::string path;
  explicit TempDirectory(const std::string& name)
      : path((std::filesystem::temp_directory_path() / ("vsgl_cache_" + name)).string()) {
    std::filesystem::remove_all(path);
  }
  ~TempDirectory() { std::filesystem::remove_all(path); }
};

truth::CachedImage smallImage() {
  truth::CachedImage image{2, 3, 2, {}, {4.5, -1.0}};
  for (int i = 0; i < 12; ++i) image.values.push_back(0.1 * i - 0.35);
  return image;
}

// Tests run in parallel ask for the same reference: the second waits for the first's entry
// rather than tracing it again. A second holder of the same entry's lock blocks until the first
// lets go (flock, which holds between two opens in one process as between processes).
TEST(ReferenceCache, EntryLockMakesASecondHolderWait) {
  const TempDirectory dir("lock");
  const truth::ReferenceCache cache(dir.path);
  truth::CacheKey key;
  key.add(7);
  std::atomic<int> stage{0};  // 1: the first let go; 2: the second got it after that
  std::optional<truth::ReferenceCache::EntryLock> first;
  first.emplace(cache, "test", key);
  std::thread second([&] {
    const truth::ReferenceCache::EntryLock lock(cache, "test", key);
    stage = stage == 1 ? 2 : -1;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(stage, 0) << "the second holder did not wait";
  stage = 1;
  first.reset();
  second.join();
  EXPECT_EQ(stage, 2);
}

TEST(ReferenceCache, StoredEntryComesBackBitForBit) {
  const TempDirectory dir("roundtrip");
  const truth::ReferenceCache cache(dir.path);
  truth::CacheKey key;
  key.add(42).add(std::string("settings"));
  EXPECT_FALSE(cache.load("test", key));
  const truth::CachedImage image = smallImage();
  cache.store("test", key, image);
  const std::optional<truth::CachedImage> back = cache.load("test", key);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->width, image.width);
  EXPECT_EQ(back->height, image.height);
  EXPECT_EQ(back->channels, image.channels);
  EXPECT_EQ(back->values, image.values);
  EXPECT_EQ(back->scalars, image.scalars);
}

TEST(ReferenceCache, KeyChangesWithEveryInput) {
  const truth::AnalyticSceneParams params;
  engine::Scene scene = truth::makeAnalyticScene(params);
  const engine::View view = engine::cameraView(scene.cameras.front(), 8, 6);
  const uint64_t base = truth::CacheKey().add(scene).add(view).value();
  scene.lights[0].intensity *= 1.0001f;
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), base);
  scene = truth::makeAnalyticScene(params);
  scene.materials[0].roughnessFactor = 0.5f;
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), base);
  scene = truth::makeAnalyticScene(params);
  scene.materials[0].specularFactor = 0.5f;
  const uint64_t specular = truth::CacheKey().add(scene).add(view).value();
  EXPECT_NE(specular, base);
  scene.materials[0].specularColorFactor.g = 0.5f;
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), specular);
  scene = truth::makeAnalyticScene(params);
  scene.materials[0].emissiveFactor.r = 0.5f;  // the direct term carries emission
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), base);
  scene = truth::makeAnalyticScene(params);
  scene.textures.push_back(scene.textures.empty() ? engine::Texture{"n", 1, 1, {128, 128, 255, 255}}
                                                  : scene.textures.front());
  const uint64_t texture = truth::CacheKey().add(scene).add(view).value();
  scene.materials[0].normalTexture = static_cast<int>(scene.textures.size()) - 1;
  const uint64_t normal = truth::CacheKey().add(scene).add(view).value();
  EXPECT_NE(normal, texture);
  scene.materials[0].normalScale = 0.5f;
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), normal);
  scene = truth::makeAnalyticScene(params);
  scene.materials[0].alphaCutoff = 0.5f;  // cut-outs change what the rays meet
  EXPECT_NE(truth::CacheKey().add(scene).add(view).value(), base);
  scene = truth::makeAnalyticScene(params);
  EXPECT_EQ(truth::CacheKey().add(scene).add(view).value(), base);
  const engine::View wider = engine::cameraView(scene.cameras.front(), 9, 6);
  EXPECT_NE(truth::CacheKey().add(scene).add(wider).value(), base);
}

TEST(ReferenceCache, DamagedEntryIsRenderedAgain) {
  const TempDirectory dir("damaged");
  const truth::ReferenceCache cache(dir.path);
  truth::CacheKey key;
  key.add(7);
  cache.store("test", key, smallImage());
  std::filesystem::resize_file(cache.path("test", key), 40);  // truncated
  EXPECT_FALSE(cache.load("test", key));
  std::ofstream(cache.path("test", key), std::ios::binary | std::ios::trunc) << "not a reference";
  EXPECT_FALSE(cache.load("test", key));
}

TEST(ReferenceCache, PathTraceRendersOnceThenReads) {
  const TempDirectory dir("pathtrace");
  const truth::ReferenceCache cache(dir.path);
  const truth::AnalyticSceneParams params;
  const engine::Scene scene = truth::makeAnalyticScene(params);
  const engine::View view = engine::cameraView(scene.cameras.front(), 10, 6);
  truth::PathTraceSettings settings;
  settings.relativeError = 0.1;
  settings.minSamples = 32;
  settings.maxSamples = 256;
  bool fromCache = true;
  const truth::PathTraceImage first =
      truth::cachedPathTrace(cache, scene, view, 0, settings, &fromCache);
  EXPECT_FALSE(fromCache);
  const truth::PathTraceImage second =
      truth::cachedPathTrace(cache, scene, view, 0, settings, &fromCache);
  EXPECT_TRUE(fromCache);
  EXPECT_EQ(second.direct, first.direct);
  EXPECT_EQ(second.diffuse, first.diffuse);
  EXPECT_EQ(second.glossy, first.glossy);
  EXPECT_EQ(second.standardError, first.standardError);
  EXPECT_EQ(second.samples, first.samples);
  settings.seed = 2;  // another input: rendered again
  truth::cachedPathTrace(cache, scene, view, 0, settings, &fromCache);
  EXPECT_FALSE(fromCache);
}

}  // namespace
