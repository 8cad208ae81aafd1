// The public API's implementation: the frame graph of the module, recorded into the host's
// command buffer (docs/architecture.md "data flow"):
//   [BRSM stage A: importance VSGLs from the host G-buffer] -> RSM (light-view raster, flux) ->
//   attribute pyramids -> [BRSM stage B: view-dependent PDF] -> VSGL generation -> [ISM build]
//   -> shading -> [debug visibility].
#include "gi/indirect_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/commands.h"
#include "engine/raster_clusters.h"
#include "engine/rasterizer.h"
#include "frame_reuse.h"
#include "light_validation.h"
#include "passes/adaptive_shading.h"
#include "passes/brsm_pdf.h"
#include "passes/env_fis.h"
#include "passes/env_map.h"
#include "passes/env_sg.h"
#include "passes/gbuffer_convert.h"
#include "passes/ism.h"
#include "passes/kmeans.h"
#include "passes/vsgl_allocation.h"
#include "passes/vsgl_shade.h"
#include "shared/scene_data.h"
#include "shared/vsgl_shade.h"

namespace gi {
namespace {

// Timed scopes per frame: about 12 fixed passes, per light view (a point light has six) 5 more
// and 3 per k-means iteration (64 at most).
constexpr uint32_t kProfilerScopes = 16 + kCubeFaces * (5 + 3 * 64);

// Settings that size resources; setSettings refuses to change them.
bool sameCreationFields(const Settings& a, const Settings& b) {
  return a.rsmSize == b.rsmSize && a.maxVsglCount == b.maxVsglCount &&
         a.brsm.importanceCount == b.brsm.importanceCount && a.brsm.gridSize == b.brsm.gridSize &&
         a.ism.mapSize == b.ism.mapSize && a.ism.pointCount == b.ism.pointCount &&
         a.ism.pointsPerVsgl == b.ism.pointsPerVsgl && a.ism.depthBias == b.ism.depthBias &&
         a.ism.slopeBias == b.ism.slopeBias && a.ism.centreOffset == b.ism.centreOffset &&
         a.ism.pcf == b.ism.pcf && a.environment.mapSize == b.environment.mapSize;
}

// The methods whose VSGLs VsglGenerator writes (filtered sampling and its point rule).
bool filtered(VsglMethod method) {
  return method == VsglMethod::FilteredImportanceSampling || method == VsglMethod::Vpl;
}

engine::Light engineLight(const Light& light) {
  engine::Light l;
  l.name = "FrameInput.light";
  l.type = light.type == Light::Type::Spot          ? engine::LightType::Spot
           : light.type == Light::Type::Directional ? engine::LightType::Directional
                                                    : engine::LightType::Point;
  l.position = light.position;
  // A point light has no direction: one it does not read may be anything, even zero.
  const float length = glm::length(light.direction);
  l.direction = length > 0.0f ? light.direction / length : glm::vec3(0.0f, 0.0f, -1.0f);
  l.color = light.color;
  l.intensity = light.intensity;
  l.innerConeAngle = light.innerConeAngle;
  l.outerConeAngle = light.outerConeAngle;
  l.range = light.range;
  return l;
}

// Whether a spot's or point light's range window (zero from `range` on) ends before the nearest
// point of the scene's box: then no surface receives its light, direct or bounced.
bool rangeEndsBeforeScene(const Light& light, const engine::Bounds& bounds) {
  if (light.type == Light::Type::Directional || !(light.range > 0.0f)) return false;
  const glm::vec3 nearest = glm::clamp(light.position, bounds.min, bounds.max);
  return glm::length(nearest - light.position) >= light.range;
}

engine::Image borrowImage(const ImageRef& ref, uint32_t width, uint32_t height, VkFormat format) {
  engine::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  return engine::Image::borrow(ref.image, ref.view, desc, ref.layout);
}

// The host's G-buffer images move from the layouts it handed in to GENERAL, after whatever
// stage wrote them (the host may have rasterised them with graphics pipelines).
void acquireHostImages(VkCommandBuffer cmd, engine::GBuffer& g, bool depthAspect) {
  std::vector<VkImageMemoryBarrier2> barriers;
  for (engine::Image* image : {&g.depth, &g.normal, &g.diffuse, &g.specular}) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    b.oldLayout = image->layout();
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image->handle();
    const bool depth = depthAspect && image == &g.depth;
    b.subresourceRange = {depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0,
                          1};
    barriers.push_back(b);
    image->setLayout(VK_IMAGE_LAYOUT_GENERAL);
  }
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = static_cast<uint32_t>(barriers.size());
  dep.pImageMemoryBarriers = barriers.data();
  vkCmdPipelineBarrier2(cmd, &dep);
}

// A borrowed handle on one of the module's own images (GENERAL), to stand in a GBuffer.
engine::Image borrowOwn(const engine::Image& image) {
  return engine::Image::borrow(image.handle(), image.view(), image.desc(), image.layout());
}

Status failure(const std::string& message) {
  return {false, message};
}

}  // namespace

// One RSM view, the light it sees and what its RSM and pyramids are made from.
struct LightView {
  RsmView view;
  engine::Light light;
  uint32_t lightIndex = 0;  // in FrameInput::lights
  LightViewInputs inputs;
};

struct IndirectLighting::Impl {
  Impl(const DeviceHandles& device, const Settings& s, uint32_t w, uint32_t h)
      : ctx({device.instance, device.physicalDevice, device.device, device.queueFamily,
             device.enabledFeatures}),
        settings(s),
        maxCount(s.maxVsglCount ? s.maxVsglCount : s.vsglCount),
        width(w),
        height(h),
        rasterizer(ctx),
        clusterBounds(ctx),
        resolve(ctx),
        mips(ctx),
        rsm(ctx, s.rsmSize),
        attributes(ctx, s.rsmSize),
        allocation(ctx),
        generator(ctx, maxCount),
        ism(ctx, s.ism, maxCount),
        shade(ctx),
        adaptive(ctx, w, h),
        indirect(createIndirectImages(ctx, w, h)),
        profiler(ctx, kProfilerScopes) {
    if (s.pdf == PdfKind::Brsm) createBrsm();
  }

