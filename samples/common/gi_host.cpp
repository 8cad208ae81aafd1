#include "gi_host.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

#include "engine/rasterizer.h"
#include "engine/tonemap.h"

namespace samples {

void check(const gi::Status& status) {
  if (!status) throw engine::Error(status.message);
}

std::vector<uint32_t> bouncingLights(const engine::Scene& scene) {
  if (scene.lights.empty())
    throw engine::Error(scene.source +
                        ": no light to bounce (--light none; auto, sun or headlight add one)");
  if (scene.lights.size() > gi::kMaxLights)
    throw engine::Error(scene.source + ": " + std::to_string(scene.lights.size()) +
                        " lights; the module bounces " + std::to_string(gi::kMaxLights) +
                        " at most");
  std::vector<uint32_t> lights(scene.lights.size());
  for (uint32_t i = 0; i < lights.size(); ++i) lights[i] = i;
  return lights;
}

int firstDirectedLight(const engine::Scene& scene) {
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type != engine::LightType::Point) return int(i);
  return -1;
}

float maxReflectance(const engine::Scene& scene) {
  // The smallest and largest value of a texture channel over every texel ({1, 1}: no texture).
  auto textureRange = [&](int index, int channel) {
    if (index < 0) return std::pair{1.0f, 1.0f};
    uint8_t lo = 255, hi = 0;
    const std::vector<uint8_t>& t = scene.textures.at(size_t(index)).rgba8;
    for (size_t i = size_t(channel); i < t.size(); i += 4) {
      lo = std::min(lo, t[i]);
      hi = std::max(hi, t[i]);
    }
    return std::pair{float(lo) / 255.0f, float(hi) / 255.0f};
  };
  // The diffuse albedo base (1 - metallic) <= base; the specular lobe reflects at most its
  // largest F0 channel or F90 (Schlick's grazing value, which a black metal still has):
  // maxSpecular bounds both.
  float bound = maxSpecular(scene);
  for (const engine::Material& m : scene.materials)
    for (int c = 0; c < 3; ++c)
      bound = std::max(bound, m.baseColorFactor[c] *
                                  engine::srgbToLinear(textureRange(m.baseColorTexture, c).second));
  return std::min(bound, 1.0f);
}

float maxSpecular(const engine::Scene& scene) {
  float bound = 0.0f;
  for (const engine::Material& m : scene.materials) {
    float metallic = m.metallicFactor;  // the largest metallic over the texture
    if (m.metallicRoughnessTexture >= 0) {
      uint8_t hi = 0;
      const std::vector<uint8_t>& t = scene.textures.at(size_t(m.metallicRoughnessTexture)).rgba8;
      for (size_t i = 2; i < t.size(); i += 4) hi = std::max(hi, t[i]);
      metallic *= float(hi) / 255.0f;
    }
    // F90 = s + (1 - s) metallic and F0 <= max(F0 of the dielectric, base colour) <= 1 once
    // metallic > 0; for a dielectric F0 = min(0.04 c, 1) s <= s.
    const float f90 = m.specularFactor + (1.0f - m.specularFactor) * std::min(metallic, 1.0f);
    bound = std::max({bound, f90, metallic > 0.0f ? 1.0f : 0.0f});
  }
  return std::min(bound, 1.0f);
}

bool canOcclude(const engine::Scene& scene) {
  if (scene.triangleCount() > kOccluderTestTriangles) return true;
  const engine::Bounds b = scene.bounds();
  const float tolerance = 1e-5f * glm::length(b.max - b.min);
  for (uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const glm::vec3 p0 = scene.positions[scene.indices[3 * t]];
    const glm::vec3 n = glm::cross(scene.positions[scene.indices[3 * t + 1]] - p0,
                                   scene.positions[scene.indices[3 * t + 2]] - p0);
    const float length = glm::length(n);
    if (!(length > 0.0f)) continue;  // a degenerate triangle blocks nothing
    for (const glm::vec3& p : scene.positions)
      if (glm::dot(n, p - p0) < -tolerance * length) return true;  // a vertex behind the plane
  }
  return false;
}

