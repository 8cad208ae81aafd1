// The G-buffer resolve against its CPU twin (engine/gbuffer_reference.h). The reference reads
// the GPU's own visibility buffer, so both resolve the same triangle per pixel and the only
// differences left are fp32 arithmetic and the storage formats' quantisation, bounded below.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "engine/builtin_scenes.h"
#include "engine/gbuffer.h"
#include "engine/gbuffer_reference.h"
#include "engine/rasterizer.h"
#include "engine/view.h"
#include "gpu_fixture.h"

namespace {

using engine::GBufferData;
using engine::GBufferSample;
using engine::Scene;

constexpr uint32_t kWidth = 96;
constexpr uint32_t kHeight = 64;

// RG16_SNORM stores each octahedral coordinate e as one of the two codes nearest to
// e * 32767 (Vulkan leaves the rounding direction open), so |de| <= 1/32767 per component.
// The octahedral decode stretches de most at the face centre (1, 1, 1) / 3 of the octahedron,
// where |dp| = sqrt(6) |de| lies in the tangent plane and |p| = 1/sqrt(3): the angle is at
// most sqrt(18) / 32767 = 1.29e-4 rad. 1e-6 rad more covers the shader's fp32 normalize and
// encode (a few ulps).
constexpr double kNormalTolerance = 3.0 * std::numbers::sqrt2 / 32767.0 + 1e-6;
// RGBA16F: Vulkan rounds a float to either neighbouring half (the mode is not defined; round
// toward zero is common), an error below one half ulp = 2^-10 relative for normal halves and
// one subnormal step 2^-24 below 2^-14. The shader's few fp32 products add ~1e-7 relative.
constexpr double kHalfRelative = 0x1p-10 + 1e-6;
constexpr double kHalfAbsolute = 0x1p-24;

bool withinHalf(double gpu, double cpu) {
  return std::abs(gpu - cpu) <= kHalfRelative * std::abs(cpu) + kHalfAbsolute;
}

double angleBetween(glm::dvec3 a, glm::dvec3 b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

struct GpuResolve {
  std::vector<uint64_t> visibility;
  GBufferData gbuffer;                  // decoded
  std::vector<std::byte> raw[4];        // depth, normal, diffuse, specular as read back
};

class GBufferTest : public testing_gpu::GpuTest {
 protected:
  GpuResolve resolve(const Scene& scene, const engine::View& view) {
    engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
    engine::Rasterizer rasterizer(ctx());
    engine::GBufferResolve resolve(ctx());
    engine::GBuffer g = engine::createGBuffer(ctx(), view.width, view.height);
    engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(view.width, view.height),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, view.width, view.height});
      resolve.record(cmd, gpuScene, visibility, view, g);
    });
    GpuResolve out;
    out.visibility = visibility.readbackAs<uint64_t>(ctx());
    out.raw[0] = g.depth.readback(ctx());
    out.raw[1] = g.normal.readback(ctx());
    out.raw[2] = g.diffuse.readback(ctx());
    out.raw[3] = g.specular.readback(ctx());
    out.gbuffer = engine::decodeGBuffer(view.width, view.height, out.raw[0], out.raw[1],
                                        out.raw[2], out.raw[3]);
    return out;
  }
};

// Bytes of pixel i in each of the four images are all zero except a depth of exactly 1.
bool rawBackground(const GpuResolve& r, size_t i) {
  float depth;
  std::memcpy(&depth, r.raw[0].data() + 4 * i, 4);
  auto zero = [](const std::vector<std::byte>& bytes, size_t first, size_t count) {
    return std::all_of(bytes.begin() + static_cast<ptrdiff_t>(first),
                       bytes.begin() + static_cast<ptrdiff_t>(first + count),
                       [](std::byte b) { return b == std::byte{0}; });
  };
  return depth == 1.0f && zero(r.raw[1], 4 * i, 4) && zero(r.raw[2], 8 * i, 8) && zero(r.raw[3], 8 * i, 8);
}

struct Comparison {
  size_t surfacePixels = 0;
  size_t failures = 0;
  std::string firstFailure;
  double maxNormalAngle = 0.0;
  double maxMaterialRelative = 0.0;  // |gpu - cpu| / max(|cpu|, 2^-14) over every channel
};