  void createBrsm() {
    importance.emplace(ctx, width, height, settings.brsm.importanceCount);
    brsmPdf.emplace(ctx, settings.rsmSize, settings.brsm.gridSize);
  }

  void record(VkCommandBuffer cmd, const FrameInput& in, FrameOutput& out);
  // Every pass of a frame that bounces light, in order, less those whose inputs are as when
  // they last ran (frame_reuse.h); returns the frame's VSGLs.
  const engine::Buffer& recordPasses(VkCommandBuffer cmd, engine::GBuffer& gbuffer,
                                     const engine::View& camera,
                                     const std::vector<LightView>& views, uint32_t rule,
                                     const CameraInputs& cameraIn, const SceneInputs& sceneIn);
  // FramePlan::Reuse::reasons: what this frame kept from earlier ones.
  std::vector<std::string> reuseReasons(const FrameInput& in, size_t viewCount) const;
  // Both outputs cleared to black, visible to the host's next reads like the shaded ones.
  void recordBlackOutputs(VkCommandBuffer cmd);
  // The VSGLs of this frame: sampled with FIS or clustered with k-means.
  // `count` of them from record `first` on, from one view of the light (`several`: the light has
  // more than one, whose clusters must not start from each other's k-means centres).
  void recordVsgls(VkCommandBuffer cmd, const RsmView& rsmView, uint32_t rule, uint32_t first,
                   uint32_t count, bool several);
  // The buffer recordVsgls writes with the frame's method.
  const engine::Buffer& vsglBuffer() const;
  // View v's attribute pyramids.
  VsglAttributes& attributesOf(uint32_t v) {
    if (v == 0) return attributes;
    while (moreAttributes.size() < v)
      moreAttributes.push_back(std::make_unique<VsglAttributes>(ctx, settings.rsmSize));
    return *moreAttributes[v - 1];
  }
  // View v's light-view buffer, created with the first frame that has the view.
  const engine::Buffer& lightViewMap(uint32_t v) {
    while (lightViewMaps.size() <= v) {
      lightViewMaps.emplace_back(
          ctx, engine::Rasterizer::visibilityBytes(settings.rsmSize, settings.rsmSize),
          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::GpuOnly);
      lightViewMapInputs.emplace_back();
    }
    return lightViewMaps[v];
  }
  // The environment's conversion (when it changed) and shading into `environmentImages`.
  void recordEnvironment(VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera);

  engine::Context ctx;
  Settings settings;
  uint32_t maxCount;
  uint32_t width, height;
  std::optional<engine::SceneGpu> scene;
  engine::Bounds bounds;
  float maxReflectance = 1.0f;  // SceneGeometry::maxReflectance
  bool canOcclude = true;       // SceneGeometry::canOcclude
  float maxSpecular = 1.0f;     // SceneGeometry::maxSpecular
  FramePlan plan;               // of the last recorded frame
  engine::Rasterizer rasterizer;
  engine::ClusterBounds clusterBounds;  // the boxes the RSM's raster culls with
  engine::GBufferResolve resolve;
  MipPyramid mips;
  ReflectiveShadowMap rsm;
  // Each RSM view's rasterized light view (FrameOutput::lightViews) and the inputs it was
  // rasterized from (none: not yet, or another view's since).
  std::vector<engine::Buffer> lightViewMaps;
  std::vector<std::optional<LightViewInputs>> lightViewMapInputs;
  VsglAttributes attributes;  // of view 0
  // Of views 1.. (a point light's other faces, the other lights), created as frames need them:
  // every view's pyramids live until the VSGLs are shared among the views.
  std::vector<std::unique_ptr<VsglAttributes>> moreAttributes;
  VsglAllocation allocation;
  VsglGenerator generator;
  std::optional<KmeansClustering> kmeans;     // created with the first k-means frame
  std::optional<ImportanceVsgls> importance;  // BRSM stage A, created with the first Brsm frame
  std::optional<BrsmPdf> brsmPdf;             // BRSM stage B
  Ism ism;                                    // always built: ismEnabled may change per frame
  bool ismPointsStale = true;  // the scene changed since the point pool was generated
  VsglShade shade;
  AdaptiveShading adaptive;
  IndirectImages indirect;
  std::optional<engine::Image> debugVisibility;  // created with the first debug frame
  std::optional<GBufferConvert> converter;       // created with the first converted frame
  // Environment lighting: created together by the first setEnvironment; `environmentSet` is
  // false again after setEnvironment with width 0.
  std::optional<EnvironmentMap> environmentMap;
  std::optional<EnvFisShade> environmentShade;
  std::optional<EnvSgLights> environmentLights;
  std::optional<IndirectImages> environmentImages;
  bool environmentSet = false;
  // The SG lights' count and K when they were generated (0: not since the last conversion).
  uint32_t lightsCount = 0;
  float lightsKernelScale = 0.0f;
  // Reuse across frames (frame_reuse.h): the stages' inputs when they last ran, and the counts
  // that tell a changed scene or environment from a kept one.
  LastInputs last;
  uint64_t frameCount = 0, sceneSerial = 0, environmentSerial = 0;
  engine::GpuProfiler profiler;
};

