#include "gpu_fixture.h"

#include "engine/rasterizer.h"

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

}  // namespace testing_gpu