// Compares a decoded GPU G-buffer with the reference pixel by pixel.
Comparison compare(const GpuResolve& gpu, const GBufferData& cpu) {
  Comparison c;
  auto fail = [&](size_t i, const std::string& what) {
    if (c.failures++ == 0)
      c.firstFailure = what + " at (" + std::to_string(i % cpu.width) + ", " +
                       std::to_string(i / cpu.width) + ")";
  };
  for (size_t i = 0; i < cpu.samples.size(); ++i) {
    const GBufferSample& g = gpu.gbuffer.samples[i];
    const GBufferSample& r = cpu.samples[i];
    if (g.depth != r.depth) fail(i, "depth " + std::to_string(g.depth) + " vs " + std::to_string(r.depth));
    if (r.background()) {
      if (!rawBackground(gpu, i)) fail(i, "background texel not cleared");
      continue;
    }
    ++c.surfacePixels;
    double angle = angleBetween(g.normal, r.normal);
    c.maxNormalAngle = std::max(c.maxNormalAngle, angle);
    if (!(angle <= kNormalTolerance)) fail(i, "normal off by " + std::to_string(angle) + " rad");
    const double gv[8] = {g.diffuse.r, g.diffuse.g, g.diffuse.b, g.roughness, g.f0.r, g.f0.g, g.f0.b, g.metallic};
    const double rv[8] = {r.diffuse.r, r.diffuse.g, r.diffuse.b, r.roughness, r.f0.r, r.f0.g, r.f0.b, r.metallic};
    for (int k = 0; k < 8; ++k) {
      c.maxMaterialRelative = std::max(c.maxMaterialRelative, std::abs(gv[k] - rv[k]) / std::max(std::abs(rv[k]), 0x1p-14));
      if (!withinHalf(gv[k], rv[k]))
        fail(i, "material channel " + std::to_string(k) + ": " + std::to_string(gv[k]) + " vs " + std::to_string(rv[k]));
    }
  }
  return c;
}

class GBufferScenes : public GBufferTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(GBufferScenes, MatchesReference) {
  Scene scene = engine::makeBuiltinScene(GetParam());
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);
  Comparison c = compare(gpu, cpu);
  RecordProperty("max_normal_angle", std::to_string(c.maxNormalAngle));
  RecordProperty("max_material_relative", std::to_string(c.maxMaterialRelative));
  // The cameras look into closed rooms: (nearly) every pixel sees a surface.
  EXPECT_GT(c.surfacePixels, kWidth * kHeight / 2);
  EXPECT_EQ(c.failures, 0u) << "first: " << c.firstFailure;
}

INSTANTIATE_TEST_SUITE_P(GBuffer, GBufferScenes, ::testing::ValuesIn(engine::builtinSceneNames()));

TEST_F(GBufferTest, CameraSeeingNothingGivesBackground) {
  Scene scene = engine::makeBuiltinScene("cornell");
  // From the cornell camera's position, looking away from the open box.
  glm::mat4 viewMatrix = engine::lookAlong({0.0f, 1.0f, 3.4f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f});
  engine::View view = engine::makeView(viewMatrix, engine::perspectiveVulkan(0.69f, 1.5f, 0.05f, 0.0f), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);
  size_t notBackground = 0;
  for (size_t i = 0; i < cpu.samples.size(); ++i)
    notBackground += (cpu.samples[i].background() && rawBackground(gpu, i)) ? 0 : 1;
  EXPECT_EQ(notBackground, 0u);
}

// A 4 x 4 m quad in the plane z = -2 facing a camera at the origin that looks down -Z, so it
// fills the view. UVs (0,0) top left to (1,1) bottom right, as glTF's image orientation.
Scene texturedQuad(engine::Texture baseColor, engine::Texture metallicRoughness, engine::Material m) {
  Scene s;
  s.source = "test:textured quad";
  s.positions = {{-2, 2, -2}, {2, 2, -2}, {2, -2, -2}, {-2, -2, -2}};
  s.normals.assign(4, glm::vec3(0, 0, 1));
  s.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.indices = {0, 3, 2, 0, 2, 1};  // counter-clockwise seen from +Z
  s.triangleMaterial = {0, 0};
  s.textures = {std::move(baseColor), std::move(metallicRoughness)};
  m.baseColorTexture = 0;
  m.metallicRoughnessTexture = 1;
  s.materials = {m};
  engine::Camera camera;  // identity pose: at the origin looking down -Z
  s.cameras = {camera};
  return s;
}