namespace {

// The effect planner (docs/integration.md, "The effect planner"): which passes this frame needs.
// Each decision leaves out only work whose result is exactly zero or never read.
FramePlan planFrame(const Settings& s, const std::vector<Light>& lights,
                    const engine::Bounds& bounds, float maxReflectance, float maxSpecular,
                    bool canOcclude, bool environment, bool environmentChanged) {
  FramePlan plan;
  plan.environment = environment;
  plan.environmentConverted = environment && environmentChanged;
  plan.visibility = s.ismEnabled;
  plan.glossy = s.glossy;
  const bool points = s.method == VsglMethod::Vpl;  // point lights: no adaptive pyramid or bounds
  plan.adaptive = s.adaptive.enabled && !points;
  plan.culled = s.culling.enabled && !points;
  plan.skySkipped = s.planner.skipSky && !plan.adaptive;  // adaptive shading never queues sky
  if (!s.ismEnabled) {
    plan.reasons.push_back("ism: off in the settings: no ISM build or test");
  } else if (s.planner.skipWithoutOccluders && !canOcclude) {
    plan.visibility = false;
    plan.reasons.push_back(
        "ism: nothing can occlude (SceneGeometry.canOcclude = false): no ISM build or test");
  }
  if (!s.glossy) plan.reasons.push_back("glossy: off in the settings: no glossy shading");
  if (s.planner.skipGlossyWithoutSpecular && !(maxSpecular > 0.0f)) {
    plan.glossy = plan.specularLobes = false;
    plan.reasons.push_back(
        "glossy: no surface has a specular lobe (SceneGeometry.maxSpecular = 0): no specular VSGL "
        "lobes, specular attribute mips or glossy shading");
  } else if (s.planner.skipGlossyWithoutSpecular && s.glossy && plan.adaptive) {
    plan.reasons.push_back("glossy: texels with F0 = F90 = 0 are shaded without the glossy term");
  }
  if (plan.skySkipped)
    plan.reasons.push_back("sky: subgroups that see only sky skip the VSGL loop");
  if (points && (s.adaptive.enabled || s.culling.enabled))
    plan.reasons.push_back(
        "vpl: the VPL baseline shades every pixel with every VPL: no adaptive shading or culling");
  if (plan.adaptive)
    plan.reasons.push_back("adaptive: shaded from level " +
                           std::to_string(s.adaptive.coarsestLevel) +
                           " down, interpolated where surface, material and light agree; sky "
                           "never shaded");
  if (plan.culled) {
    char budget[32];
    std::snprintf(budget, sizeof(budget), "%g", s.culling.budget);
    plan.reasons.push_back(
        std::string("culling: per subgroup, VSGLs whose bounds add up to at most ") + budget +
        " of the pixels' light are skipped");
  }
  // Before the bounce decision, whose reason comes last.
  if (!environment)
    plan.reasons.push_back("environment: none set (setEnvironment): no environment passes");
  else if (!environmentChanged)
    plan.reasons.push_back("environment: unchanged since its conversion: not converted again");
  // Per light: one without power, or whose range ends before the scene, reflects exactly nothing.
  const bool one = lights.size() == 1;
  const std::string whole = ": no RSM, PDF, VSGL, ISM or shading pass; black outputs";
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const float power = light.intensity * std::max({light.color.r, light.color.g, light.color.b});
    const std::string name = one ? "light: " : "light " + std::to_string(i) + ": ";
    const std::string field =
        one ? "FrameInput.lights[0]" : "FrameInput.lights[" + std::to_string(i) + "]";
    if (s.planner.skipWithoutBounce && !(power > 0.0f))
      plan.reasons.push_back(name + "no power (intensity x colour = 0)" +
                             (one ? whole : ": no RSM"));
    else if (s.planner.skipWithoutBounce && rangeEndsBeforeScene(light, bounds))
      plan.reasons.push_back(name + "its range ends before the scene's bounds (" + field +
                             ".range)" + (one ? whole : ": no RSM"));
    else
      plan.lights.push_back(i);
  }
  if (lights.empty()) {
    plan.bounce = false;
    plan.reasons.push_back("lights: none in FrameInput.lights" + whole);
  } else if (plan.lights.empty()) {
    plan.bounce = false;
    if (!one) plan.reasons.push_back("lights: none can bounce" + whole);
  } else if (s.planner.skipWithoutBounce && !(maxReflectance > 0.0f)) {
    plan.bounce = false;
    plan.reasons.push_back(
        "scene: no surface reflects (SceneGeometry.maxReflectance = 0): no RSM, PDF, VSGL, ISM "
        "or shading pass; black outputs");
  }
  for (uint32_t i : plan.lights)
    if (plan.bounce && lights[i].type == Light::Type::Point)
      plan.reasons.push_back(std::string(one ? "light: " : "light " + std::to_string(i) + ": ") +
                             "a point light: six cube-face RSMs of rsmSize^2, rendered one after "
                             "another, sharing the N VSGLs with the other views by their power");
  if (!plan.bounce) plan.lights.clear();
  if (!plan.bounce)
    plan.visibility = plan.glossy = plan.specularLobes = plan.skySkipped = plan.adaptive =
        plan.culled = false;
  return plan;
}

}  // namespace

