// Every setting of the indirect-lighting module in one struct (docs/integration.md). Each field
// states its default, range, unit and what it costs; validateSettings() names the first field
// that is out of range. Fields marked "creation" size resources: changing them means creating a
// new IndirectLighting; the others may change every frame (IndirectLighting::setSettings).
#pragma once

#include <cstdint>
#include <string>

namespace gi {

// The largest VSGL count (Settings::maxVsglCount) and importance-VSGL count
// (BrsmSettings::importanceCount). A shading pass's invocation runs a loop iteration per VSGL
// (and the BRSM evaluation two per importance VSGL, one per lobe), and lavapipe ends an
// invocation's loops silently after 65 535 iterations in all (docs/performance.md): measured on
// it, shading reached about 50 000 VSGLs of 65 535 and lost the rest. These bounds leave room.
constexpr uint32_t kMaxVsglCount = 32768;
constexpr uint32_t kMaxImportanceCount = 16384;

// How each VSGL's filter kernel is sized (vsgl-math.md section 5).
enum class KernelRule : uint32_t {
  Tok15 = 0,     // Tokuyoshi 2015: mip level from the PDF at the kernel centre
  Modified = 1,  // modified FIS: the kernel holds K/N of the PDF mass (bisection, [S3] Eq. 3)
};

// How the RSM's texels become VSGLs.
enum class VsglMethod : uint32_t {
  // The module's method: kernels sampled from the PDF and sized by `rule` (vsgl-math.md 5-6).
  FilteredImportanceSampling = 0,
  // The baseline ([S3] Tables 1-3): k-means clusters of texels in 2-D RSM image coordinates or
  // of VPL positions in 3-D world space (vsgl-math.md section 9, docs/techniques/kmeans.md).
  KmeansImage = 1,
  KmeansWorld = 2,
  // The instant-radiosity baseline (docs/techniques/vpl-baseline.md): N VPLs, one RSM texel
  // each, drawn from the same PDF and lattice, shaded as point lights with the receiver's exact
  // BRDF and the same ISMs. K, the rule, adaptive shading and culling do not apply.
  Vpl = 3,
};

struct KmeansSettings {
  // Lloyd iterations per frame, [1, 64]. Cost per iteration ~ rsmSize^2 x vsglCount distance
  // tests (assignment) + a radix sort of rsmSize^2 pairs + the sums.
  uint32_t iterations = 4;
  // Centres weighted by the PDF (view-dependent with PdfKind::Brsm, [PKD12]); false: every
  // texel with power weighs the same. No cost.
  bool pdfWeighted = true;
  // Start each frame from the previous frame's centres (temporally coherent, [PKD12]); false:
  // fresh PDF-proportional seeds every frame. Changing vsglCount or the method reseeds.
  bool temporal = true;
  bool operator==(const KmeansSettings&) const = default;
};

// Which PDF the VSGLs sample over the RSM (vsgl-math.md section 7).
enum class PdfKind : uint32_t {
  Flux = 0,  // proportional to reflected flux: view-independent, cheapest
  Brsm = 1,  // view-dependent bidirectional RSM: importance VSGLs from the camera G-buffer
};

struct BrsmSettings {
  // Creation. Importance VSGLs generated from the camera G-buffer, [1, kMaxImportanceCount]
  // ([S3]: 2048).
  // Cost: stage B is linear in it (cells x count x 4 SG inner products).
  uint32_t importanceCount = 2048;
  // Creation. Cells per side of the stage-B grid, a power of two in [1, rsmSize]; rsmSize makes
  // it per texel. Within a cell the PDF follows the texels' flux. Cost ~ gridSize^2 x
  // importanceCount (about 38 ns per cell and importance VSGL on lavapipe, 2 cores: 32^2 x 2048
  // = 80 ms, 64^2 x 2048 = 0.3 s).
  uint32_t gridSize = 32;
  // Share e in (0, 1] of the flux-proportional PDF mixed in: every lit texel keeps p > 0, so no
  // light is lost where the importance estimate is zero; 1 = the flux PDF. No cost.
  float fluxMix = 0.1f;
  bool operator==(const BrsmSettings&) const = default;
};

// Percentage-closer filtering of the ISM depth test (shaders/shared/ism.h ISM_PCF_*).
enum IsmFilter : uint32_t { IsmNearest = 0, IsmBilinear = 1, IsmBox3 = 2 };

struct IsmSettings {
  // Texels per side of one VSGL's paraboloid map, a power of two in [16, 256] ([S3]: 64). Cost:
  // atlas maxVsglCount x mapSize^2 x 4 bytes plus a third of that as pull-push scratch (21 MB
  // at 1024 x 64^2); pull-push time ~ VSGLs x mapSize^2; a bigger map needs proportionally more
  // points per VSGL for the same coverage (holes are filled, but blur the shadows).
  uint32_t mapSize = 64;
  // Pool of surface points P, a power of two in [2^10, 2^22]. Cost: 8 bytes (point) + 16 bytes
  // (position) each; generation time ~ P log2(triangles), once per scene change. P /
  // pointsPerVsgl VSGLs get disjoint subsets; beyond that subsets repeat.
  uint32_t pointCount = 1u << 18;
  // Points splatted per VSGL M, a power of two in [64, pointCount]. Cost: splat time ~ VSGLs x M
  // (1024 x 4096 = 4M 32-bit atomics per build). 4096 puts about one point on every texel a
  // 64^2 hemisphere sees of a closed room: fewer leave more of the map to pull-push (softer,
  // leakier shadows).
  uint32_t pointsPerVsgl = 4096;
  // Constant depth bias, metres, [0, 10]: subtracted from the receiver's distance. Hides the
  // depth spread of one texel's points on a receiver facing the VSGL. No cost.
  float depthBias = 0.03f;
  // Slope-scaled bias in texel footprints, [0, 16]: (distance x texel angle) x tan(receiver
  // angle) more bias, the depth change across one texel on a tilted receiver. Larger = less
  // acne, more light leaking at contacts. No cost.
  float slopeBias = 1.5f;
  // Metres the ISM centre sits above the VSGL's mean along its axis, [0, 10]: keeps the VSGL's
  // own (flat) surface below the hemisphere. Larger = contact shadows near the VSGL lost.
  float centreOffset = 0.02f;
  // IsmNearest (1 texel), IsmBilinear (2 x 2, default) or IsmBox3 (3 x 3). Cost: 1, 4 or 9
  // atlas reads per pixel-VSGL pair.
  uint32_t pcf = IsmBilinear;
  bool operator==(const IsmSettings&) const = default;
};

// The effect planner's decisions (docs/integration.md, "The effect planner"), each of which can
// be turned off for comparison. A decision leaves out work whose result is exactly zero or never
// read, so the images are the same with it on or off; skipWithoutOccluders says how it differs.
struct PlannerSettings {
  // No light can bounce (light intensity x colour = 0, a spot whose range ends before the
  // scene's bounds, or SceneGeometry::maxReflectance = 0): skip every pass and write black
  // outputs.
  bool skipWithoutBounce = true;
  // Subgroups of pixels that all see the sky (depth 1) skip the VSGL loop.
  bool skipSky = true;
  // Nothing can occlude (SceneGeometry::canOcclude = false): no ISM build or test. Unlike the
  // others this decision changes the image: it removes the ISMs' own errors (light lost to
  // their holes and biases), where the exact visibility is 1. In an open-top room under a sun
  // (the walls' lit outer faces must not light the room) it lowers the relMSE against the path
  // tracer from 0.0038 to 0.0032 (tests/gpu/test_accuracy_gate.cpp).
  bool skipWithoutOccluders = true;
  // Pixels with no glossy term (F0 = F90 = 0: a dielectric with KHR_materials_specular's
  // strength 0) are shaded without it. Per texel, in adaptive shading's queues (with adaptive
  // shading off every pixel runs the glossy term).
  bool skipGlossyWithoutSpecular = true;
  bool operator==(const PlannerSettings&) const = default;
};

// Adaptive shading (docs/techniques/adaptive-shading.md, after [S4] section 3.2): the VSGL sum
// is shaded on a pyramid of the G-buffer, coarse to fine, and interpolated wherever a texel's
// four parents lie on its surface, share its material and agree on the light. Off: every pixel
// is shaded. Shading cost ~ the texels shaded (FrameStats::shaded) x vsglCount.
struct AdaptiveSettings {
  bool enabled = true;
  // The coarsest level, [0, 3]: level L shades one pixel in 2^L x 2^L. Every texel of it that
  // sees a surface is shaded. 0 shades every pixel through the level-0 queue (the same image as
  // enabled = false, for testing).
  uint32_t coarsestLevel = 2;
  // Interpolate only when the parents' light, as this texel would show it (luminance of albedo
  // x diffuse + glossy), spreads by at most this fraction of its mean, [0, 10]. Smaller = more
  // texels shaded, closer to full shading; 0 interpolates only where the light is flat.
  float lightTolerance = 0.2f;
  // A parent is on the texel's surface when the texel lies within this fraction of its distance
  // from the eye of the parent's tangent plane, [0, 1] ...
  float planeTolerance = 0.01f;
  // ... and their normals differ by at most this angle, radians, [0, pi].
  float normalAngle = 0.35f;
  // Largest difference of perceptual roughness, [0, 1], and of any F0 channel or F90, [0, 1],
  // between a texel and its parents: light is not carried across a material edge.
  float roughnessTolerance = 0.05f;
  float f0Tolerance = 0.02f;
  bool operator==(const AdaptiveSettings&) const = default;
};

// VSGL culling (docs/techniques/vsgl-culling.md): per subgroup of pixels shaded together (the
// tile), VSGLs are skipped in order while their conservative upper bounds over the tile's
// receivers (positions, normals, materials; visibility 1) add up to at most `budget` of the
// least light any of its pixels has gathered so far. Each pixel loses at most `budget` of its
// light (largest channel). Off by default: on the built-in scenes it skips 0-3.5 % of the
// VSGLs, which saves about what the bounds cost (docs/techniques/vsgl-culling.md); it pays where
// many VSGLs are far from, or face away from, most of the view.
struct CullingSettings {
  bool enabled = false;
  float budget = 0.01f;  // tau, [0, 0.5]; larger = more VSGLs skipped, more light lost
  bool operator==(const CullingSettings&) const = default;
};

// Environment lighting (docs/techniques/environment.md), used when the host has set an
// environment (IndirectLighting::setEnvironment): filtered importance sampling of a
// dual-paraboloid map after Colbert and Krivanek (vsgl-math.md section 10), unshadowed.
enum class EnvironmentSampling : uint32_t {
  Filtered = 0,    // each sample reads the mip level its solid angle covers (the method)
  Unfiltered = 1,  // level 0: the aliasing the filter removes (comparison)
  Randomised = 2,  // level 0, the sample set rotated per pixel: noise instead of aliasing
};
// How the environment is shaded: filtered importance sampling per pixel ([S1], [S2]), or N SG
// lights sampled from the environment like the VSGLs from the RSM (the Fibonacci lattice,
// hierarchical warping and the modified-FIS kernel) and shaded with the SG lighting of the VSGL
// path (docs/techniques/environment.md, pass 4).
enum class EnvironmentMethod : uint32_t { Fis = 0, SgLights = 1 };
// The lobe sampled and shaded for the glossy term. Ggx is the G-buffer's BRDF (brdf.glsl);
// Phong (exponent 2 / alpha^2 - 2) and Ward (alpha_x = alpha, alpha_y = alpha x wardAnisotropy)
// reflect a constant F0 and exist to compare the samplers of [S1] and [S2].
enum class EnvironmentBrdf : uint32_t { Ggx = 0, Phong = 1, Ward = 2 };

struct EnvironmentSettings {
  EnvironmentMethod method = EnvironmentMethod::Fis;
  // SgLights: lights N, [1, 4096], generated once per environment and count; shading costs
  // ~ N x pixels. Their kernels hold sgKernelScale / N of the luminance, [1, N] ([S3]'s K).
  uint32_t sgLightCount = 64;
  float sgKernelScale = 1.0f;
  // FIS samples per pixel N, [1, 4096] ([S2]: 24-50 look right). Cost ~ N x pixels.
  uint32_t sampleCount = 40;
  EnvironmentSampling sampling = EnvironmentSampling::Filtered;
  EnvironmentBrdf brdf = EnvironmentBrdf::Ggx;  // SgLights: Ggx only
  float wardAnisotropy = 1.0f;                  // alpha_y / alpha_x of the Ward lobe, [0.01, 100]
  // K of the level rule l = max(log4(K S^2 / (N p r)), 0), [1, 16] ([S2]: 4). Larger =
  // blurrier, less aliasing. No cost.
  float kernelScale = 4.0f;
  // Creation. Texels per side of each paraboloid map S, a power of two in [16, 2048]. Cost:
  // 32 S^2 bytes with mips, converted once per environment.
  uint32_t mapSize = 256;
  bool operator==(const EnvironmentSettings&) const = default;
};

struct Settings {
  // Creation. RSM side in texels, a power of two in [16, 2048] ([S3]: 512). Cost ~ rsmSize^2 in
  // the RSM, attribute and mip passes (about 0.3 us per texel on lavapipe). A point light
  // renders six cube faces of rsmSize^2 one after another in the same memory: six times the
  // per-view passes, BRSM evaluation included (measured 5.7x, 48 -> 273 ms at 256^2 on lavapipe;
  // docs/techniques/point-lights.md).
  uint32_t rsmSize = 256;
  // Creation. Largest VSGL count this instance will be asked for, [1, kMaxVsglCount]; sizes the
  // VSGL buffer and the ISM atlas. 0 = vsglCount.
  uint32_t maxVsglCount = 0;
  // VSGLs per frame N, [1, maxVsglCount] ([S3]: 1024). Cost ~ N x pixels in shading (the
  // dominant pass) and ~ N in the ISM build.
  uint32_t vsglCount = 1024;
  // K, [1, vsglCount]: each kernel holds K/N of the PDF mass. Larger = blurrier and temporally
  // steadier ([S3]: 1). No cost.
  float kernelScale = 1.0f;
  KernelRule rule = KernelRule::Modified;
  PdfKind pdf = PdfKind::Brsm;
  // FilteredImportanceSampling, or a baseline for comparison: k-means (its resources are created
  // with its first frame: keys, values and sort scratch of 16 bytes per RSM texel) or VPLs (no
  // resources of its own; a pixel-VPL pair costs about a third of a pixel-VSGL pair, 14-28 against
  // 51-74 ns on lavapipe, but every pixel is shaded: docs/benchmarks.md).
  VsglMethod method = VsglMethod::FilteredImportanceSampling;
  KmeansSettings kmeans;
  BrsmSettings brsm;
  // Indirect visibility with imperfect shadow maps (vsgl-math.md section 8). Off: every VSGL
  // lights every receiver it faces (light leaks through walls); saves the ISM build and the
  // per pair depth test (measured on lavapipe: 20 % of the shading time). Each combination of
  // ismEnabled and glossy is its own shading pipeline, compiled at its first record.
  bool ismEnabled = true;
  // Creation. The imperfect shadow maps' resolution, point set and biases (docs/techniques/ism.md).
  IsmSettings ism;
  // Shade the glossy (GGX) term; off, the glossy output is 0 and shading costs about 40 % less
  // (measured on lavapipe: 252 -> 155 ns per pixel-VSGL pair with ISMs).
  bool glossy = true;
  // Flat clusters shade as planar emitters (docs/techniques/planar-emitters.md): no light below
  // or along a VSGL's plane (a floor does not light itself, a wall's outer face does not light
  // the room), power kept. Off: the SG emitter of vsgl-math.md section 3.4 for every VSGL, for
  // comparison. Cost: a few flops per pixel-VSGL pair (measured in docs/accuracy.md).
  bool planarEmitters = true;
  // The light's filtered-sampling kernels stay on one surface (docs/techniques/vsgl-generation.md,
  // "Kernels that leave their surface"): a kernel whose mean lies more than this many standard
  // deviations (weighted by its planarity) off the surface under its centre, because it spans a
  // depth discontinuity of the light's image, is shrunk to the level at which it first leaves
  // it, so that no VSGL lights the room from mid-air. [0, 10]; 0 = off, kernels as the rule
  // sizes them. Smaller is more accurate and flickers more: on the atrium at 0.2 (the default: the
  // smallest at which no built-in scene's accuracy gate got worse) relMSE 0.0117 -> 0.0079 at N =
  // 64, image flicker under an orbiting camera 0.049 -> 0.064 (docs/flicker.md). Cost: a short
  // search per VSGL in generation.
  float surfaceTolerance = 0.2f;
  // A VPL's reflection no narrower than the Lambert lobe joins the VSGL's diffuse lobe, a narrow
  // one stays in its glossy lobe, and one between is shared (docs/techniques/vsgl-generation.md,
  // "Broad reflections"): one SG cannot hold a mirror's narrow reflection and a matte surface's
  // broad one at once. On, the accuracy gate's checker (polished and matte tiles) reads relMSE
  // 0.0056 / 0.0030 at N = 64 / 512 instead of 0.0061 / 0.0036, its mean 0.935 instead of
  // 0.920. Off by default: the now narrow glossy lobes of kernels across a crease light the
  // polished floor from its own plane, and under an orbiting camera the checker gets fireflies
  // (a pixel 50x the reference's brightest in one frame; image flicker 0.052 -> 0.154,
  // docs/flicker.md). Cost: none in shading.
  bool broadReflections = false;
  PlannerSettings planner;
  AdaptiveSettings adaptive;
  CullingSettings culling;
  EnvironmentSettings environment;
  // Debug: index of the VSGL whose ISM visibility is written to FrameOutput::debugVisibility,
  // or -1 for none. Cost: one extra pass over the pixels.
  int32_t debugVsgl = -1;
  // Reuse across frames (docs/techniques/reuse.md): a pass reruns only when one of its inputs
  // changed since it last ran; every frame is bit-identical to the same frame with reuse off.
  // Needs the host to number its G-buffer and geometry (FrameInput::gbufferGeneration,
  // sceneGeneration); a host that leaves them 0 gets every pass every frame. No cost.
  bool reuse = true;

  bool operator==(const Settings&) const = default;
};

// Empty when every field is in range, else one line naming the first bad field, e.g.
// "Settings.rsmSize: 300 is not a power of two in [16, 2048]".
std::string validateSettings(const Settings& settings);

}  // namespace gi
