// Imperfect shadow maps (gi/src/passes/ism.h) against their CPU twins and against ray-cast
// ground truth: the point pool, the splat, pull-push, the lookup, the visibility of a hovering
// box seen through VSGLs above and beside it, and points that follow moved vertices.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "engine/alpha_cutout.h"
#include "engine/builtin_scenes.h"
#include "engine/commands.h"
#include "engine/gbuffer_reference.h"
#include "engine/rasterizer.h"
#include "gpu_fixture.h"
#include "passes/ism.h"
#include "reference/ism_reference.h"
#include "shared/scene_data.h"

namespace {

using engine::Scene;

// Appends the parallelogram corner + s edgeU + t edgeV, cut into cells of at most `cell`.
void addRect(Scene& s, glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, float cell) {
  const int nu = std::max(1, static_cast<int>(std::ceil(glm::length(edgeU) / cell)));
  const int nv = std::max(1, static_cast<int>(std::ceil(glm::length(edgeV) / cell)));
  const glm::vec3 normal = glm::normalize(glm::cross(edgeU, edgeV));
  const auto base = static_cast<uint32_t>(s.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      s.positions.push_back(corner + float(i) / float(nu) * edgeU + float(j) / float(nv) * edgeV);
      s.normals.push_back(normal);
      s.uvs.emplace_back(0.0f);
    }
  const auto row = static_cast<uint32_t>(nu + 1);
  for (uint32_t j = 0; j < uint32_t(nv); ++j)
    for (uint32_t i = 0; i < uint32_t(nu); ++i) {
      const uint32_t a = base + j * row + i;
      s.indices.insert(s.indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
      s.triangleMaterial.insert(s.triangleMaterial.end(), 2, 0u);
    }
}

// A 6 x 6 m floor (y = 0) under a closed 1.2 x 0.4 x 1.2 m box hovering from y = 0.5 to 0.9,
// a 1 m high wall strip on the left (x = -3) and a 2 m high one at the back (z = -3), and a
// camera above the front looking down at the box: every pixel sees the floor, box or walls.
Scene occluderScene() {
  Scene s;
  s.source = "test:ism occluder";
  addRect(s, {-3.0f, 0.0f, 3.0f}, {6.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -6.0f}, 0.5f);  // floor, +Y
  const glm::vec3 lo(-0.6f, 0.5f, -0.6f), hi(0.6f, 0.9f, 0.6f);
  const glm::vec3 dx(hi.x - lo.x, 0, 0), dy(0, hi.y - lo.y, 0), dz(0, 0, hi.z - lo.z);
  addRect(s, lo + dz, dx, -dz, 0.3f);             // bottom, -Y
  addRect(s, {lo.x, hi.y, hi.z}, dx, -dz, 0.3f);  // top, +Y (cross(dx, -dz) = +Y)
  addRect(s, lo, dz, dy, 0.3f);                   // -X
  addRect(s, {hi.x, lo.y, hi.z}, -dz, dy, 0.3f);  // +X
  addRect(s, {lo.x, lo.y, hi.z}, dx, dy, 0.3f);   // +Z
  addRect(s, {hi.x, lo.y, lo.z}, -dx, dy, 0.3f);  // -Z
  addRect(s, {-3.0f, 0.0f, -3.0f}, {0, 1.0f, 0}, {0, 0, 6.0f}, 0.5f);  // left wall, +X
  addRect(s, {-3.0f, 0.0f, -3.0f}, {6.0f, 0, 0}, {0, 2.0f, 0}, 0.5f);  // back wall, +Z
  engine::Material m;
  m.baseColorFactor = glm::vec4(0.7f);
  m.roughnessFactor = 0.6f;
  m.metallicFactor = 0.0f;
  s.materials = {m};
  const glm::vec3 eye(0.0f, 2.8f, 2.0f), target(0.0f, 0.3f, -0.3f);
  const glm::vec3 forward = glm::normalize(target - eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  engine::Camera camera;
  camera.cameraToWorld =
      glm::mat4(glm::vec4(right, 0), glm::vec4(up, 0), glm::vec4(-forward, 0), glm::vec4(eye, 1));
  camera.yfov = 0.9f;
  s.cameras = {camera};
  return s;
}

gpu::VsglLobe lobe(glm::vec3 mean, glm::vec3 axis, float power) {
  gpu::VsglLobe l{};
  l.meanVariance = glm::vec4(mean, 1e-3f);
  l.axisSharpness = glm::vec4(glm::normalize(axis), 2.0f);
  l.power = glm::vec4(glm::vec3(power), power);
  return l;
}

// Hand-made VSGLs of the kinds an RSM produces: on a (virtual) ceiling facing down, slanted,
// on the wall facing +X, on the floor facing up, with both lobes, specular only, and a dark one;
// two with a visibility point beside their mean (a kernel's centre, Vsgl::visibilityPoint).
std::vector<gpu::Vsgl> testVsgls() {
  std::vector<gpu::Vsgl> v(7, gpu::Vsgl{});
  v[0].diffuse = lobe({0.2f, 1.8f, 0.1f}, {0, -1, 0}, 1.0f);
  v[1].diffuse = lobe({-1.1f, 1.6f, -0.7f}, {0.4f, -1.0f, 0.3f}, 2.0f);
  v[2].diffuse = lobe({-3.0f, 0.6f, 0.2f}, {1, 0, 0}, 1.0f);
  v[3].diffuse = lobe({1.3f, 0.0f, -1.2f}, {0, 1, 0}, 1.0f);
  v[3].specular = lobe({1.5f, 0.0f, -1.0f}, {0.3f, 1.0f, 0.0f}, 0.5f);
  v[4].specular = lobe({-0.3f, 1.3f, 1.3f}, {0.0f, -1.0f, -0.6f}, 1.0f);
  // v[5] stays dark (zero power): its map is empty and it never shadows.
  v[6].diffuse = lobe({0.9f, 1.4f, 0.9f}, {-0.5f, -1.0f, -0.4f}, 1.0f);
  v[6].specular = lobe({1.0f, 1.5f, 0.8f}, {-0.2f, -1.0f, -0.2f}, 3.0f);
  v[1].visibilityPoint = glm::vec4(-0.9f, 1.65f, -0.5f, 1.0f);
  v[6].visibilityPoint = glm::vec4(0.7f, 1.5f, 1.1f, 1.0f);
  return v;
}

std::vector<double> toReferenceAtlas(const std::vector<uint32_t>& bits) {
  std::vector<double> out(bits.size());
  for (size_t i = 0; i < bits.size(); ++i) {
    float f;
    std::memcpy(&f, &bits[i], 4);
    out[i] = bits[i] == ISM_EMPTY ? gi::kIsmEmptyReference : double(f);
  }
  return out;
}

class IsmTest : public testing_gpu::GpuTest {
 protected:
  static constexpr uint32_t kSize = 64;  // G-buffer

  void SetUp() override {
    testing_gpu::GpuTest::SetUp();
    if (IsSkipped()) return;
    scene_ = occluderScene();
    gpuScene_ = std::make_unique<engine::SceneGpu>(engine::uploadScene(ctx(), scene_));
    vsglData_ = testVsgls();
    vsgls_ = std::make_unique<engine::Buffer>(ctx(), sizeof(gpu::Vsgl) * vsglData_.size(),
                                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                              engine::MemoryUsage::GpuOnly);
    vsgls_->upload(ctx(), std::span<const gpu::Vsgl>(vsglData_));
  }

  uint32_t vsglCount() const { return static_cast<uint32_t>(vsglData_.size()); }

  // Level 0 of the atlas image as tile-major uint bits, tile k = VSGL k.
  std::vector<uint32_t> atlasBits(gi::Ism& ism) {
    const auto bytes = ism.atlas().readback(ctx(), 0);
    const uint32_t width = ism.atlas().desc().width, size = ism.settings().mapSize;
    std::vector<uint32_t> image(bytes.size() / 4), bits;
    std::memcpy(image.data(), bytes.data(), bytes.size());
    for (uint32_t k = 0; k < vsglCount(); ++k) {
      const glm::uvec2 origin = ism.tileOrigin(k);
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
          bits.push_back(image[size_t{origin.y + y} * width + origin.x + x]);
    }
    return bits;
  }

  Scene scene_;
  std::unique_ptr<engine::SceneGpu> gpuScene_;
  std::vector<gpu::Vsgl> vsglData_;
  std::unique_ptr<engine::Buffer> vsgls_;
};

// The GPU pool against the double twin. The GPU's area CDF is fp32 (sums of ~560 areas, ~1e-6
// relative), so a point whose target lies within 1e-5 of the total area of a triangle boundary
// may pick the neighbour; every other point must pick the same triangle, and barycentrics agree
// to one unorm16 step (the GPU rounds an fp32 value). Points per triangle are within one of
// P A / A_total (stratification), and a second generation is bit-identical (no atomics).
TEST_F(IsmTest, PointsMatchTheReference) {
  gi::IsmSettings settings;
  settings.pointCount = 1u << 14;
  settings.pointsPerVsgl = 1024;
  gi::Ism ism(ctx(), settings, vsglCount());
  ctx().submitAndWait([&](VkCommandBuffer cmd) { ism.recordPoints(cmd, *gpuScene_); });
  const auto gpu = ism.points().readbackAs<gpu::IsmPoint>(ctx());
  const auto ref = gi::ismPointsReference(scene_.positions, scene_.indices, settings.pointCount);
  const auto cdf = gi::ismTriangleCdfReference(scene_.positions, scene_.indices);
  const double total = cdf.back();
  ASSERT_EQ(gpu.size(), ref.size());
  size_t boundary = 0;
  std::vector<uint32_t> perTriangle(cdf.size(), 0);
  for (size_t i = 0; i < gpu.size(); ++i) {
    ASSERT_LT(gpu[i].triangle, cdf.size()) << "point " << i;
    ++perTriangle[gpu[i].triangle];
    if (gpu[i].triangle != ref[i].triangle) {
      const double target = (double(i) + 0.5) / settings.pointCount * total;
      const double lo = gpu[i].triangle > 0 ? cdf[gpu[i].triangle - 1] : 0.0;
      ASSERT_TRUE(target >= lo - 1e-5 * total && target <= cdf[gpu[i].triangle] + 1e-5 * total)
          << "point " << i << ": GPU triangle " << gpu[i].triangle << ", reference "
          << ref[i].triangle;
      ++boundary;
    }
    const double b1 = (gpu[i].bary & 0xFFFFu) / 65535.0, b2 = (gpu[i].bary >> 16) / 65535.0;
    ASSERT_NEAR(b1, ref[i].bary.x, 1.0 / 65535.0) << "point " << i;
    ASSERT_NEAR(b2, ref[i].bary.y, 1.0 / 65535.0) << "point " << i;
  }
  std::printf("%zu of %u points on a neighbouring triangle at a CDF boundary\n", boundary,
              settings.pointCount);
  EXPECT_LE(boundary, gpu.size() / 1000);
  for (size_t t = 0; t < cdf.size(); ++t) {
    const double expected = settings.pointCount * (cdf[t] - (t ? cdf[t - 1] : 0.0)) / total;
    ASSERT_NEAR(perTriangle[t], expected, 1.0 + 1e-3 * expected) << "triangle " << t;
  }
  ctx().submitAndWait([&](VkCommandBuffer cmd) { ism.recordPoints(cmd, *gpuScene_); });
  const auto again = ism.points().readbackAs<gpu::IsmPoint>(ctx());
  ASSERT_EQ(0, std::memcmp(gpu.data(), again.data(), gpu.size() * sizeof(gpu::IsmPoint)));
}

// An alpha-tested material (random alpha bytes, a texture transform): the points it cuts lie on
// no triangle, as the twin cuts them. Both test the texel under the same unorm16 barycentrics;
// the GPU interpolates the coordinates in fp32 and may quantise a barycentric one step apart,
// so a point within ~1e-4 texel of a texel edge may be decided the other way: 0.2 % of the
// points may differ (a few expected among 16 384).
TEST_F(IsmTest, CutOutPointsMatchTheReference) {
  Scene scene = scene_;
  for (size_t i = 0; i < scene.positions.size(); ++i)
    scene.uvs[i] =
        glm::vec2(scene.positions[i].x + scene.positions[i].y, scene.positions[i].z) * 0.9f;
  engine::Texture texture{"random alpha", 8, 8, {}};
  uint32_t state = 12345;
  for (int i = 0; i < 64; ++i) {
    state = state * 1664525u + 1013904223u;
    texture.rgba8.insert(texture.rgba8.end(), {255, 255, 255, static_cast<uint8_t>(state >> 24)});
  }
  scene.textures = {texture};
  scene.materials[0].baseColorTexture = 0;
  scene.materials[0].alphaCutoff = 0.4f;
  scene.materials[0].baseColorTransform.rotation = 0.5f;
  const engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
  ASSERT_TRUE(gpuScene.alphaCutouts);
  gi::IsmSettings settings;
  settings.pointCount = 1u << 14;
  settings.pointsPerVsgl = 1024;
  gi::Ism ism(ctx(), settings, vsglCount());
  ctx().submitAndWait([&](VkCommandBuffer cmd) { ism.recordPoints(cmd, gpuScene); });
  const auto gpu = ism.points().readbackAs<gpu::IsmPoint>(ctx());
  auto ref = gi::ismPointsReference(scene.positions, scene.indices, settings.pointCount);
  gi::ismCutPointsReference(ref, scene);
  size_t cut = 0, differing = 0;
  for (size_t i = 0; i < gpu.size(); ++i) {
    const bool gpuCut = gpu[i].triangle == ISM_NO_TRIANGLE;
    cut += gpuCut;
    if (gpuCut) {
      EXPECT_EQ(gpu[i].bary, 0u) << "point " << i;
    }
    differing += gpuCut != (ref[i].triangle == ISM_NO_TRIANGLE);
  }
  std::printf("cut-outs: %zu of %zu points cut, %zu decided otherwise by the twin\n", cut,
              gpu.size(), differing);
  EXPECT_LE(differing, gpu.size() / 500);
  // About the share of texels the test cuts (alpha x 0.7 below 0.4: 34 of 64): the uv map
  // repeats the 8 x 8 texture dozens of times over the scene, so the area-uniform points sample
  // every texel about equally; a binomial spread of 0.004, 0.03 allowed for the uneven
  // coverage of texels at the surfaces' edges.
  const engine::AlphaCutouts cutouts(scene);
  size_t cutTexels = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      cutTexels +=
          !cutouts.opaque(0, glm::vec2((float(x) + 0.5f) / 8.0f, (float(y) + 0.5f) / 8.0f));
  EXPECT_EQ(cutTexels, 34u);
  EXPECT_NEAR(static_cast<double>(cut) / static_cast<double>(gpu.size()),
              static_cast<double>(cutTexels) / 64.0, 0.03);
}

// The splat against the twin on the GPU's own points, then pull-push against the twin on the
// GPU's own raw atlas. Splat tolerance: positions and projections are fp32 on the GPU, so a
// point within ~1e-6 texel of a texel edge may land next door, and depths agree to ~1e-6
// relative; we allow 1e-5 relative and 0.1 % of texels differing (none expected: a few
// thousand splats, ~1e-5 texel boundary band). Pull-push: fp32 means of up to 4 values per
// level, 7 levels: 1e-5 relative.
TEST_F(IsmTest, SplatAndPullPushMatchTheReference) {
  gi::IsmSettings settings;  // the defaults: 64^2 maps, 2^18 points, 4096 per VSGL
  gi::Ism ism(ctx(), settings, vsglCount());
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    ism.recordPoints(cmd, *gpuScene_);
    ism.recordPositions(cmd, *gpuScene_, vsglCount());
    ism.recordSplat(cmd, *vsgls_, vsglCount());
  });
  const auto points = ism.points().readbackAs<gpu::IsmPoint>(ctx());
  const auto raw = toReferenceAtlas(atlasBits(ism));
  const auto ref =
      gi::ismSplatReference(scene_.positions, scene_.indices, points, vsglData_, settings.mapSize,
                            settings.pointsPerVsgl, settings.centreOffset);
  const size_t tile = size_t{settings.mapSize} * settings.mapSize;
  size_t differ = 0, filled = 0;
  for (size_t i = 0; i < raw.size(); ++i) {
    filled += raw[i] >= 0.0;
    const bool same =
        (raw[i] < 0.0 && ref[i] < 0.0) ||
        (raw[i] >= 0.0 && ref[i] >= 0.0 && std::abs(raw[i] - ref[i]) <= 1e-5 * ref[i]);
    differ += !same;
  }
  std::printf("splat: %zu of %zu texels filled, %zu differ from the reference\n", filled,
              raw.size(), differ);
  EXPECT_LE(differ, raw.size() / 1000);
  EXPECT_GT(filled, raw.size() / 10) << "too few splats for a meaningful comparison";
  for (size_t i = 5 * tile; i < 6 * tile; ++i) ASSERT_LT(raw[i], 0.0) << "the dark VSGL's tile";

  ctx().submitAndWait([&](VkCommandBuffer cmd) { ism.recordPullPush(cmd, vsglCount()); });
  const auto bits = atlasBits(ism);
  const auto filledRef = gi::ismPullPushReference(raw, settings.mapSize, vsglCount());
  for (size_t i = 0; i < bits.size(); ++i) {
    float f;
    std::memcpy(&f, &bits[i], 4);
    if (std::isinf(filledRef[i])) {
      ASSERT_TRUE(std::isinf(f) && f > 0.0f) << "texel " << i;
      continue;
    }
    ASSERT_NEAR(f, filledRef[i], 1e-5 * filledRef[i]) << "texel " << i << " tile " << i / tile;
    if (raw[i] >= 0.0) {
      ASSERT_EQ(double(f), raw[i]) << "pull-push changed a splatted texel " << i;
    }
  }
}

// The product test: visibility from the ISMs against ray casting from the same ISM centre,
// over every pixel of a 64^2 G-buffer in each lit VSGL's hemisphere (behind it the lookup is the
// extent fade, a light model rather than a depth test; the dark VSGL must give 1 everywhere).
// A pair agrees when the PCF visibility is >= 1/2 exactly where the ray cast sees the VSGL.
// ISMs are imperfect by design (single-point splats, holes filled by pull-push, 3.6-degree
// texels at the pole of a 64^2 map, depth bias): disagreements sit along shadow boundaries,
// where sparse near occluders let background points through, and at contacts; we require
// 90 % (measured: 94.6 %). The scene must really be shadowed: >= 20 % of the pairs occluded by
// the ray cast (measured: 28.5 %). The GPU lookup is also compared with its CPU twin on the GPU
// atlas and G-buffer, for every PCF mode: they differ only where the fp32 receiver position
// (rebuilt from depth, ~1e-4 m off) moves a depth test across its threshold.
TEST_F(IsmTest, VisibilityAgreesWithRayCasting) {
  const engine::View view = engine::cameraView(scene_.cameras[0], kSize, kSize);
  engine::Rasterizer rasterizer(ctx());
  engine::GBufferResolve resolve(ctx());
  engine::GBuffer gbuffer = engine::createGBuffer(ctx(), kSize, kSize);
  engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(kSize, kSize),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, *gpuScene_, view.viewProj, {&visibility, 0, kSize, kSize});
    resolve.record(cmd, *gpuScene_, visibility, view, gbuffer);
  });
  const engine::GBufferData g = engine::readbackGBuffer(ctx(), gbuffer);
  const glm::dmat4 invViewProj(view.invViewProj);
  std::vector<glm::dvec3> receivers;  // world positions rebuilt from depth, as the shader does
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      ASSERT_FALSE(g.at(x, y).background()) << "the camera should see geometry everywhere";
      const glm::dvec2 ndc = (glm::dvec2(x, y) + 0.5) / double(kSize) * 2.0 - 1.0;
      const glm::dvec4 h = invViewProj * glm::dvec4(ndc, double(g.at(x, y).depth), 1.0);
      receivers.push_back(glm::dvec3(h) / h.w);
    }
  engine::ImageDesc desc;
  desc.width = desc.height = kSize;
  desc.format = VK_FORMAT_R32_SFLOAT;
  engine::Image out(ctx(), desc);

  for (uint32_t pcf : {ISM_PCF_BILINEAR, ISM_PCF_NEAREST, ISM_PCF_BOX3}) {  // the default first
    gi::IsmSettings settings;
    settings.pcf = pcf;
    gi::Ism ism(ctx(), settings, vsglCount());
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      ism.recordPoints(cmd, *gpuScene_);
      ism.recordBuild(cmd, *gpuScene_, *vsgls_, vsglCount());
    });
    std::vector<double> atlas;
    for (uint32_t bits : atlasBits(ism)) {
      float f;
      std::memcpy(&f, &bits, 4);
      atlas.push_back(f);
    }
    size_t pairs = 0, agree = 0, occluded = 0, twinDiffer = 0;
    for (uint32_t k = 0; k < vsglCount(); ++k) {
      ctx().submitAndWait(
          [&](VkCommandBuffer cmd) { ism.recordVisibility(cmd, gbuffer, view, *vsgls_, k, out); });
      std::vector<float> gpu(size_t{kSize} * kSize);
      const auto bytes = out.readback(ctx());
      std::memcpy(gpu.data(), bytes.data(), bytes.size());
      const gi::IsmFrameReference frame =
          gi::ismFrameReference(vsglData_[k], settings.centreOffset);
      size_t vsglAgree = 0, vsglOccluded = 0, vsglPairs = 0;
      for (size_t i = 0; i < gpu.size(); ++i) {
        const float v = gpu[i];
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << "VSGL " << k << " pixel " << i << ": " << v;
        const double twin = gi::ismVisibilityReference(atlas, ism.params(), frame, k, receivers[i],
                                                       g.samples[i].normal);
        twinDiffer += std::abs(twin - v) > 1e-3;
        if (!frame.lit) {
          ASSERT_EQ(v, 1.0f) << "a dark VSGL never shadows";
          continue;
        }
        if (pcf != ISM_PCF_BILINEAR) continue;
        // The map holds the hemisphere only; behind it the lookup is the extent fade, which
        // the twin comparison above checks.
        if (!(gi::ismProjectReference(frame, receivers[i]).cosAxis > 0.0)) continue;
        ++vsglPairs;
        // The ray ends 2 mm off the receiver's visible side (the G-buffer normal faces the
        // camera), far above the error of the rebuilt position: a grazing ray cannot hit the
        // receiver's own plane short of it, and a VSGL behind the receiver's surface is
        // occluded by it.
        const bool truth = gi::ismRayCastVisible(scene_.positions, scene_.indices, frame.centre,
                                                 receivers[i] + 0.002 * g.samples[i].normal);
        vsglOccluded += !truth;
        vsglAgree += (v >= 0.5f) == truth;
      }
      if (!frame.lit || pcf != ISM_PCF_BILINEAR) continue;
      std::printf(
          "VSGL %u: %zu pixels in its hemisphere, %5.1f %% of them occluded, %5.1f %% agree\n", k,
          vsglPairs, 100.0 * double(vsglOccluded) / double(std::max<size_t>(vsglPairs, 1)),
          100.0 * double(vsglAgree) / double(std::max<size_t>(vsglPairs, 1)));
      pairs += vsglPairs;
      agree += vsglAgree;
      occluded += vsglOccluded;
    }
    const size_t lookups = size_t{vsglCount()} * kSize * kSize;
    std::printf("PCF mode %u: GPU lookup and CPU twin differ in %zu of %zu lookups\n", pcf,
                twinDiffer, lookups);
    EXPECT_LE(twinDiffer, lookups / 500);
    if (pcf != ISM_PCF_BILINEAR) continue;
    const double agreement = double(agree) / double(pairs);
    const double shadowed = double(occluded) / double(pairs);
    std::printf(
        "ISM vs ray cast: %.2f %% agreement over %zu (pixel in the hemisphere, lit VSGL) "
        "pairs, %.1f %% "
        "occluded\n",
        100.0 * agreement, pairs, 100.0 * shadowed);
    EXPECT_GE(shadowed, 0.2) << "too little shadow for the test to mean anything";
    EXPECT_GE(agreement, 0.9);
  }
}

