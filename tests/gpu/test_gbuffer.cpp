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
// RGBA16F: Vulkan rounds a float to either neighbouring half (the mode is not defined;
// lavapipe truncates), an error below one ulp: 2^-10 relative for normal halves, one
// subnormal step 2^-24 below 2^-14. The shader's few fp32 products add ~1e-7 relative.
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
  GBufferData gbuffer;            // decoded
  std::vector<std::byte> raw[5];  // depth, normal, diffuse, specular, emission as read back
};

class GBufferTest : public testing_gpu::GpuTest {
 protected:
  GpuResolve resolve(const Scene& scene, const engine::View& view,
                     engine::BackFaces backFaces = engine::BackFaces::AsFront) {
    engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
    engine::Rasterizer rasterizer(ctx());
    engine::GBufferResolve resolvePass(ctx());
    engine::GBuffer g = engine::createGBuffer(ctx(), view.width, view.height);
    engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(view.width, view.height),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
      rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, view.width, view.height});
      resolvePass.record(cmd, gpuScene, visibility, view, g, nullptr, backFaces);
    });
    GpuResolve out;
    out.visibility = visibility.readbackAs<uint64_t>(ctx());
    out.raw[0] = g.depth.readback(ctx());
    out.raw[1] = g.normal.readback(ctx());
    out.raw[2] = g.diffuse.readback(ctx());
    out.raw[3] = g.specular.readback(ctx());
    out.raw[4] = g.emission.readback(ctx());
    out.gbuffer = engine::decodeGBuffer(view.width, view.height, out.raw[0], out.raw[1], out.raw[2],
                                        out.raw[3], out.raw[4]);
    return out;
  }
};