engine::Texture makeTexture(const std::string& name, int size, auto texelAt) {
  engine::Texture t;
  t.name = name;
  t.width = t.height = size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      glm::u8vec4 c = texelAt(x, y);
      t.rgba8.insert(t.rgba8.end(), {c.r, c.g, c.b, c.a});
    }
  return t;
}

// Half the distance between the decoded values of the codes next to `code`: a filtered result
// closer than this to the code's own value can only have come from that code.
double halfCodeStep(int code, bool srgb) {
  auto decode = [&](double c) { return srgb ? engine::srgbToLinear(c / 255.0) : c / 255.0; };
  return 0.5 * std::min(code > 0 ? decode(code) - decode(code - 1) : 1.0,
                        code < 255 ? decode(code + 1) - decode(code) : 1.0);
}

TEST_F(GBufferTest, ConstantTexturesMultiplyFactors) {
  const glm::u8vec4 kBase(200, 100, 30, 255);  // sRGB
  const glm::u8vec4 kMr(0, 150, 90, 255);      // G = roughness, B = metallic (linear)
  engine::Material m;
  m.baseColorFactor = {0.8f, 0.9f, 0.5f, 1.0f};
  m.roughnessFactor = 0.9f;
  m.metallicFactor = 0.7f;
  Scene scene = texturedQuad(makeTexture("base", 8, [&](int, int) { return kBase; }),
                             makeTexture("mr", 8, [&](int, int) { return kMr; }), m);
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);

  // factor * texture with glTF's metallic-roughness model, from the texel codes.
  glm::dvec3 base;
  for (int k = 0; k < 3; ++k) base[k] = m.baseColorFactor[k] * engine::srgbToLinear(kBase[k] / 255.0);
  const double roughness = m.roughnessFactor * (kMr.g / 255.0);
  const double metallic = m.metallicFactor * (kMr.b / 255.0);
  const glm::dvec3 diffuse = base * (1.0 - metallic);
  const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), base, metallic);
  // GPU: the filtered texel must decode to within half a code step of its code (the 8-bit
  // quantisation), scaled by the factors, then stored as fp16.
  auto tolerance = [&](double expected, double factorStep) {
    return factorStep + kHalfRelative * std::abs(expected) + kHalfAbsolute;
  };
  const double roughnessStep = m.roughnessFactor * halfCodeStep(kMr.g, false);
  const double metallicStep = m.metallicFactor * halfCodeStep(kMr.b, false);

  size_t checked = 0;
  double maxError = 0.0;
  for (size_t i = 0; i < cpu.samples.size(); ++i) {
    const GBufferSample& r = cpu.samples[i];
    const GBufferSample& g = gpu.gbuffer.samples[i];
    ASSERT_FALSE(r.background()) << "the quad fills the view";
    ++checked;
    // The reference filters the same constant texels: equal up to double rounding.
    EXPECT_NEAR(r.roughness, roughness, 1e-12);
    EXPECT_NEAR(r.metallic, metallic, 1e-12);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(r.diffuse[k], diffuse[k], 1e-12);
      EXPECT_NEAR(r.f0[k], f0[k], 1e-12);
      // Both diffuse and F0 are linear in base colour and metallic.
      const double baseStep = m.baseColorFactor[k] * halfCodeStep(kBase[k], true);
      const double diffuseStep = baseStep * (1.0 - metallic) + std::abs(base[k]) * metallicStep;
      const double f0Step = baseStep * metallic + std::abs(base[k] - 0.04) * metallicStep;
      ASSERT_NEAR(g.diffuse[k], diffuse[k], tolerance(diffuse[k], diffuseStep)) << "pixel " << i;
      ASSERT_NEAR(g.f0[k], f0[k], tolerance(f0[k], f0Step)) << "pixel " << i;
      maxError = std::max({maxError, std::abs(g.diffuse[k] - diffuse[k]), std::abs(g.f0[k] - f0[k])});
    }
    ASSERT_NEAR(g.roughness, roughness, tolerance(roughness, roughnessStep)) << "pixel " << i;
    ASSERT_NEAR(g.metallic, metallic, tolerance(metallic, metallicStep)) << "pixel " << i;
    maxError = std::max({maxError, std::abs(g.roughness - roughness), std::abs(g.metallic - metallic)});
  }
  RecordProperty("max_abs_error", std::to_string(maxError));
  EXPECT_EQ(checked, size_t{kWidth} * kHeight);
}

}  // namespace