void IndirectLighting::Impl::record(VkCommandBuffer cmd, const FrameInput& in, FrameOutput& out) {
  const GBufferImages& g = in.gbuffer;
  if (g.width != width || g.height != height)
    throw engine::Error("FrameInput.gbuffer: " + std::to_string(g.width) + "x" +
                        std::to_string(g.height) + " differs from the " + std::to_string(width) +
                        "x" + std::to_string(height) + " this instance was created for (recreate)");
  for (const ImageRef* ref : {&g.depth, &g.normal, &g.diffuse, &g.specular})
    if (!ref->image || !ref->view || ref->layout == VK_IMAGE_LAYOUT_UNDEFINED)
      throw engine::Error(
          "FrameInput.gbuffer: every image needs its VkImage, VkImageView and current layout "
          "(not UNDEFINED)");
  if (g.depthEncoding > DepthEncoding::ViewDistance)
    throw engine::Error(
        "FrameInput.gbuffer.depthEncoding: " + std::to_string(uint32_t(g.depthEncoding)) +
        " is none of Ndc, ReversedNdc, ViewDistance");
  if (g.normalEncoding > NormalEncoding::WorldUnsigned)
    throw engine::Error(
        "FrameInput.gbuffer.normalEncoding: " + std::to_string(uint32_t(g.normalEncoding)) +
        " is none of Octahedral, WorldSigned, WorldUnsigned");
  if (g.depthFormat != VK_FORMAT_R32_SFLOAT && g.depthFormat != VK_FORMAT_D32_SFLOAT)
    throw engine::Error("FrameInput.gbuffer.depthFormat: " + std::to_string(g.depthFormat) +
                        " is neither VK_FORMAT_R32_SFLOAT nor VK_FORMAT_D32_SFLOAT");
  if (in.lights.size() > kMaxLights)
    throw engine::Error("FrameInput.lights: " + std::to_string(in.lights.size()) +
                        " lights, more than kMaxLights = " + std::to_string(kMaxLights));
  for (size_t i = 0; i < in.lights.size(); ++i)
    if (std::string bad =
            validateLight(in.lights[i], "FrameInput.lights[" + std::to_string(i) + "]");
        !bad.empty())
      throw engine::Error(bad);
  if (!scene) throw engine::Error("IndirectLighting::record: setScene was not called");
  if (settings.pdf == PdfKind::Brsm && !importance) createBrsm();

  engine::GBuffer gbuffer;
  gbuffer.width = width;
  gbuffer.height = height;
  gbuffer.depth = borrowImage(g.depth, width, height, g.depthFormat);
  gbuffer.normal = borrowImage(g.normal, width, height, VK_FORMAT_R16G16_SNORM);
  // Another encoding than the module's: converted first (GBufferConvert), into its own images.
  const bool convert = g.depthEncoding != DepthEncoding::Ndc ||
                       g.depthFormat != VK_FORMAT_R32_SFLOAT ||
                       g.normalEncoding != NormalEncoding::Octahedral;
  if (convert && !converter) converter.emplace(ctx, width, height);
  gbuffer.diffuse = borrowImage(g.diffuse, width, height, VK_FORMAT_R16G16B16A16_SFLOAT);
  gbuffer.specular = borrowImage(g.specular, width, height, VK_FORMAT_R16G16B16A16_SFLOAT);

  // The module works with forward depth: a reversed-Z projection's clip z becomes w - z.
  glm::mat4 proj = in.camera.proj;
  if (g.depthEncoding == DepthEncoding::ReversedNdc) {
    glm::mat4 flip(1.0f);
    flip[2][2] = -1.0f;
    flip[3][2] = 1.0f;
    proj = flip * proj;
  }
  const engine::View camera = engine::makeView(in.camera.view, proj, width, height);
  const uint32_t rule = static_cast<uint32_t>(settings.rule);

  plan = planFrame(settings, in.lights, bounds, maxReflectance, maxSpecular, canOcclude,
                   environmentSet, environmentSet && environmentMap->pending());
  ++frameCount;
  if (!settings.reuse) last = {};
  const CameraInputs cameraIn = cameraInputs(in, frameCount);
  const SceneInputs sceneIn = sceneInputs(sceneSerial, in, frameCount);
  // The RSM views of the lights that bounce, in order, each with its light.
  std::vector<LightView> views;
  for (uint32_t i : plan.lights) {
    const engine::Light light = engineLight(in.lights[i]);
    uint32_t face = 0;
    for (const RsmView& view : makeRsmViews(bounds, light, settings.rsmSize))
      views.push_back({view,
                       light,
                       i,
                       {sceneIn, in.lights[i], face++, plan.specularLobes,
                        settings.broadReflections, settings.pdf}});
  }

  // Every view's pyramids exist before the deferred setup that gives new images their layout.
  if (views.size() > 1 && filtered(settings.method))
    attributesOf(static_cast<uint32_t>(views.size() - 1));
  ctx.recordDeferredSetup(cmd);
  profiler.beginFrame(cmd);
  const engine::Buffer* vsgls = nullptr;  // this frame's, from filtered sampling or k-means
  {
    engine::ProfileScope frame(&profiler, cmd, "frame");
    acquireHostImages(cmd, gbuffer, g.depthFormat == VK_FORMAT_D32_SFLOAT);
    // What earlier frames wrote and this one keeps becomes visible to its reads (their own
    // last barriers cover it too; this one does not rely on how they ended).
    engine::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    plan.reuse.gbuffer = convert && last.converted == cameraIn;
    if (!convert) last.converted.reset();
    if (convert && !plan.reuse.gbuffer) {
      last.converted = cameraIn;
      gpu::GBufferConvertPush push{};
      push.depthRow = glm::vec4(proj[2][2], proj[3][2], proj[2][3], proj[3][3]);
      push.viewport = {width, height};
      push.depthEncoding = static_cast<uint32_t>(g.depthEncoding);
      push.normalEncoding = static_cast<uint32_t>(g.normalEncoding);
      converter->record(cmd, gbuffer.depth, gbuffer.normal, push, &profiler);
    }
    if (convert) {
      gbuffer.depth = borrowOwn(converter->depth());
      gbuffer.normal = borrowOwn(converter->normal());
    }
    if (plan.bounce) {
      vsgls = &recordPasses(cmd, gbuffer, camera, views, rule, cameraIn, sceneIn);
      // The outputs, written by compute, become visible to whatever the host does next.
      engine::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
    } else {
      const ShadingInputs black{};  // black outputs depend on nothing
      plan.reuse.shading = last.shading == black;
      if (!plan.reuse.shading) recordBlackOutputs(cmd);
      last.shading = black;
    }
    if (plan.environment) {
      const EnvironmentInputs environmentIn{cameraIn, environmentSerial, settings.environment};
      plan.reuse.environment = last.environment == environmentIn;
      if (!plan.reuse.environment) recordEnvironment(cmd, gbuffer, camera);
      last.environment = environmentIn;
    }
  }
  plan.reuse.reasons = reuseReasons(in, views.size());

  out = {};
  out.indirectDiffuse = {indirect.diffuse.handle(), indirect.diffuse.view(),
                         indirect.diffuse.layout()};
  out.indirectGlossy = {indirect.glossy.handle(), indirect.glossy.view(), indirect.glossy.layout()};
  if (plan.environment) {
    const IndirectImages& e = *environmentImages;
    out.environmentDiffuse = {e.diffuse.handle(), e.diffuse.view(), e.diffuse.layout()};
    out.environmentGlossy = {e.glossy.handle(), e.glossy.view(), e.glossy.layout()};
  }
  if (vsgls && plan.adaptive) {
    engine::Image& levels = adaptive.levelMap();
    out.shadingLevels = {levels.handle(), levels.view(), levels.layout()};
  }
  if (vsgls && settings.debugVsgl >= 0)
    out.debugVisibility = {debugVisibility->handle(), debugVisibility->view(),
                           debugVisibility->layout()};
  // No bounce: no VSGLs this frame (the buffer is still a valid handle).
  out.vsgls = (vsgls ? *vsgls : generator.vsgls()).handle();
  out.vsglCount = vsgls ? settings.vsglCount : 0;
  out.vsglViews = allocation.ranges().handle();
  out.viewCount = vsgls ? static_cast<uint32_t>(views.size()) : 0;
  for (uint32_t v = 0; v < out.viewCount; ++v) {
    if (v >= lightViewMapInputs.size() || lightViewMapInputs[v] != views[v].inputs) continue;
    const LightViewInputs& i = views[v].inputs;
    out.lightViews.push_back({views[v].lightIndex, i.face, settings.rsmSize,
                              views[v].view.view.viewProj, lightViewMaps[v].handle(), 0});
  }
  out.gbufferLayout = VK_IMAGE_LAYOUT_GENERAL;
}