// Bytes of pixel i in each of the images are all zero except a depth of exactly 1.
bool rawBackground(const GpuResolve& r, size_t i) {
  float depth;
  std::memcpy(&depth, r.raw[0].data() + 4 * i, 4);
  auto zero = [](const std::vector<std::byte>& bytes, size_t first, size_t count) {
    return std::all_of(bytes.begin() + static_cast<ptrdiff_t>(first),
                       bytes.begin() + static_cast<ptrdiff_t>(first + count),
                       [](std::byte b) { return b == std::byte{0}; });
  };
  return depth == 1.0f && zero(r.raw[1], 4 * i, 4) && zero(r.raw[2], 8 * i, 8) &&
         zero(r.raw[3], 8 * i, 8) && zero(r.raw[4], 8 * i, 8);
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
    if (g.depth != r.depth)
      fail(i, "depth " + std::to_string(g.depth) + " vs " + std::to_string(r.depth));
    if (r.background()) {
      if (!rawBackground(gpu, i)) fail(i, "background texel not cleared");
      continue;
    }
    ++c.surfacePixels;
    double angle = angleBetween(g.normal, r.normal);
    c.maxNormalAngle = std::max(c.maxNormalAngle, angle);
    if (!(angle <= kNormalTolerance)) fail(i, "normal off by " + std::to_string(angle) + " rad");
    const double gv[8] = {g.diffuse.r, g.diffuse.g, g.diffuse.b, g.roughness,
                          g.f0.r,      g.f0.g,      g.f0.b,      g.f90};
    const double rv[8] = {r.diffuse.r, r.diffuse.g, r.diffuse.b, r.roughness,
                          r.f0.r,      r.f0.g,      r.f0.b,      r.f90};
    for (int k = 0; k < 8; ++k) {
      c.maxMaterialRelative = std::max(
          c.maxMaterialRelative, std::abs(gv[k] - rv[k]) / std::max(std::abs(rv[k]), 0x1p-14));
      if (!withinHalf(gv[k], rv[k]))
        fail(i, "material channel " + std::to_string(k) + ": " + std::to_string(gv[k]) + " vs " +
                    std::to_string(rv[k]));
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

// The lounge seen from behind its back wall, whose single-sided plaster faces into the room. A
// light's view (BackFaces::PerMaterial) keeps the wall's depth and blackens it; a camera view,
// or a double-sided material, shows it as its front. GPU and twin agree in both.
TEST_F(GBufferTest, LightViewBlackensSingleSidedBackFaces) {
  Scene scene = engine::makeBuiltinScene("lounge");
  const glm::mat4 viewMatrix =
      engine::lookAlong({0.0f, 1.2f, -5.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f});
  const engine::View view = engine::makeView(
      viewMatrix, engine::perspectiveVulkan(0.69f, 1.5f, 0.05f, 0.0f), kWidth, kHeight);
  for (const bool doubleSided : {false, true}) {
    for (engine::Material& m : scene.materials) m.doubleSided = doubleSided;
    for (const engine::BackFaces mode :
         {engine::BackFaces::AsFront, engine::BackFaces::PerMaterial}) {
      SCOPED_TRACE(std::string(doubleSided ? "double" : "single") + "-sided, " +
                   (mode == engine::BackFaces::AsFront ? "camera view" : "light view"));
      GpuResolve gpu = resolve(scene, view, mode);
      GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility, mode);
      Comparison c = compare(gpu, cpu);
      EXPECT_EQ(c.failures, 0u) << "first: " << c.firstFailure;
      const bool black = mode == engine::BackFaces::PerMaterial && !doubleSided;
      size_t surface = 0, reflecting = 0;
      for (const engine::GBufferSample& s : gpu.gbuffer.samples) {
        if (s.background()) continue;
        ++surface;
        reflecting += glm::length(s.diffuse) + glm::length(s.f0) + s.f90 > 0.0;
      }
      EXPECT_GT(surface, kWidth * kHeight / 2);  // the wall fills most of the view
      EXPECT_EQ(reflecting, black ? 0u : surface);
    }
  }
}

TEST_F(GBufferTest, CameraSeeingNothingGivesBackground) {
  Scene scene = engine::makeBuiltinScene("cornell");
  // From the cornell camera's position, looking away from the open box.
  glm::mat4 viewMatrix =
      engine::lookAlong({0.0f, 1.0f, 3.4f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f});
  engine::View view = engine::makeView(
      viewMatrix, engine::perspectiveVulkan(0.69f, 1.5f, 0.05f, 0.0f), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);
  size_t notBackground = 0;
  for (size_t i = 0; i < cpu.samples.size(); ++i)
    notBackground += (cpu.samples[i].background() && rawBackground(gpu, i)) ? 0 : 1;
  EXPECT_EQ(notBackground, 0u);
}

// A 4 x 4 m quad in the plane z = -2 facing a camera at the origin that looks down -Z, so it
// fills the view. UVs run from (uv0, uv0) top left to (uv1, uv1) bottom right (glTF's image
// orientation).
Scene texturedQuad(engine::Texture baseColor, engine::Texture metallicRoughness, engine::Material m,
                   float uv0 = 0.0f, float uv1 = 1.0f) {
  Scene s;
  s.source = "test:textured quad";
  s.positions = {{-2, 2, -2}, {2, 2, -2}, {2, -2, -2}, {-2, -2, -2}};
  s.normals.assign(4, glm::vec3(0, 0, 1));
  s.uvs = {{uv0, uv0}, {uv1, uv0}, {uv1, uv1}, {uv0, uv1}};
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

// Half the distance between the decoded values of the codes next to `code`: how far a
// correct sampler may land from the code's value. sRGB decoding may err that much (the D3D10
// rule, which lavapipe's polynomial meets with +-0.35 code: mesa's lp_bld_format_srgb.c), and
// lavapipe filters UNORM8 textures in 8-bit fixed point, rounding the result to 8 bits.
double halfCodeStep(int code, bool srgb) {
  auto decode = [&](double c) { return srgb ? engine::srgbToLinear(c / 255.0) : c / 255.0; };
  return 0.5 * std::min(code > 0 ? decode(code) - decode(code - 1) : 1.0,
                        code < 255 ? decode(code + 1) - decode(code) : 1.0);
}

// A host's bad indices (gi::SceneGeometry without CPU copies to check): a triangle naming a
// vertex past the buffer is left out by the rasterizer, one naming a material past the buffer
// keeps its depth and reflects nothing; nothing is read out of bounds, and the good triangle
// resolves as usual.
TEST_F(GBufferTest, BadIndicesAreNeverReadOutOfBounds) {
  engine::Material m;
  m.baseColorFactor = glm::vec4(0.5f, 0.6f, 0.7f, 1.0f);
  m.metallicFactor = 0.0f;
  Scene scene = texturedQuad(makeTexture("white", 1, [](int, int) { return glm::u8vec4(255); }),
                             makeTexture("white", 1, [](int, int) { return glm::u8vec4(255); }), m);
  scene.indices.insert(scene.indices.end(), {0, 2, 1000});  // a third triangle, vertex 1000
  scene.triangleMaterial = {0, 7, 0};                       // material 7 of 1
  const engine::View view = engine::cameraView(scene.cameras.at(0), kWidth, kHeight);
  const GpuResolve gpu = resolve(scene, view);
  size_t good = 0, black = 0;
  for (size_t i = 0; i < gpu.visibility.size(); ++i) {
    ASSERT_NE(gpu.visibility[i], ~uint64_t{0}) << "the quad fills the view";
    const auto triangle = static_cast<uint32_t>(gpu.visibility[i] & 0xFFFFFFFFu);
    ASSERT_LT(triangle, 2u) << "pixel " << i;
    const GBufferSample& s = gpu.gbuffer.samples[i];
    ASSERT_TRUE(std::isfinite(s.depth) && s.depth < 1.0f) << "pixel " << i;
    if (triangle == 1) {
      EXPECT_EQ(s.diffuse, glm::dvec3(0.0)) << "pixel " << i;
      EXPECT_EQ(s.f0, glm::dvec3(0.0)) << "pixel " << i;
      ++black;
    } else {
      EXPECT_TRUE(withinHalf(s.diffuse.g, 0.6)) << "pixel " << i;
      ++good;
    }
  }
  EXPECT_GT(good, gpu.visibility.size() / 4);
  EXPECT_GT(black, gpu.visibility.size() / 4);
}

TEST_F(GBufferTest, BackFacesTurnTheirNormalToTheViewer) {
  // The quad from behind: its front and its vertex normals point to +Z, away from a camera
  // at z = -6 looking towards +Z, so both sides must flip the normal to -Z.
  const glm::u8vec4 kWhite(255, 255, 255, 255);
  Scene scene = texturedQuad(makeTexture("base", 1, [&](int, int) { return kWhite; }),
                             makeTexture("mr", 1, [&](int, int) { return kWhite; }), {});
  glm::mat4 viewMatrix =
      engine::lookAlong({0.0f, 0.0f, -4.5f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f});
  engine::View view = engine::makeView(
      viewMatrix, engine::perspectiveVulkan(0.8f, 1.5f, 0.05f, 0.0f), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);
  for (size_t i = 0; i < cpu.samples.size(); ++i) {
    ASSERT_FALSE(cpu.samples[i].background()) << "the quad fills the view";
    ASSERT_LE(angleBetween(cpu.samples[i].normal, glm::dvec3(0, 0, -1)), 1e-12) << "pixel " << i;
  }
  Comparison c = compare(gpu, cpu);
  EXPECT_EQ(c.failures, 0u) << "first: " << c.firstFailure;
}

// A constant normal map on the quad, which faces +Z with u along +X and v down the image (-Y):
// its tangent frame is T = +X, B = +Y (the image's up), so the texel's (x, y, z) is the normal
// (x, y, z). With u mirrored (running along -X) T = -X while B stays up: (-x, y, z). The light's
// view (the RSM's resolve) shows the same normals. GPU and twin against the texel's decoded
// value, within the normal's storage tolerance (a constant 8-bit texture filters to its code).
TEST_F(GBufferTest, NormalMapTiltsTheNormalInTheTrianglesFrame) {
  const glm::u8vec4 kWhite(255, 255, 255, 255);
  const glm::u8vec4 kNormal(200, 90, 230, 255);
  engine::Material m;
  m.normalScale = 0.8f;
  const glm::dvec3 mapped = glm::dvec3(kNormal.r, kNormal.g, kNormal.b) / 255.0 * 2.0 - 1.0;
  const glm::dvec3 scaled(mapped.x * m.normalScale, mapped.y * m.normalScale, mapped.z);
  for (const bool mirrored : {false, true}) {
    Scene scene = texturedQuad(makeTexture("base", 1, [&](int, int) { return kWhite; }),
                               makeTexture("mr", 1, [&](int, int) { return kWhite; }), m,
                               mirrored ? 1.0f : 0.0f, mirrored ? 0.0f : 1.0f);
    if (mirrored)  // u back to the glTF layout's v: only u runs the other way
      for (glm::vec2& uv : scene.uvs) uv.y = 1.0f - uv.y;
    scene.textures.push_back(makeTexture("normal", 4, [&](int, int) { return kNormal; }));
    scene.materials[0].normalTexture = 2;
    const glm::dvec3 expected =
        glm::normalize(glm::dvec3(mirrored ? -scaled.x : scaled.x, scaled.y, scaled.z));
    engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
    for (const engine::BackFaces mode :
         {engine::BackFaces::AsFront, engine::BackFaces::PerMaterial}) {
      SCOPED_TRACE(std::string(mirrored ? "mirrored u" : "glTF layout") +
                   (mode == engine::BackFaces::AsFront ? ", camera view" : ", light view"));
      GpuResolve gpu = resolve(scene, view, mode);
      GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility, mode);
      double gpuError = 0.0, cpuError = 0.0;
      for (size_t i = 0; i < cpu.samples.size(); ++i) {
        ASSERT_FALSE(cpu.samples[i].background()) << "the quad fills the view";
        cpuError = std::max(cpuError, angleBetween(cpu.samples[i].normal, expected));
        gpuError = std::max(gpuError, angleBetween(gpu.gbuffer.samples[i].normal, expected));
      }
      EXPECT_LE(cpuError, 1e-12);
      EXPECT_LE(gpuError, kNormalTolerance);
      // The tilt is large: a map that was not applied would miss by 0.5 rad.
      EXPECT_GT(angleBetween(expected, glm::dvec3(0, 0, 1)), 0.4);
    }
  }
}

// glTF emission: factor (with KHR_materials_emissive_strength's scale folded in) times the sRGB
// emissive texture, in the G-buffer's emission image, GPU and twin; the back of a single-sided
// material in a light's view emits nothing there either.
TEST_F(GBufferTest, EmissionIsFactorTimesTexture) {
  const glm::u8vec4 kWhite(255, 255, 255, 255);
  const glm::u8vec4 kGlow(200, 100, 30, 255);  // sRGB
  engine::Material m;
  m.emissiveFactor = {0.5f, 2.0f, 4.0f};
  Scene scene = texturedQuad(makeTexture("base", 1, [&](int, int) { return kWhite; }),
                             makeTexture("mr", 1, [&](int, int) { return kWhite; }), m);
  scene.textures.push_back(makeTexture("glow", 4, [&](int, int) { return kGlow; }));
  scene.materials[0].emissiveTexture = 2;
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  const GpuResolve resolved = resolve(scene, view);
  const GBufferData& gpu = resolved.gbuffer;
  const GBufferData cpu = engine::resolveGBufferReference(scene, view, resolved.visibility);
  for (int c = 0; c < 3; ++c) {
    const double expected = m.emissiveFactor[c] * engine::srgbToLinear(kGlow[c] / 255.0);
    const double tolerance =
        m.emissiveFactor[c] * halfCodeStep(kGlow[c], true) + kHalfRelative * expected;
    for (size_t i = 0; i < cpu.samples.size(); ++i) {
      ASSERT_NEAR(cpu.samples[i].emission[c], expected, 1e-12) << "pixel " << i;
      ASSERT_NEAR(gpu.samples[i].emission[c], expected, tolerance) << "pixel " << i;
    }
  }
  // From behind, in a light's view, the single-sided quad is no surface: no emission.
  const glm::mat4 behind =
      engine::lookAlong({0.0f, 0.0f, -4.5f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f});
  const engine::View back =
      engine::makeView(behind, engine::perspectiveVulkan(0.8f, 1.5f, 0.05f, 0.0f), kWidth, kHeight);
  const GpuResolve light = resolve(scene, back, engine::BackFaces::PerMaterial);
  const GBufferData lightCpu = engine::resolveGBufferReference(scene, back, light.visibility,
                                                               engine::BackFaces::PerMaterial);
  for (size_t i = 0; i < lightCpu.samples.size(); ++i) {
    ASSERT_FALSE(lightCpu.samples[i].background());
    ASSERT_EQ(lightCpu.samples[i].emission, glm::dvec3(0.0)) << "pixel " << i;
    ASSERT_EQ(light.gbuffer.samples[i].emission, glm::dvec3(0.0)) << "pixel " << i;
  }
}

TEST_F(GBufferTest, ConstantTexturesMultiplyFactors) {
  const glm::u8vec4 kBase(200, 100, 30, 255);  // sRGB
  const glm::u8vec4 kMr(0, 150, 90, 255);      // G = roughness, B = metallic (linear)
  engine::Material m;
  m.baseColorFactor = {0.8f, 0.9f, 0.5f, 1.0f};
  m.roughnessFactor = 0.9f;
  m.metallicFactor = 0.7f;
  // KHR_materials_specular: half strength, a colour that clamps nothing (0.04 x 2 < 1).
  m.specularFactor = 0.5f;
  m.specularColorFactor = {0.5f, 1.0f, 2.0f};
  Scene scene = texturedQuad(makeTexture("base", 8, [&](int, int) { return kBase; }),
                             makeTexture("mr", 8, [&](int, int) { return kMr; }), m);
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);

  // factor * texture with glTF's metallic-roughness model and KHR_materials_specular, from the
  // texel codes.
  glm::dvec3 base;
  for (int k = 0; k < 3; ++k)
    base[k] = m.baseColorFactor[k] * engine::srgbToLinear(kBase[k] / 255.0);
  const double roughness = m.roughnessFactor * (kMr.g / 255.0);
  const double metallic = m.metallicFactor * (kMr.b / 255.0);
  const glm::dvec3 diffuse = base * (1.0 - metallic);
  const glm::dvec3 dielectricF0 =
      0.04 * glm::dvec3(m.specularColorFactor) * double(m.specularFactor);
  const glm::dvec3 f0 = glm::mix(dielectricF0, base, metallic);
  const double f90 = m.specularFactor + (1.0 - m.specularFactor) * metallic;
  // The GPU: the 8-bit quantisation (half a code, scaled by the factors and carried through
  // the linear metallic mix), then fp16 storage.
  auto tolerance = [&](double expected, double textureError) {
    return textureError + kHalfRelative * std::abs(expected) + kHalfAbsolute;
  };
  const double roughnessError = m.roughnessFactor * halfCodeStep(kMr.g, false);
  const double metallicError = m.metallicFactor * halfCodeStep(kMr.b, false);

  double maxError = 0.0;
  for (size_t i = 0; i < cpu.samples.size(); ++i) {
    const GBufferSample& r = cpu.samples[i];
    const GBufferSample& g = gpu.gbuffer.samples[i];
    ASSERT_FALSE(r.background()) << "the quad fills the view";
    // The reference filters the same constant texels: equal up to double rounding.
    ASSERT_NEAR(r.roughness, roughness, 1e-12);
    ASSERT_NEAR(r.f90, f90, 1e-12);
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(r.diffuse[k], diffuse[k], 1e-12);
      ASSERT_NEAR(r.f0[k], f0[k], 1e-12);
      const double baseError = m.baseColorFactor[k] * halfCodeStep(kBase[k], true);
      const double diffuseError = baseError * (1.0 - metallic) + std::abs(base[k]) * metallicError;
      const double f0Error =
          baseError * metallic + std::abs(base[k] - dielectricF0[k]) * metallicError;
      ASSERT_NEAR(g.diffuse[k], diffuse[k], tolerance(diffuse[k], diffuseError)) << "pixel " << i;
      ASSERT_NEAR(g.f0[k], f0[k], tolerance(f0[k], f0Error)) << "pixel " << i;
      maxError =
          std::max({maxError, std::abs(g.diffuse[k] - diffuse[k]), std::abs(g.f0[k] - f0[k])});
    }
    ASSERT_NEAR(g.roughness, roughness, tolerance(roughness, roughnessError)) << "pixel " << i;
    const double f90Error = (1.0 - m.specularFactor) * metallicError;
    ASSERT_NEAR(g.f90, f90, tolerance(f90, f90Error)) << "pixel " << i;
    maxError = std::max({maxError, std::abs(g.roughness - roughness), std::abs(g.f90 - f90)});
  }
  RecordProperty("max_abs_error", std::to_string(maxError));
}

