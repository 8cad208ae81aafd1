// CPU twins of the imperfect-shadow-map passes (shaders/shared/ism.h, common/ism_lookup.glsl),
// in double and naive on purpose, plus the ground truth they approximate: brute-force ray
// casting against every triangle. Geometry is passed as the scene's world positions and
// indices (3 per triangle), the same data the GPU reads from engine::SceneGpu.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "engine/scene.h"
#include "shared/ism.h"
#include "shared/vsgl.h"

namespace gi {

using IsmPositions = std::span<const glm::vec3>;
using IsmIndices = std::span<const uint32_t>;

// Inclusive prefix sums of the triangle areas (m^2): element t = area of triangles 0..t.
std::vector<double> ismTriangleCdfReference(IsmPositions positions, IsmIndices indices);

// R2 point i as the GPU forms it: (frac(1/2 + i a1), frac(1/2 + i a2)) in 32-bit fixed point,
// truncated to 24 bits (exact in fp32).
glm::dvec2 ismR2(uint32_t i);

// Pool point i: the triangle where the CDF first exceeds (i + 1/2) / P of the total, and the
// barycentric weights (b1, b2) of its vertices 1 and 2 before unorm16 quantisation. The triangle
// is ISM_NO_TRIANGLE when the scene has no area.
struct IsmPointReference {
  uint32_t triangle = ISM_NO_TRIANGLE;
  glm::dvec2 bary{0.0};
};
std::vector<IsmPointReference> ismPointsReference(IsmPositions positions, IsmIndices indices,
                                                  uint32_t pointCount);
// ism_points.comp's alpha test: a point of the pool that an alpha-tested material of `scene`
// cuts (engine/alpha_cutout.h) lies on no triangle. The test is made at the barycentrics
// rounded to unorm16, where the GPU places the point.
void ismCutPointsReference(std::vector<IsmPointReference>& points, const engine::Scene& scene);

// World position of a (GPU) pool point on the current geometry; nullopt-like: w = 0 when the
// point lies on no triangle.
glm::dvec4 ismPointPosition(IsmPositions positions, IsmIndices indices, const gpu::IsmPoint& point);

struct IsmFrameReference {
  glm::dvec3 centre{0.0};
  glm::dvec3 tangent{1.0, 0.0, 0.0};
  glm::dvec3 bitangent{0.0, 1.0, 0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};
  bool lit = false;
  double extent = 0.0;  // m, the lobes' power-weighted spatial standard deviation
};
// ismFrame of common/ism_lookup.glsl: the lobes' frame (ismFrameFromLobes), centred on the
// VSGL's visibility point when it has one.
IsmFrameReference ismFrameReference(const gpu::Vsgl& vsgl, double centreOffset);

// Paraboloid coordinates of p in the frame, and its distance and d_z; uv is meaningful for
// d_z > 0 only.
struct IsmProjection {
  glm::dvec2 uv{0.0};
  double distance = 0.0;
  double cosAxis = 0.0;
};
IsmProjection ismProjectReference(const IsmFrameReference& frame, glm::dvec3 p);

// Depth texel value meaning "no point" in the raw splat of the reference.
constexpr double kIsmEmptyReference = -1.0;

// The raw atlas after the splat: vsglCount tiles of mapSize^2 distances (tile-major),
// kIsmEmptyReference where no point landed. `points` is the pool (the GPU's, so that the
// splat is checked on its own), positions taken from the given geometry.
std::vector<double> ismSplatReference(IsmPositions positions, IsmIndices indices,
                                      std::span<const gpu::IsmPoint> points,
                                      std::span<const gpu::Vsgl> vsgls, uint32_t mapSize,
                                      uint32_t pointsPerVsgl, double centreOffset);

// Pull-push of every tile of a raw atlas (kIsmEmptyReference = hole): the final atlas, +inf
// in tiles without any point.
std::vector<double> ismPullPushReference(std::span<const double> raw, uint32_t mapSize,
                                         uint32_t vsglCount);

// ismVisibility of common/ism_lookup.glsl on a final atlas.
double ismVisibilityReference(std::span<const double> atlas, const gpu::IsmParams& params,
                              const IsmFrameReference& frame, uint32_t vsglIndex,
                              glm::dvec3 position, glm::dvec3 normal);

// Ground truth: true when no triangle crosses the segment from `from` to `to`, ignoring hits
// within `endTolerance` metres of `to` (the receiver's own surface) and of `from`.
bool ismRayCastVisible(IsmPositions positions, IsmIndices indices, glm::dvec3 from, glm::dvec3 to,
                       double endTolerance = 1e-3);

}  // namespace gi