// Points are (triangle, barycentrics): moving the vertices moves the splats without
// regenerating the pool. The whole scene drops by 0.25 m under the VSGLs: the new raw atlas
// matches the twin on the moved vertices with the OLD points, and the VSGL straight above the
// box (VSGL 0, axis -Y) sees its pole texel 0.25 m further away.
TEST_F(IsmTest, PointsFollowMovingGeometry) {
  gi::IsmSettings settings;
  gi::Ism ism(ctx(), settings, vsglCount());
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    ism.recordPoints(cmd, *gpuScene_);
    ism.recordPositions(cmd, *gpuScene_, vsglCount());
    ism.recordSplat(cmd, *vsgls_, vsglCount());
  });
  const auto points = ism.points().readbackAs<gpu::IsmPoint>(ctx());
  const auto before = toReferenceAtlas(atlasBits(ism));

  const glm::vec3 shift(0.0f, -0.25f, 0.0f);
  std::vector<glm::vec3> moved = scene_.positions;
  for (glm::vec3& p : moved) p += shift;
  auto vertices = gpuScene_->vertices.readbackAs<gpu::SceneVertex>(ctx());
  for (gpu::SceneVertex& v : vertices) v.positionU += glm::vec4(shift, 0.0f);
  gpuScene_->vertices.upload(ctx(), std::span<const gpu::SceneVertex>(vertices));
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    ism.recordPositions(cmd, *gpuScene_, vsglCount());  // no recordPoints
    ism.recordSplat(cmd, *vsgls_, vsglCount());
  });
  const auto after = toReferenceAtlas(atlasBits(ism));
  const auto ref = gi::ismSplatReference(moved, scene_.indices, points, vsglData_, settings.mapSize,
                                         settings.pointsPerVsgl, settings.centreOffset);
  size_t differ = 0, changed = 0;
  for (size_t i = 0; i < after.size(); ++i) {
    const bool same =
        (after[i] < 0.0 && ref[i] < 0.0) ||
        (after[i] >= 0.0 && ref[i] >= 0.0 && std::abs(after[i] - ref[i]) <= 1e-5 * ref[i]);
    differ += !same;
    changed += after[i] != before[i];
  }
  std::printf("moved geometry: %zu texels changed, %zu differ from the reference\n", changed,
              differ);
  EXPECT_LE(differ, after.size() / 1000);
  EXPECT_GT(changed, after.size() / 20);
  // VSGL 0 looks straight down at the box top (0.9 m high): the nearest splat around the
  // pole (the central 9 x 9 texels, ~0.3 rad) moves 0.25 m further away.
  auto nearestAroundPole = [&](const std::vector<double>& atlas) {
    double nearest = std::numeric_limits<double>::infinity();
    const int c = int(settings.mapSize / 2);
    for (int y = c - 4; y <= c + 4; ++y)
      for (int x = c - 4; x <= c + 4; ++x) {
        const double v = atlas[size_t(y) * settings.mapSize + size_t(x)];
        if (v >= 0.0) nearest = std::min(nearest, v);
      }
    return nearest;
  };
  const double nearBefore = nearestAroundPole(before), nearAfter = nearestAroundPole(after);
  std::printf("nearest splat around VSGL 0's pole: %.4f m before, %.4f m after\n", nearBefore,
              nearAfter);
  EXPECT_NEAR(nearBefore, 1.78 - 0.9, 0.02);
  EXPECT_NEAR(nearAfter - nearBefore, 0.25, 0.02);
}

}  // namespace