// Identity, and a KHR_texture_transform (scale 0.5, rotation 0.3 rad, offset (0.1, 0.3)) that
// keeps the transformed coordinates inside the outer texel centres too (u' in [0.14, 0.69],
// v' in [0.19, 0.74]): the GPU's transform of coordinates and gradients against the twin's.
class MagnifiedTextures : public GBufferTest,
                          public ::testing::WithParamInterface<engine::TextureTransform> {};

TEST_P(MagnifiedTextures, MatchBilinearReference) {
  // 8 x 8 ramps stretched over the view: ~0.05 texels per pixel, so the GPU's LOD is < 0 and
  // its trilinear filter reduces to bilinear on mip 0, the reference's filter. UVs stay
  // between the outer texel centres (1/16 .. 15/16) so no tap wraps around.
  constexpr int kSize = 8;
  auto baseAt = [](int x, int y) {
    return glm::u8vec4(40 + 20 * x, 200 - 15 * y, 100 + 5 * (x + y), 255);
  };
  auto mrAt = [](int x, int) { return glm::u8vec4(0, 60 + 20 * x, 0, 255); };
  engine::Material m;
  m.baseColorFactor = {1.0f, 0.8f, 0.6f, 1.0f};
  m.roughnessFactor = 0.75f;
  m.metallicFactor = 0.0f;  // diffuse = base colour, F0 = 0.04
  m.baseColorTransform = m.metallicRoughnessTransform = GetParam();
  Scene scene = texturedQuad(makeTexture("base", kSize, baseAt), makeTexture("mr", kSize, mrAt), m,
                             0.5f / kSize, 1.0f - 0.5f / kSize);
  engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  GpuResolve gpu = resolve(scene, view);
  GBufferData cpu = engine::resolveGBufferReference(scene, view, gpu.visibility);

  // Per channel: half a code as above, plus the sampler's quantisation of each bilinear
  // weight to subTexelPrecisionBits, which moves the result by at most 2^-bits times the
  // largest step between neighbouring texels, per axis.
  const double weightError =
      2.0 * std::ldexp(1.0, -static_cast<int>(ctx().properties().limits.subTexelPrecisionBits));
  auto samplerError = [&](auto texelAt, int channel, bool srgb, double factor) {
    auto decode = [&](int x, int y) {
      double c = texelAt(x, y)[channel] / 255.0;
      return srgb ? engine::srgbToLinear(c) : c;
    };
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        double step = std::max(x + 1 < kSize ? std::abs(decode(x + 1, y) - decode(x, y)) : 0.0,
                               y + 1 < kSize ? std::abs(decode(x, y + 1) - decode(x, y)) : 0.0);
        worst = std::max(worst, halfCodeStep(texelAt(x, y)[channel], srgb) + weightError * step);
      }
    return factor * worst;
  };
  const double baseError[3] = {samplerError(baseAt, 0, true, m.baseColorFactor.r),
                               samplerError(baseAt, 1, true, m.baseColorFactor.g),
                               samplerError(baseAt, 2, true, m.baseColorFactor.b)};
  const double roughnessError = samplerError(mrAt, 1, false, m.roughnessFactor);

  double maxError = 0.0;
  for (size_t i = 0; i < cpu.samples.size(); ++i) {
    const GBufferSample& r = cpu.samples[i];
    const GBufferSample& g = gpu.gbuffer.samples[i];
    ASSERT_FALSE(r.background()) << "the quad fills the view";
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(g.diffuse[k], r.diffuse[k],
                  baseError[k] + kHalfRelative * r.diffuse[k] + kHalfAbsolute)
          << "pixel " << i << " channel " << k;
      ASSERT_TRUE(withinHalf(g.f0[k], 0.04)) << g.f0[k];
      maxError = std::max(maxError, std::abs(g.diffuse[k] - r.diffuse[k]));
    }
    ASSERT_NEAR(g.roughness, r.roughness,
                roughnessError + kHalfRelative * r.roughness + kHalfAbsolute)
        << "pixel " << i;
    ASSERT_EQ(g.f90, 1.0);  // a dielectric without KHR_materials_specular
    maxError = std::max(maxError, std::abs(g.roughness - r.roughness));
  }
  RecordProperty("max_abs_error", std::to_string(maxError));
}

INSTANTIATE_TEST_SUITE_P(GBuffer, MagnifiedTextures,
                         ::testing::Values(engine::TextureTransform{},
                                           engine::TextureTransform{
                                               {0.1f, 0.3f}, 0.3f, {0.5f, 0.5f}}));

}  // namespace