gi::SceneGeometry sceneGeometry(const engine::SceneGpu& gpuScene, const engine::Scene& scene) {
  gi::SceneGeometry geometry;
  geometry.vertices = gpuScene.vertices.handle();
  geometry.vertexBytes = gpuScene.vertices.size();
  geometry.indices = gpuScene.indices.handle();
  geometry.indexBytes = gpuScene.indices.size();
  geometry.triangleMaterials = gpuScene.triangleMaterials.handle();
  geometry.triangleMaterialBytes = gpuScene.triangleMaterials.size();
  geometry.materials = gpuScene.materials.handle();
  geometry.materialBytes = gpuScene.materials.size();
  geometry.triangleCount = gpuScene.triangleCount;
  geometry.vertexCount = gpuScene.vertexCount;
  geometry.materialCount = gpuScene.materialCount;
  // The CPU copies, so that setScene checks every index (the scene outlives the call).
  geometry.indexData = scene.indices;
  geometry.triangleMaterialData = scene.triangleMaterial;
  geometry.baseColorTextures = gpuScene.baseColorTextures.view();
  geometry.dataTextures = gpuScene.dataTextures.view();
  geometry.sampler = gpuScene.sampler.handle();
  const engine::Bounds bounds = scene.bounds();
  geometry.boundsMin = bounds.min;
  geometry.boundsMax = bounds.max;
  geometry.maxReflectance = maxReflectance(scene);
  geometry.canOcclude = canOcclude(scene);
  geometry.alphaCutouts = gpuScene.alphaCutouts;
  geometry.maxSpecular = maxSpecular(scene);
  return geometry;
}

std::unique_ptr<gi::IndirectLighting> createIndirect(engine::Context& ctx,
                                                     const gi::Settings& settings, uint32_t width,
                                                     uint32_t height,
                                                     const engine::SceneGpu& gpuScene,
                                                     const engine::Scene& scene) {
  gi::Status status;
  auto lighting = gi::IndirectLighting::create(
      {ctx.instance(), ctx.physicalDevice(), ctx.device(), ctx.queueFamily()}, settings, width,
      height, &status);
  check(status);
  check(lighting->setScene(sceneGeometry(gpuScene, scene)));
  return lighting;
}

engine::GBuffer renderGBuffer(engine::Context& ctx, const engine::SceneGpu& gpuScene,
                              const engine::View& view) {
  engine::GBuffer gbuffer = engine::createGBuffer(ctx, view.width, view.height);
  engine::Rasterizer rasterizer(ctx);
  engine::GBufferResolve resolve(ctx);
  engine::Buffer visibility(ctx, engine::Rasterizer::visibilityBytes(view.width, view.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, view.width, view.height});
    resolve.record(cmd, gpuScene, visibility, view, gbuffer);
  });
  return gbuffer;
}

gi::Light apiLight(const engine::Light& light) {
  gi::Light l;
  l.type = light.type == engine::LightType::Spot          ? gi::Light::Type::Spot
           : light.type == engine::LightType::Directional ? gi::Light::Type::Directional
                                                          : gi::Light::Type::Point;
  l.position = light.position;
  l.direction = light.direction;
  l.color = light.color;
  l.intensity = light.intensity;
  l.innerConeAngle = light.innerConeAngle;
  l.outerConeAngle = light.outerConeAngle;
  l.range = light.range;
  return l;
}

gi::FrameInput frameInput(const engine::GBuffer& gbuffer, const engine::View& view,
                          std::span<const engine::Light> lights) {
  gi::FrameInput in;
  auto ref = [](const engine::Image& image) {
    return gi::ImageRef{image.handle(), image.view(), image.layout()};
  };
  in.gbuffer = {gbuffer.width,       gbuffer.height,       ref(gbuffer.depth),
                ref(gbuffer.normal), ref(gbuffer.diffuse), ref(gbuffer.specular)};
  in.camera = {view.view, view.proj};
  for (const engine::Light& light : lights) in.lights.push_back(apiLight(light));
  return in;
}