const engine::Buffer& IndirectLighting::Impl::recordPasses(
    VkCommandBuffer cmd, engine::GBuffer& gbuffer, const engine::View& camera,
    const std::vector<LightView>& views, uint32_t rule, const CameraInputs& cameraIn,
    const SceneInputs& sceneIn) {
  const bool brsm = settings.pdf == PdfKind::Brsm;
  const auto viewCount = static_cast<uint32_t>(views.size());
  // With several views (a point light's faces, several lights) filtered sampling shares the N
  // VSGLs among them on the GPU by their importance-weighted power, each view keeping its own
  // pyramids; k-means, whose passes size their dispatches with K on the host, gives each view
  // N / views in turn through the same pyramids (docs/techniques/point-lights.md).
  const bool shared = viewCount > 1 && filtered(settings.method);
  const bool ownPyramids = viewCount == 1 || shared;
  // Temporal k-means starts from the last frame's centres: its VSGLs change in every frame,
  // so neither they nor what is made from them are kept.
  const bool evolving = !filtered(settings.method) && settings.kmeans.temporal;

  VsglInputs vsglIn{{},
                    std::nullopt,
                    settings.vsglCount,
                    settings.kernelScale,
                    settings.rule,
                    settings.pdf,
                    settings.method,
                    settings.kmeans,
                    settings.brsm,
                    settings.surfaceTolerance};
  for (const LightView& v : views) vsglIn.views.push_back(v.inputs);
  if (brsm)
    vsglIn.importance = {cameraIn, settings.brsm.importanceCount, settings.rule, plan.specularLobes,
                         settings.broadReflections};
  plan.reuse.vsgls = !evolving && last.vsgls == vsglIn;
  if (plan.reuse.vsgls) {  // and with them all they are made from
    plan.reuse.importance = brsm;
    plan.reuse.lightViews = viewCount;
  } else {
    // [S3] generates the importance VSGLs with the rule under test and K = 1.
    plan.reuse.importance = brsm && last.importance == vsglIn.importance;
    if (brsm && !plan.reuse.importance) {
      // The importance VSGLs keep their kernels as sized: kept on their surfaces they flickered
      // more under a moving camera for little accuracy (docs/techniques/vsgl-generation.md).
      importance->record(cmd, gbuffer, camera, {settings.brsm.importanceCount, 1.0f, rule}, mips,
                         &profiler, plan.specularLobes, settings.broadReflections);
      last.importance = vsglIn.importance;
    }
    // One RSM at a time, each view with its attribute pyramids and PDF.
    if (last.views.size() < viewCount) last.views.resize(viewCount);
    std::vector<glm::uvec2> hostRanges;
    for (uint32_t v = 0, first = 0; v < viewCount; ++v) {
      const uint32_t count =
          settings.vsglCount / viewCount + (v < settings.vsglCount % viewCount ? 1u : 0u);
      if (!shared) hostRanges.emplace_back(first, count);
      if (count == 0 && !shared) continue;
      VsglAttributes& pyramids = attributesOf(shared ? v : 0);
      const RsmView& view = views[v].view;
      std::optional<LightViewInputs>& kept = last.views[shared ? v : 0];
      if (ownPyramids && kept == views[v].inputs) {
        ++plan.reuse.lightViews;
      } else {
        if (last.clusterBounds != sceneIn) {  // the geometry changed, or may have
          clusterBounds.record(cmd, *scene, &profiler);
          last.clusterBounds = sceneIn;
        }
        rsm.record(cmd, *scene, rasterizer, resolve, view, views[v].light, &profiler,
                   &lightViewMap(v));
        lightViewMapInputs[v] = views[v].inputs;
        pyramids.record(cmd, rsm.vpls(), rsm.surface(), view, mips, &profiler, plan.specularLobes,
                        settings.broadReflections);
        kept = views[v].inputs;
        if (!ownPyramids) kept.reset();  // the next view overwrites them
      }
      // BRSM's PDF is written over the pyramids' PDF channel from their power channels, which
      // it leaves as they are: it can run again on kept pyramids.
      if (brsm)
        brsmPdf->record(cmd, pyramids, view, importance->vsgls(), settings.brsm, mips, &profiler,
                        plan.specularLobes);
      if (shared) {
        allocation.recordWeight(cmd, v, pyramids, brsm ? &brsmPdf->cells() : nullptr);
      } else {
        recordVsgls(cmd, view, rule, first, count, viewCount > 1);
        first += count;
      }
    }
    if (!shared) allocation.recordRanges(cmd, hostRanges);
    if (shared) {
      allocation.recordAllocate(cmd, viewCount, settings.vsglCount,
                                brsm ? settings.brsm.fluxMix : 1.0f, &profiler);
      const uint32_t generation = settings.method == VsglMethod::Vpl ? VSGL_RULE_POINT : rule;
      for (uint32_t v = 0; v < viewCount; ++v)
        generator.recordRanged(
            cmd, attributesOf(v), views[v].view,
            {settings.vsglCount, settings.kernelScale, generation, 0, settings.surfaceTolerance},
            allocation.ranges(), v, &profiler);
    }
    last.vsgls = vsglIn;
  }
  const engine::Buffer* vsgls = &vsglBuffer();
  // The maps are built for the shading's visibility or for the debug view, whichever asks.
  const bool isms = plan.visibility || settings.debugVsgl >= 0;
  if (isms) {
    const IsmInputs ismIn{vsglIn, sceneIn};
    plan.reuse.isms = !evolving && last.isms == ismIn;
    plan.reuse.ismPositions = plan.reuse.isms;
    if (!plan.reuse.isms) {
      if (ismPointsStale) ism.recordPoints(cmd, *scene, &profiler);
      ismPointsStale = false;
      const IsmPositionInputs positionIn{sceneIn, settings.vsglCount};
      plan.reuse.ismPositions = last.ismPositions == positionIn;
      if (!plan.reuse.ismPositions) ism.recordPositions(cmd, *scene, settings.vsglCount, &profiler);
      ism.recordSplat(cmd, *vsgls, settings.vsglCount, &profiler);
      ism.recordPullPush(cmd, settings.vsglCount, &profiler);
      last.ismPositions = positionIn;
      last.isms = ismIn;
    }
  }
  const ShadingInputs shadingIn{vsglIn, isms, cameraIn, sceneIn, settings};
  plan.reuse.shading = !evolving && last.shading == shadingIn;
  last.shading = shadingIn;
  if (plan.reuse.shading) return *vsgls;
  const uint32_t flags =
      (plan.glossy ? VSGL_SHADE_GLOSSY : 0u) | (plan.visibility ? VSGL_SHADE_VISIBILITY : 0u) |
      (plan.skySkipped ? VSGL_SHADE_SKIP_SKY : 0u) |
      (plan.specularLobes ? 0u : VSGL_SHADE_DIFFUSE_LOBES) | (plan.culled ? VSGL_SHADE_CULL : 0u) |
      (settings.planarEmitters ? VSGL_SHADE_PLANAR : 0u);
  VsglShade::Inputs shading{vsgls, settings.vsglCount, flags, &ism.atlas(), ism.params()};
  shading.cullBudget = settings.culling.budget;
  shading.points = settings.method == VsglMethod::Vpl;
  if (plan.culled) shade.recordStatsReset(cmd);
  if (plan.adaptive)
    adaptive.record(cmd, gbuffer, camera, shading, settings.adaptive,
                    plan.glossy && settings.planner.skipGlossyWithoutSpecular, shade, indirect,
                    &profiler);
  else
    shade.record(cmd, gbuffer, camera, shading, indirect, &profiler);
  if (plan.culled) shade.recordStatsReadback(cmd);
  if (settings.debugVsgl >= 0) {
    if (!debugVisibility) {
      engine::ImageDesc desc;
      desc.width = width;
      desc.height = height;
      desc.format = VK_FORMAT_R32_SFLOAT;
      debugVisibility.emplace(ctx, desc);  // recordVisibility gives it its first layout
    }
    ism.recordVisibility(cmd, gbuffer, camera, *vsgls, static_cast<uint32_t>(settings.debugVsgl),
                         *debugVisibility, &profiler);
  }
  return *vsgls;
}

