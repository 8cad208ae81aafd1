// The public API of the module: one-bounce diffuse and glossy indirect light from virtual
// spherical Gaussian lights for a deferred renderer. docs/integration.md walks through it with
// a complete example and the resource table.
//
// The host owns everything Vulkan: instance, device, queues, command buffers, its G-buffer and
// its scene buffers. IndirectLighting records compute work into a command buffer the host gives
// it and never submits, waits or presents. It allocates its own intermediate resources on the
// host's device and hands back two images the host composites: indirect diffuse and indirect
// glossy radiance. No exception crosses this API: failures come back as a Status with one line.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gi/settings.h"

namespace gi {

struct Status {
  bool ok = true;
  std::string message;  // one line naming the input or field and the problem when !ok
  explicit operator bool() const { return ok; }
};

// The host's device. Requirements: Vulkan 1.3 with synchronization2 and maintenance4 enabled,
// VK_KHR_push_descriptor, shaderInt64 and shaderBufferInt64Atomics (Vulkan 1.2 features); the
// queue that runs our commands must support compute. `create` refuses a device that lacks one,
// naming it: the features in `enabledFeatures` when the host gives the chain it created the
// device with (Vulkan has no query for a device's enabled features), else the physical device's
// support; a missing VK_KHR_push_descriptor or subgroup ballot is always found.
struct DeviceHandles {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  const VkPhysicalDeviceFeatures2* enabledFeatures = nullptr;  // VkDeviceCreateInfo::pNext
};

// A host image: the view covers its single mip level; `layout` is the layout it is in when the
// recorded commands start (any layout that holds its contents; not UNDEFINED).
struct ImageRef {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

// The host's G-buffer, width x height, usage STORAGE (the module reads it with imageLoad).
// Formats and encodings (shaders/shared/gbuffer.h):
//   depth    R32_SFLOAT           Vulkan NDC depth in [0, 1] of `Camera::viewProj`; 1 = sky
//   normal   R16G16_SNORM         world-space unit normal, octahedral encoding, facing the viewer
//   diffuse  R16G16B16A16_SFLOAT  rgb = diffuse albedo (base colour x (1 - metallic)),
//                                 a = perceptual roughness r (GGX alpha = r^2)
//   specular R16G16B16A16_SFLOAT  rgb = F0, a = F90, Schlick's F = F0 + (F90 - F0)(1 - v.h)^5:
//                                 F0 = mix(0.04 s c, base colour, metallic), F90 =
//                                 mix(s, 1, metallic) with KHR_materials_specular's strength s
//                                 and colour c (1 without it). F0 = F90 = 0: no glossy term.
// The module leaves all four in VK_IMAGE_LAYOUT_GENERAL (also reported in FrameOutput).
// Depth and normal may come as the host renders them instead (depthEncoding, depthFormat,
// normalEncoding): the module then converts both first, into images of its own
// (gbuffer_convert.comp, one small pass), and reads the host's two through sampled views, so
// they need VK_IMAGE_USAGE_SAMPLED_BIT rather than STORAGE (a depth-aspect view for D32).
enum class DepthEncoding : uint32_t {
  Ndc = 0,          // Vulkan NDC depth of a forward projection: near 0, far 1; 1 = sky
  ReversedNdc = 1,  // reversed-Z: Camera::proj maps near to 1 and far (or infinity) to 0; 0 = sky
  ViewDistance = 2  // metres along the view axis (-z of Camera::view), Camera::proj forward;
                    // 0, negative or non-finite = sky
};
enum class NormalEncoding : uint32_t {
  Octahedral = 0,    // R16G16_SNORM, octahedral (as above)
  WorldSigned = 1,   // rgb = the world-space unit normal (a float or SNORM format); 0 = sky
  WorldUnsigned = 2  // rgb = normal * 0.5 + 0.5 (a UNORM format: RGBA8, A2B10G10R10)
};
struct GBufferImages {
  uint32_t width = 0;
  uint32_t height = 0;
  ImageRef depth, normal, diffuse, specular;
  DepthEncoding depthEncoding = DepthEncoding::Ndc;
  VkFormat depthFormat = VK_FORMAT_R32_SFLOAT;  // or VK_FORMAT_D32_SFLOAT
  NormalEncoding normalEncoding = NormalEncoding::Octahedral;
};

// Scene geometry in host buffers, read by the module's light-view rasteriser (the RSM) and by
// the ISM point generation. Layouts (std430, shaders/shared/scene_data.h):
//   vertices           gpu::SceneVertex per vertex: vec4(world position, u), vec4(unit normal, v)
//   indices            uint32 x 3 per triangle, counter-clockwise seen from the front
//   triangleMaterials  uint32 material index per triangle
//   materials          gpu::SceneMaterial per material (glTF metallic-roughness factors,
//                      KHR_materials_specular factors, texture layers, -1 = none, with their
//                      KHR_texture_transform, and doubleSided)
//   baseColorTextures  2-D array view, R8G8B8A8_SRGB, layers indexed by the materials
//   dataTextures       2-D array view, R8G8B8A8_UNORM (glTF metallic-roughness: g = roughness,
//                      b = metallic); both in SHADER_READ_ONLY_OPTIMAL, sampled with `sampler`
// Vertex positions may change every frame (animation): the ISM points are stored as (triangle,
// barycentrics) and follow them. Call setScene again when the triangle set changes.
struct SceneGeometry {
  VkBuffer vertices = VK_NULL_HANDLE;
  VkDeviceSize vertexBytes = 0;
  VkBuffer indices = VK_NULL_HANDLE;
  VkDeviceSize indexBytes = 0;
  VkBuffer triangleMaterials = VK_NULL_HANDLE;
  VkDeviceSize triangleMaterialBytes = 0;
  VkBuffer materials = VK_NULL_HANDLE;
  VkDeviceSize materialBytes = 0;
  uint32_t triangleCount = 0;
  uint32_t vertexCount = 0;    // vertices in `vertices`; every buffer must hold its count
  uint32_t materialCount = 0;  // materials in `materials`
  // Optional CPU copies of the index and triangle-material buffers (3 and 1 values per
  // triangle). With them setScene checks every index against vertexCount and every material
  // against materialCount. Without them it cannot read the buffers, and the GPU passes guard
  // instead: a triangle naming a vertex past vertexCount is left out of the light's view and the
  // ISMs, one naming a material past materialCount reflects nothing in the light's view (it
  // still casts shadows); nothing is read out of bounds either way.
  std::span<const uint32_t> indexData;
  std::span<const uint32_t> triangleMaterialData;
  VkImageView baseColorTextures = VK_NULL_HANDLE;
  VkImageView dataTextures = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  glm::vec3 boundsMin{0.0f};  // world-space box around all geometry (RSM depth range, ISM far
  glm::vec3 boundsMax{0.0f};  // distance, directional lights' orthographic view)
  // The largest reflectance of any surface: the largest channel of any material's diffuse
  // albedo, specular F0 or F90 (Schlick's grazing reflectance: a black metal has F90 = 1),
  // textures included, in [0, 1]. 0 means nothing can bounce light, and
  // the effect planner then skips every pass (FramePlan). A host that does not know leaves 1.
  float maxReflectance = 1.0f;
  // The largest F0 channel or F90 of any material, textures included, in [0, 1]. 0 means no
  // surface has a specular lobe: the effect planner then builds no glossy VSGL lobes or their
  // attribute mips and shades no glossy term (FramePlan). A host that does not know leaves 1.
  float maxSpecular = 1.0f;
  // Whether any surface can block light between two others. false, e.g. for the inside of a
  // convex room, where every vertex lies on or in front of every triangle's plane: the
  // effect planner then skips the ISMs (FramePlan). A host that does not know leaves true.
  bool canOcclude = true;
  // Whether any material is alpha-tested (SceneMaterial::alphaCutoff > 0, glTF MASK). false
  // runs the RSM's raster and the ISM points without the cut-out test (compiled out). A host
  // that does not know leaves true.
  bool alphaCutouts = true;
};

// The light that bounces: a spot, directional or point light in KHR_lights_punctual units. A
// point light's RSM is the six faces of a cube, each rsmSize^2 (docs/techniques/point-lights.md).
struct Light {
  enum class Type : uint32_t { Spot, Directional, Point };
  Type type = Type::Spot;
  glm::vec3 position{0.0f};                // world, metres (spot, point)
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit, the way light travels (spot, directional)
  glm::vec3 color{1.0f};                   // linear RGB
  float intensity = 1.0f;                  // spot, point: W/sr (candela / 683); directional: W/m^2
  float innerConeAngle = 0.0f;             // radians, [0, outer)
  float outerConeAngle = 0.785398f;        // radians, (0, 1.3]
  // Spot and point: metres, 0 = none. KHR_lights_punctual's window clamp(1 - (d / range)^4, 0, 1)
  // at distance d scales the light that reaches the RSM, so the bounce ends where the host's direct
  // light does. Ignored for a directional light (KHR has no range for it).
  float range = 0.0f;
  bool operator==(const Light&) const = default;
};

// The camera that produced the G-buffer: Vulkan clip space (NDC y down, depth [0, 1]),
// column-major GLM matrices, clip = proj * view * world.
struct Camera {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
};

// An environment light (docs/techniques/environment.md): radiance from infinitely far away as an
// equirectangular (latitude-longitude) image in world space, y up: row 0 looks along +y, row
// height - 1 along -y, and column u (texel centres at (i + 1/2) / width) at azimuth
// phi = 2 pi u from +x towards +z. glTF has no environment; hosts take it from their own files.
struct EnvironmentImage {
  uint32_t width = 0;  // 0: no environment
  uint32_t height = 0;
  // width x height RGBA linear floats (radiance, W sr^-1 m^-2; alpha ignored), row 0 first.
  // Copied by setEnvironment: the host may free it on return.
  const float* rgba = nullptr;
};

// Lights one frame bounces at most: 48 RSM views (a point light has six) share the N VSGLs.
constexpr uint32_t kMaxLights = 8;

struct FrameInput {
  GBufferImages gbuffer;
  Camera camera;
  // Every light whose bounce the frame shows, at most kMaxLights (docs/techniques/
  // many-lights.md). Their RSM views share the N VSGLs in proportion to the light each reflects
  // towards the view, so a dim light gets few and one that bounces nothing none; a light without
  // power, or whose range ends before the scene, gets no RSM (FramePlan). One shading pass
  // shades them all. Each extra view (a spot or directional light is one, a point light six)
  // costs its RSM, attribute and PDF passes (lavapipe: about 45 ms at rsmSize 256) and 128 x
  // rsmSize^2 x 4/3 bytes of attribute pyramids (8.4 MB at 256) and 8 x rsmSize^2 bytes for its
  // light view (FrameOutput::lightViews, 0.5 MB at 256).
  std::vector<Light> lights;
  // What changed since earlier frames, for reuse across frames (Settings::reuse,
  // docs/techniques/reuse.md): each is a number the host changes whenever the content it names
  // changes and keeps while it does not. 0 means "not known" and counts as a change in every
  // frame, so a host that leaves them at 0 gets every pass in every frame.
  // The G-buffer images' content: whatever the host rendered differently (a new camera, moved
  // geometry, edited materials). The images' handles and the camera are compared besides.
  uint64_t gbufferGeneration = 0;
  // The content of SceneGeometry's buffers and textures (vertices moved in place, materials
  // edited). A setScene call is a change by itself.
  uint64_t sceneGeneration = 0;
};

// One view of a bouncing light as the module's RSM rasterized it this frame (or kept it from an
// earlier one, reuse), for a host that shadows its direct light with it instead of rasterizing
// the light's view again. docs/integration.md, "The light's view".
struct LightViewOutput {
  uint32_t light = 0;  // index into FrameInput::lights
  uint32_t face = 0;   // a point light's cube face (+x, -x, +y, -y, +z, -z), else 0
  uint32_t size = 0;   // texels per side (Settings::rsmSize)
  // World -> Vulkan clip space (x right, y down, depth [0, 1]) of the view: a spot's square
  // frustum around its outer cone, a directional light's box around the scene's bounds, a
  // point light's 90-degree cube face; near and far planes from SceneGeometry's bounds.
  glm::mat4 viewProj{1.0f};
  // size x size uint64 texels from `offset`, row 0 at the top (NDC y = -1): (NDC depth as float
  // bits << 32) | triangle id of the nearest surface, all ones where the view sees nothing; the
  // texel (x, y) samples NDC ((x + 0.5) / size * 2 - 1, (y + 0.5) / size * 2 - 1). Owned by the
  // module, written by compute and visible to any later stage; valid until the next record.
  VkBuffer visibility = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
};

struct FrameOutput {
  // RGBA32F radiance toward the camera (W sr^-1 m^-2, linear, alpha 1), width x height, in
  // VK_IMAGE_LAYOUT_GENERAL, written by compute; the barrier after the module's last pass makes
  // them visible to any later stage. Sky pixels are 0. Owned by the module.
  ImageRef indirectDiffuse;
  ImageRef indirectGlossy;
  // R32_SFLOAT visibility of VSGL Settings::debugVsgl from each pixel (VK_NULL_HANDLE when
  // debugVsgl < 0).
  ImageRef debugVisibility;
  // R32_SFLOAT level (0..3) at which each pixel's light was shaded by adaptive shading, -1 for
  // the sky, for debug views (VK_NULL_HANDLE when adaptive shading is off).
  ImageRef shadingLevels;
  // RGBA32F radiance toward the camera reflected from the environment light (albedo and BRDF
  // applied, unshadowed), like the indirect images; VK_NULL_HANDLE without an environment.
  ImageRef environmentDiffuse;
  ImageRef environmentGlossy;
  // The VSGL records of this frame (gpu::Vsgl, shaders/shared/vsgl.h), for debug views.
  VkBuffer vsgls = VK_NULL_HANDLE;
  uint32_t vsglCount = 0;
  // Which records came from which RSM view (gpu::VsglViewRange, shaders/shared/
  // vsgl_allocation.h: x = first record, y = count), one per view in order: one for a spot or
  // directional light, six for a point light's cube faces (+x, -x, +y, -y, +z, -z).
  VkBuffer vsglViews = VK_NULL_HANDLE;
  uint32_t viewCount = 0;
  // The RSM views of this frame's bouncing lights (FramePlan::lights), in the order of
  // vsglViews; a view the frame gave no VSGLs and did not rasterize is left out.
  std::vector<LightViewOutput> lightViews;
  // Layout the module left the host's G-buffer images in.
  VkImageLayout gbufferLayout = VK_IMAGE_LAYOUT_GENERAL;
};

// What the effect planner ran in the last recorded frame, and why it left work out
// (docs/integration.md, "The effect planner"). Settings::planner turns each decision off.
struct FramePlan {
  bool bounce = true;                 // RSM, PDF, VSGL generation, ISM and shading ran
  bool visibility = true;             // the ISMs were built and tested
  bool glossy = true;                 // the glossy term was shaded
  bool specularLobes = true;          // the VSGLs' specular lobes were built and shaded
  bool skySkipped = true;             // subgroups that see only sky skipped the VSGL loop
  bool adaptive = true;               // shaded on the adaptive pyramid (Settings::adaptive)
  bool culled = false;                // VSGLs culled per subgroup (Settings::culling)
  bool environment = false;           // the environment was shaded (an environment is set)
  bool environmentConverted = false;  // ... and converted this frame (it changed)
  std::vector<uint32_t> lights;       // the FrameInput::lights that bounced, by index
  // Reuse across frames (Settings::reuse): what this frame kept from the frame that last
  // computed it instead of recording its passes again. Nothing reused when all are false/0.
  struct Reuse {
    bool gbuffer = false;       // the converted G-buffer (depth and normal encodings)
    bool importance = false;    // BRSM stage A's importance VSGLs
    uint32_t lightViews = 0;    // RSM views whose RSM, flux and attribute pyramids were kept
    bool vsgls = false;         // the VSGLs, with their PDF and allocation
    bool ismPositions = false;  // the ISM points' positions (kept with the ISMs, or alone)
    bool isms = false;          // the imperfect shadow maps
    bool shading = false;       // the outputs (indirect images, levels, debug visibility)
    bool environment = false;   // the environment's outputs
    // One line per stage kept and why, or why a host gets no reuse (e.g. no generation numbers).
    std::vector<std::string> reasons;
  } reuse;
  std::vector<std::string> reasons;  // one line per decision that left work out
};

// What adaptive shading (Settings::adaptive) and VSGL culling did in the last frame, per level
// 0..3: level L has one texel per 2^L x 2^L pixels. Valid like lastFrameTimes().
struct ShadingCounts {
  bool adaptive = false;             // false: adaptive shading was off and every pixel was shaded
  std::array<uint32_t, 4> shaded{};  // texels shaded (the cost: each x vsglCount pairs)
  // Of those, the texels shaded without the glossy term: F0 = F90 = 0 there (the planner's
  // PlannerSettings::skipGlossyWithoutSpecular).
  std::array<uint32_t, 4> shadedWithoutGlossy{};
  std::array<uint32_t, 4> interpolated{};  // texels filled from their parents
  // Texels that could not interpolate but took the light their first parent shaded at the same
  // pixel (each pixel is shaded at most once: the cost never exceeds full-rate shading).
  std::array<uint32_t, 4> reused{};
  // Pixels whose light was shaded at each level, followed through the interpolation (sky
  // pixels excluded).
  std::array<uint32_t, 4> pixelsFrom{};
  uint32_t skyPixels = 0;
  // VSGL culling (Settings::culling), per level (level 0 also holds full-rate shading): VSGLs
  // tested against a subgroup's bound, and of those skipped there. Zero when culling was off.
  std::array<uint32_t, 4> vsglTests{};
  std::array<uint32_t, 4> vsglsSkipped{};
};

struct PassTime {
  std::string name;
  double ms = 0.0;
  uint32_t dispatches = 0;  // compute dispatches the pass recorded
};

class IndirectLighting {
 public:
  // Validates the settings and creates every pipeline and resource for a width x height
  // G-buffer (a resolution change means a new instance). Null on failure, with `status` set.
  static std::unique_ptr<IndirectLighting> create(const DeviceHandles& device,
                                                  const Settings& settings, uint32_t width,
                                                  uint32_t height, Status* status);
  ~IndirectLighting();
  IndirectLighting(const IndirectLighting&) = delete;
  IndirectLighting& operator=(const IndirectLighting&) = delete;