gi::FrameInput frameInput(const engine::GBuffer& gbuffer, const engine::View& view,
                          const engine::Light& light) {
  return frameInput(gbuffer, view, std::span<const engine::Light>(&light, 1));
}

namespace {

engine::ImageRgba32f toImage(const std::vector<glm::vec4>& texels, uint32_t width,
                             uint32_t height) {
  engine::ImageRgba32f image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.pixels.assign(&texels.data()->x, &texels.data()->x + 4 * texels.size());
  return image;
}

// The module's output images, read through a non-owning engine image of the host's own.
engine::ImageRgba32f readOutput(engine::Context& ctx, const gi::ImageRef& ref, uint32_t width,
                                uint32_t height, VkFormat format) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  engine::Image image = engine::Image::borrow(ref.image, ref.view, desc, ref.layout);
  return toImage(image.readbackRgba32f(ctx), width, height);
}

}  // namespace

engine::ImageRgba32f readRadiance(engine::Context& ctx, engine::Image& image) {
  return toImage(image.readbackRgba32f(ctx), image.desc().width, image.desc().height);
}

Indirect readIndirect(engine::Context& ctx, const gi::FrameOutput& output, uint32_t width,
                      uint32_t height) {
  return {readOutput(ctx, output.indirectDiffuse, width, height, VK_FORMAT_R32G32B32A32_SFLOAT),
          readOutput(ctx, output.indirectGlossy, width, height, VK_FORMAT_R32G32B32A32_SFLOAT)};
}

Indirect readEnvironment(engine::Context& ctx, const gi::FrameOutput& output, uint32_t width,
                         uint32_t height) {
  return {readOutput(ctx, output.environmentDiffuse, width, height, VK_FORMAT_R32G32B32A32_SFLOAT),
          readOutput(ctx, output.environmentGlossy, width, height, VK_FORMAT_R32G32B32A32_SFLOAT)};
}

std::vector<glm::dvec3> indirectSum(const Indirect& indirect) {
  std::vector<glm::dvec3> sum(indirect.diffuse.pixels.size() / 4);
  for (size_t i = 0; i < sum.size(); ++i)
    for (int c = 0; c < 3; ++c)
      sum[i][c] = double(indirect.diffuse.pixels[4 * i + c]) + indirect.glossy.pixels[4 * i + c];
  return sum;
}

std::vector<gpu::Vsgl> readVsgls(engine::Context& ctx, const gi::FrameOutput& output) {
  engine::Buffer buffer =
      engine::Buffer::borrow(output.vsgls, VkDeviceSize{output.vsglCount} * sizeof(gpu::Vsgl));
  return buffer.readbackAs<gpu::Vsgl>(ctx);
}

std::vector<glm::uvec2> readVsglViews(engine::Context& ctx, const gi::FrameOutput& output) {
  engine::Buffer buffer = engine::Buffer::borrow(
      output.vsglViews, VkDeviceSize{output.viewCount} * sizeof(gpu::VsglViewRange));
  std::vector<glm::uvec2> ranges;
  for (const gpu::VsglViewRange& r : buffer.readbackAs<gpu::VsglViewRange>(ctx))
    ranges.emplace_back(r.range.x, r.range.y);
  return ranges;
}

std::vector<float> readR32f(engine::Context& ctx, const gi::ImageRef& ref, uint32_t width,
                            uint32_t height, const char* what) {
  if (!ref.image) throw engine::Error(std::string("internal: the module wrote no ") + what);
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = VK_FORMAT_R32_SFLOAT;
  engine::Image image = engine::Image::borrow(ref.image, ref.view, desc, ref.layout);
  std::vector<std::byte> bytes = image.readback(ctx);
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
  return values;
}

void addInto(engine::ImageRgba32f& sum, const engine::ImageRgba32f& term) {
  for (size_t i = 0; i < sum.pixels.size(); ++i)
    if (i % 4 != 3) sum.pixels[i] += term.pixels[i];
}

}  // namespace samples