std::vector<std::string> IndirectLighting::Impl::reuseReasons(const FrameInput& in,
                                                              size_t viewCount) const {
  std::vector<std::string> lines;
  if (!settings.reuse) return {"reuse: off in the settings: every pass runs in every frame"};
  if (in.gbufferGeneration == 0)
    lines.push_back(
        "reuse: FrameInput.gbufferGeneration = 0 (not known): the G-buffer counts as changed in "
        "every frame");
  if (in.sceneGeneration == 0)
    lines.push_back(
        "reuse: FrameInput.sceneGeneration = 0 (not known): the geometry counts as changed in "
        "every frame");
  const FramePlan::Reuse& r = plan.reuse;
  if (r.gbuffer) lines.push_back("reuse: G-buffer unchanged: not converted again");
  if (r.vsgls) {
    lines.push_back(
        "reuse: lights, geometry, view importance and VSGL settings unchanged: VSGLs kept (no "
        "RSM, attribute, PDF or VSGL pass)");
  } else {
    if (r.importance) lines.push_back("reuse: G-buffer unchanged: BRSM importance VSGLs kept");
    if (r.lightViews > 0)
      lines.push_back("reuse: light and geometry unchanged for " + std::to_string(r.lightViews) +
                      " of " + std::to_string(viewCount) +
                      " RSM views: their RSM, flux and attribute pyramids kept");
  }
  if (r.isms)
    lines.push_back("reuse: VSGLs and geometry unchanged: ISMs kept");
  else if (r.ismPositions)
    lines.push_back("reuse: geometry and VSGL count unchanged: ISM point positions kept");
  if (r.shading)
    lines.push_back("reuse: nothing the shading reads changed: outputs kept (no shading pass)");
  if (r.environment) lines.push_back("reuse: G-buffer and environment unchanged: its outputs kept");
  if (plan.bounce && !filtered(settings.method) && settings.kmeans.temporal)
    lines.push_back(
        "reuse: temporal k-means starts from the last frame's centres: its VSGLs, ISMs and "
        "shading run in every frame");
  return lines;
}

