// The error budget's CPU stages (docs/accuracy.md): the module's approximations replaced one at a
// time by their exact counterparts, so that the gap between consecutive stages is one source's
// error. In order, each stage an image of indirect radiance:
//   path tracer (the truth)
//   -> RSM:       every lit texel of the module's RSM as a VPL, exact visibility (vpl_gather.h)
//   -> grouping:  the same VPLs weighted by how the VSGL kernels cover them (kernelTexelWeights):
//                 each VSGL's own VPLs, exact visibility
//   -> grouping, unshadowed, and SG model, unshadowed: each VSGL's lobes as the module models
//                 their light (Gaussian spot x SG emission, planar emitters), integrated
//                 numerically against the true BRDF, against the same VPLs without visibility:
//                 the light model's own error
//      Beside it, the same with the flat VSGLs' light exact (their own VPLs) and with the
//                 non-flat ones' exact: which VSGLs the light model's error comes from
//   -> SG model, area visibility: the lobes shadowed by what their own VPLs see of the receiver
//                 (the best one visibility number per VSGL and receiver can do)
//   -> SG model:  the same, visibility by an exact ray from the VSGL's ISM centre (against
//                 the grouping stage: the light model and one ray per VSGL for visibility)
//   -> analytic:  the same lobes through the module's analytic SG lighting (the shading's double
//                 twin), the same visibility
//   -> module:    the GPU's image (ISM visibility, fp32, adaptive shading)
#pragma once

#include <cstdint>
#include <vector>

#include "embree_scene.h"
#include "engine/scene.h"
#include "engine/view.h"
#include "shared/vsgl.h"
#include "vpl_gather.h"

namespace truth {

// Where the VSGLs' kernels lie: the RSM views' side, and each VSGL's view, in the order of
// FrameOutput::vsglViews (a point light's six cube faces, several lights' views one after the
// other). Texel t of view v is v * rsmSize^2 + t, as rsmVpls numbers them. Without `views`
// every kernel lies in view 0.
struct KernelLayout {
  uint32_t rsmSize = 0;
  std::vector<uint32_t> views;  // per VSGL
  size_t firstTexel(size_t vsgl) const {
    return (views.empty() ? 0 : size_t{views.at(vsgl)}) * rsmSize * rsmSize;
  }
};

// Per texel of the RSM views (as Vpl::texel), the weight with which the VSGLs' kernels count
// it: sum over VSGLs i of s_i k_i(t), k_i the exact weights of filtered
// sampling's trilinear fetch at (x_i, l_i) (vsgl_generate.comp: bilinear per level with
// clamp-to-edge, each level-l texel the mean of its 4^l level-0 texels), s_i the VSGL's power
// over the kernel-weighted power of the VPLs (M / (N p~) for modified FIS, whatever the rule).
// 1 everywhere is a perfect tiling. k-means clusters (kernel.z < 0) partition the texels: 1.
std::vector<double> kernelTexelWeights(const std::vector<gpu::Vsgl>& vsgls,
                                       const KernelLayout& layout, const std::vector<Vpl>& vpls);

// `vpls` with each incident power scaled by its texel's weight.
std::vector<Vpl> weightedVpls(const std::vector<Vpl>& vpls, const std::vector<double>& weights);

// A VSGL the budget counts as flat: planar emitters' planarity (gi::vsglPlanarity of its diffuse
// lobe) at least 0.95. Without diffuse weight it has no plane and is not flat.
bool flatVsgl(const gpu::Vsgl& vsgl);

struct VsglStageImages {
  std::vector<glm::dvec3> numeric;         // SG model, numerically integrated
  std::vector<glm::dvec3> unshadowed;      // the same without visibility
  std::vector<glm::dvec3> unshadowedFlat;  // its share from the flat VSGLs (flatVsgl)
  // SG model with each VSGL's visibility the mean of its own VPLs' exact visibility, each VPL
  // weighted by its kernel weight, power and unshadowed diffuse transfer to the receiver
  // (cos_y cos_x / (d^2 + A / pi)); a VSGL none of whose VPLs faces the receiver (and every
  // k-means cluster, whose members the record does not list) keeps its one ray. Empty without
  // VsglStageSettings::kernelVpls.
  std::vector<glm::dvec3> areaVisible;
  std::vector<glm::dvec3> analytic;  // the module's analytic SG lighting (double twin)
  double seconds = 0.0;
};

struct VsglStageSettings {
  bool planarEmitters = true;
  bool glossy = true;
  double ismCentreOffset = 0.02;  // IsmSettings::centreOffset: where the visibility ray starts
  // Directions per lobe and receiver, half from the lobe's SG, half from the receiver's GGX,
  // combined by the balance heuristic (Veach 1997, 9.2); fixed stratified points, no noise
  // between runs.
  uint32_t samplesPerLobe = 32;
  unsigned threads = 0;
  // The RSM's VPLs (rsmVpls) and where the kernels lie: with them the areaVisible image is
  // computed.
  const std::vector<Vpl>* kernelVpls = nullptr;
  KernelLayout kernels;
};

// Primary rays through pixel centres (as the path tracer's); visibility of VSGL k from a
// receiver by one exact ray from its ISM centre (gi::ismFrameReference).
VsglStageImages vsglStages(const engine::Scene& scene, const EmbreeScene& rays,
                           const engine::View& view, const std::vector<gpu::Vsgl>& vsgls,
                           const VsglStageSettings& settings);

// Where errors gather, per pixel (row-major): Background, Contact (within 3 % of the scene's
// diagonal of another surface, along the receiver's tangent plane: floor-wall lines), Coplanar
// (otherwise, on the plane of a surface that holds at least 1 % of the RSM's power, facing its
// way: a floor under a lit floor), Rest.
enum class BudgetRegion : uint8_t { Background = 0, Coplanar = 1, Contact = 2, Rest = 3 };
std::vector<BudgetRegion> budgetRegions(const engine::Scene& scene, const EmbreeScene& rays,
                                        const engine::View& view, const std::vector<Vpl>& vpls);

}  // namespace truth