  // The geometry the RSM and ISMs are built from; required before the first record().
  Status setScene(const SceneGeometry& scene);

  // Sets the environment light (EnvironmentImage), or removes it with width 0. The image is
  // copied and converted in the next record(); the planner shades it only while one is set.
  // Call it when no recorded frame is still executing. Bad input (a size beyond the device's
  // image limit, a non-finite or negative texel) is refused, naming the pixel.
  Status setEnvironment(const EnvironmentImage& environment);

  // Changes the per-frame settings; a "creation" field that differs is refused (recreate).
  Status setSettings(const Settings& settings);
  const Settings& settings() const;

  // Records one frame into `cmd` (a primary command buffer in the recording state, on a queue
  // of DeviceHandles::queueFamily). The host submits it; every recorded command buffer must be
  // submitted, in recording order, because the module tracks its own image layouts.
  Status record(VkCommandBuffer cmd, const FrameInput& input, FrameOutput* output);

  // GPU time of each pass of the last recorded frame (a "frame" entry holds the total). Valid
  // once that frame's submission has completed and before the next record(); empty if its
  // timestamps are not available yet. Never waits.
  std::vector<PassTime> lastFrameTimes() const;
  // Adaptive shading's and VSGL culling's counts of the last recorded frame (valid once its
  // submission has completed and before the next record(); never waits).
  ShadingCounts lastShadingCounts() const;
  // The plan of the last recorded frame (valid right after record()).
  const FramePlan& lastPlan() const;

 private:
  struct Impl;
  explicit IndirectLighting(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gi
