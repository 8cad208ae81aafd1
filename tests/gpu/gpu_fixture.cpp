#include "gpu_fixture.h"

#include <cstring>

#include "engine/commands.h"
#include "engine/rasterizer.h"
#include "engine/scene_gpu.h"

namespace testing_gpu {
namespace {

struct Shared {
  std::unique_ptr<engine::Context> context;
  std::string reason;
  bool tried = false;
};

Shared& shared() {
  static Shared s;
  if (!s.tried) {
    s.tried = true;
    try {
      engine::ContextOptions options;
      options.validation = true;
      s.context = std::make_unique<engine::Context>(options);
    } catch (const engine::Error& e) {
      s.reason = e.what();
    }
  }
  return s;
}

}  // namespace

engine::Context* GpuTest::context() {
  return shared().context.get();
}
const std::string& GpuTest::skipReason() {
  return shared().reason;
}

void GpuTest::SetUp() {
  if (!context()) GTEST_SKIP() << "no usable Vulkan device: " << skipReason();
  messagesBefore_ = context()->validationMessageCount();
}

void GpuTest::TearDown() {
  if (!context()) return;
  auto messages = context()->validationMessages();
  EXPECT_EQ(context()->validationMessageCount(), messagesBefore_)
      << "validation layer messages during the test; last: "
      << (messages.empty() ? std::string("-") : messages.back());
}

engine::GBuffer GpuTest::renderGBuffer(const engine::SceneGpu& scene, const engine::View& view) {
  engine::GBuffer gbuffer = engine::createGBuffer(ctx(), view.width, view.height);
  engine::Rasterizer rasterizer(ctx());
  engine::GBufferResolve resolve(ctx());
  engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(view.width, view.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    rasterizer.record(cmd, scene, view.viewProj, {&visibility, 0, view.width, view.height});
    resolve.record(cmd, scene, visibility, view, gbuffer);
  });
  return gbuffer;
}

DirectFrame GpuTest::renderDirect(const engine::Scene& scene, const engine::View& view,
                                  const engine::DirectLightSettings& settings) {
  engine::SceneGpu gpuScene = engine::uploadScene(ctx(), scene);
  engine::Rasterizer rasterizer(ctx());
  engine::GBufferResolve resolve(ctx());
  engine::DirectLighting direct(ctx(), scene, settings);
  engine::GBuffer g = engine::createGBuffer(ctx(), view.width, view.height);
  engine::Buffer visibility(ctx(), engine::Rasterizer::visibilityBytes(view.width, view.height),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
  engine::ImageDesc desc;
  desc.width = view.width;
  desc.height = view.height;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  engine::Image radiance(ctx(), desc);
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    engine::imageBarrier(cmd, radiance, VK_IMAGE_LAYOUT_GENERAL);
    rasterizer.record(cmd, gpuScene, view.viewProj, {&visibility, 0, view.width, view.height});
    resolve.record(cmd, gpuScene, visibility, view, g);
    direct.record(cmd, gpuScene, rasterizer, g, view, radiance);
  });
  DirectFrame out;
  out.gbuffer = engine::readbackGBuffer(ctx(), g);
  auto bytes = radiance.readback(ctx());
  out.radiance.resize(bytes.size() / sizeof(glm::vec4));
  std::memcpy(out.radiance.data(), bytes.data(), bytes.size());
  return out;
}

void GpuTest::pokeMaterials(engine::GBuffer& gbuffer, const std::vector<MaterialPoke>& pokes) {
  std::vector<std::byte> diffuse = gbuffer.diffuse.readback(ctx());
  std::vector<std::byte> specular = gbuffer.specular.readback(ctx());
  for (const MaterialPoke& p : pokes) {
    auto* texel = reinterpret_cast<uint16_t*>((p.specular ? specular : diffuse).data()) +
                  (size_t{p.pixel.y} * gbuffer.width + p.pixel.x) * 4;
    for (int c = p.first; c <= p.last; ++c) texel[c] = p.bits;
  }
  gbuffer.diffuse.upload(ctx(), diffuse.data(), diffuse.size());
  gbuffer.specular.upload(ctx(), specular.data(), specular.size());
  ctx().submitAndWait([&](VkCommandBuffer cmd) {
    engine::imageBarrier(cmd, gbuffer.diffuse, VK_IMAGE_LAYOUT_GENERAL);
    engine::imageBarrier(cmd, gbuffer.specular, VK_IMAGE_LAYOUT_GENERAL);
  });
}

}  // namespace testing_gpu