void IndirectLighting::Impl::recordBlackOutputs(VkCommandBuffer cmd) {
  const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  engine::computeToTransferBarrier(cmd);
  for (engine::Image* image : {&indirect.diffuse, &indirect.glossy})
    vkCmdClearColorImage(cmd, image->handle(), VK_IMAGE_LAYOUT_GENERAL, &black, 1, &all);
  engine::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

void IndirectLighting::Impl::recordVsgls(VkCommandBuffer cmd, const RsmView& rsmView, uint32_t rule,
                                         uint32_t first, uint32_t count, bool several) {
  if (filtered(settings.method)) {
    const uint32_t generation = settings.method == VsglMethod::Vpl ? VSGL_RULE_POINT : rule;
    generator.record(cmd, attributes, rsmView,
                     {count, settings.kernelScale, generation, first, settings.surfaceTolerance},
                     &profiler);
    return;
  }
  if (!kmeans) kmeans.emplace(ctx, settings.rsmSize, maxCount);
  KmeansPassSettings k;
  k.clusters = count;
  k.iterations = settings.kmeans.iterations;
  k.space = settings.method == VsglMethod::KmeansImage ? KMEANS_SPACE_IMAGE : KMEANS_SPACE_WORLD;
  k.weighting = settings.kmeans.pdfWeighted ? KMEANS_WEIGHT_PDF : KMEANS_WEIGHT_UNIFORM;
  k.reuseCentres = settings.kmeans.temporal && !several;
  k.first = first;
  kmeans->record(cmd, attributes, rsmView, k, &profiler);
}

const engine::Buffer& IndirectLighting::Impl::vsglBuffer() const {
  return filtered(settings.method) ? generator.vsgls() : kmeans->vsgls();
}

IndirectLighting::IndirectLighting(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
IndirectLighting::~IndirectLighting() = default;

std::unique_ptr<IndirectLighting> IndirectLighting::create(const DeviceHandles& device,
                                                           const Settings& settings, uint32_t width,
                                                           uint32_t height, Status* status) {
  Status result;
  std::unique_ptr<IndirectLighting> lighting;
  if (std::string bad = validateSettings(settings); !bad.empty()) {
    result = failure(bad);
  } else if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    result = failure("IndirectLighting::create: G-buffer size " + std::to_string(width) + "x" +
                     std::to_string(height) + " is outside [1, 16384]");
  } else {
    try {
      lighting.reset(new IndirectLighting(std::make_unique<Impl>(device, settings, width, height)));
    } catch (const std::exception& e) {
      result = failure(e.what());
    }
  }
  if (status) *status = result;
  return lighting;
}

namespace {

// A buffer of `bytes` that must hold `count` elements of `size` bytes; empty when it does.
std::string bufferTooSmall(const char* field, VkDeviceSize bytes, uint64_t count, uint64_t size,
                           const char* counted) {
  if (bytes >= count * size) return {};
  return std::string("SceneGeometry.") + field + ": " + std::to_string(bytes) + " bytes, " +
         std::to_string(count) + " " + counted + " need " + std::to_string(count * size);
}

// The first value of `data` (`perTriangle` per triangle) at or past `limit`, named.
std::string outOfRange(const char* field, std::span<const uint32_t> data, uint32_t perTriangle,
                       uint32_t triangles, uint32_t limit, const char* what, const char* count) {
  if (data.empty()) return {};
  if (data.size() != uint64_t{triangles} * perTriangle)
    return std::string("SceneGeometry.") + field + ": " + std::to_string(data.size()) +
           " values, " + std::to_string(triangles) + " triangles need " +
           std::to_string(uint64_t{triangles} * perTriangle);
  for (size_t i = 0; i < data.size(); ++i)
    if (data[i] >= limit)
      return std::string("SceneGeometry.") + field + ": triangle " +
             std::to_string(i / perTriangle) + " names " + what + " " + std::to_string(data[i]) +
             ", past " + count + " " + std::to_string(limit);
  return {};
}

// setScene's checks of the host's buffers, in the order a reader meets the fields.
std::string validateGeometry(const SceneGeometry& s) {
  if (s.triangleCount == 0) return "SceneGeometry.triangleCount: 0 (nothing to light)";
  if (s.vertexCount == 0) return "SceneGeometry.vertexCount: 0 (the vertices' count is needed)";
  if (s.materialCount == 0)
    return "SceneGeometry.materialCount: 0 (the materials' count is needed)";
  for (const std::string& bad :
       {bufferTooSmall("vertexBytes", s.vertexBytes, s.vertexCount, sizeof(gpu::SceneVertex),
                       "vertices"),
        bufferTooSmall("indexBytes", s.indexBytes, s.triangleCount, 12, "triangles"),
        bufferTooSmall("triangleMaterialBytes", s.triangleMaterialBytes, s.triangleCount, 4,
                       "triangles"),
        bufferTooSmall("materialBytes", s.materialBytes, s.materialCount,
                       sizeof(gpu::SceneMaterial), "materials"),
        outOfRange("indexData", s.indexData, 3, s.triangleCount, s.vertexCount, "vertex",
                   "vertexCount"),
        outOfRange("triangleMaterialData", s.triangleMaterialData, 1, s.triangleCount,
                   s.materialCount, "material", "materialCount")})
    if (!bad.empty()) return bad;
  return {};
}

}  // namespace

Status IndirectLighting::setScene(const SceneGeometry& s) {
  if (!s.vertices || !s.indices || !s.triangleMaterials || !s.materials || !s.baseColorTextures ||
      !s.dataTextures || !s.sampler)
    return failure("SceneGeometry: every buffer, texture view and the sampler must be set");
  if (std::string bad = validateGeometry(s); !bad.empty()) return failure(bad);
  if (!glm::all(glm::lessThanEqual(s.boundsMin, s.boundsMax)))
    return failure("SceneGeometry.boundsMin: not below boundsMax on every axis");
  if (!(s.maxSpecular >= 0.0f && s.maxSpecular <= 1.0f))
    return failure("SceneGeometry.maxSpecular: " + std::to_string(s.maxSpecular) +
                   " is outside [0, 1]");
  if (!(s.maxReflectance >= 0.0f && s.maxReflectance <= 1.0f))
    return failure("SceneGeometry.maxReflectance: " + std::to_string(s.maxReflectance) +
                   " is outside [0, 1]");
  engine::SceneGpu scene;
  scene.vertices = engine::Buffer::borrow(s.vertices, s.vertexBytes);
  scene.indices = engine::Buffer::borrow(s.indices, s.indexBytes);
  scene.triangleMaterials = engine::Buffer::borrow(s.triangleMaterials, s.triangleMaterialBytes);
  scene.materials = engine::Buffer::borrow(s.materials, s.materialBytes);
  engine::ImageDesc array;
  array.arrayView = true;
  scene.baseColorTextures = engine::Image::borrow(VK_NULL_HANDLE, s.baseColorTextures, array,
                                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  scene.dataTextures = engine::Image::borrow(VK_NULL_HANDLE, s.dataTextures, array,
                                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  scene.sampler = engine::Sampler::borrow(s.sampler);
  scene.clusters = engine::createClusterBuffer(impl_->ctx, s.triangleCount);
  scene.triangleCount = s.triangleCount;
  scene.vertexCount = s.vertexCount;
  scene.materialCount = s.materialCount;
  scene.alphaCutouts = s.alphaCutouts;
  impl_->scene = std::move(scene);
  impl_->ismPointsStale = true;
  ++impl_->sceneSerial;
  impl_->bounds = {s.boundsMin, s.boundsMax};
  impl_->maxReflectance = s.maxReflectance;
  impl_->canOcclude = s.canOcclude;
  impl_->maxSpecular = s.maxSpecular;
  return {};
}

Status IndirectLighting::setSettings(const Settings& settings) {
  if (std::string bad = validateSettings(settings); !bad.empty()) return failure(bad);
  if (!sameCreationFields(settings, impl_->settings))
    return failure(
        "Settings: a creation field (rsmSize, maxVsglCount, brsm.importanceCount, "
        "brsm.gridSize, ism*, environment.mapSize) changed; create a new IndirectLighting instead");
  if (settings.vsglCount > impl_->maxCount)
    return failure("Settings.vsglCount: " + std::to_string(settings.vsglCount) +
                   " exceeds maxVsglCount " + std::to_string(impl_->maxCount));
  impl_->settings = settings;
  return {};
}

const Settings& IndirectLighting::settings() const {
  return impl_->settings;
}

void IndirectLighting::Impl::recordEnvironment(VkCommandBuffer cmd, engine::GBuffer& gbuffer,
                                               const engine::View& camera) {
  if (plan.environmentConverted) {
    environmentMap->record(cmd, &profiler);
    lightsCount = 0;
  }
  const EnvironmentSettings& e = settings.environment;
  if (e.method == EnvironmentMethod::SgLights) {
    // The lights depend on the environment, N and K only: generated again when one changed.
    if (lightsCount != e.sgLightCount || lightsKernelScale != e.sgKernelScale) {
      environmentLights->record(cmd, *environmentMap, e.sgLightCount, e.sgKernelScale, &profiler);
      lightsCount = e.sgLightCount;
      lightsKernelScale = e.sgKernelScale;
    }
    environmentLights->shade(cmd, gbuffer, camera, *environmentImages, &profiler);
  } else {
    EnvFisShade::Inputs in;
    in.map = &environmentMap->map();
    in.sampler = environmentMap->sampler().handle();
    in.mapSize = environmentMap->size();
    in.levels = environmentMap->levels();
    in.sh = &environmentMap->sh();
    in.sampleCount = e.sampleCount;
    in.mode = static_cast<EnvFisShade::Mode>(e.sampling);
    in.brdf = static_cast<EnvFisShade::Brdf>(e.brdf);
    in.wardAnisotropy = e.wardAnisotropy;
    in.kernelExtent = e.kernelScale;
    environmentShade->record(cmd, gbuffer, camera, in, *environmentImages, &profiler);
  }
  engine::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                        VK_ACCESS_2_MEMORY_READ_BIT);
}

Status IndirectLighting::setEnvironment(const EnvironmentImage& e) {
  if (e.width == 0) {
    impl_->environmentSet = false;
    ++impl_->environmentSerial;
    return {};
  }
  // 32768 x 16384 is already 8 GiB of texels: larger is a mistake, not an environment.
  if (e.height == 0 || e.width > 32768 || e.height > 32768 || !e.rgba)
    return failure("EnvironmentImage: " + std::to_string(e.width) + " x " +
                   std::to_string(e.height) +
                   (e.rgba ? " is not a size in [1, 32768]^2" : " without texels (rgba is null)"));
  try {
    engine::ImageRgba32f image;
    image.width = int(e.width);
    image.height = int(e.height);
    image.pixels.assign(e.rgba, e.rgba + size_t{e.width} * e.height * 4);
    // Created before the frame that first uses them: a host device gives new images their
    // first layout at the start of the next record().
    if (!impl_->environmentMap) {
      impl_->environmentMap.emplace(impl_->ctx, impl_->settings.environment.mapSize);
      impl_->environmentShade.emplace(impl_->ctx);
      impl_->environmentLights.emplace(impl_->ctx, impl_->settings.environment.mapSize);
      impl_->environmentImages = createIndirectImages(impl_->ctx, impl_->width, impl_->height);
    }
    impl_->environmentMap->upload(impl_->ctx, image);  // keeps the earlier one on failure
  } catch (const std::exception& ex) {
    return failure(std::string("EnvironmentImage: ") + ex.what());
  }
  impl_->environmentSet = true;
  ++impl_->environmentSerial;
  return {};
}

Status IndirectLighting::record(VkCommandBuffer cmd, const FrameInput& input, FrameOutput* output) {
  if (!cmd || !output) return failure("IndirectLighting::record: null command buffer or output");
  try {
    impl_->record(cmd, input, *output);
  } catch (const std::exception& e) {
    impl_->last = {};  // what the stopped frame recorded may not be submitted
    return failure(e.what());
  }
  return {};
}

ShadingCounts IndirectLighting::lastShadingCounts() const {
  ShadingCounts counts = impl_->plan.adaptive ? impl_->adaptive.lastCounts() : ShadingCounts{};
  if (impl_->plan.culled) {
    const gpu::VsglShadeStats stats = impl_->shade.lastStats();
    for (size_t level = 0; level < counts.vsglTests.size(); ++level) {
      counts.vsglTests[level] = stats.tested[level];
      counts.vsglsSkipped[level] = stats.skipped[level];
    }
  }
  return counts;
}

const FramePlan& IndirectLighting::lastPlan() const {
  return impl_->plan;
}

std::vector<PassTime> IndirectLighting::lastFrameTimes() const {
  std::vector<PassTime> out;
  for (const engine::PassTime& p : impl_->profiler.results(false))
    out.push_back({p.name, p.ms, p.dispatches});
  return out;
}

}  // namespace gi
