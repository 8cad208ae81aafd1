// The VPL gather against the analytic scene's quadrature at three RSM resolutions, and where its
// VPLs lie on the built-in scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analytic_scene.h"
#include "embree_scene.h"
#include "engine/builtin_scenes.h"
#include "engine/gbuffer_reference.h"
#include "reference/rsm_reference.h"
#include "vpl_gather.h"

namespace {

constexpr uint32_t kWidth = 40, kHeight = 24;  // aspect 1.66: the wall spans the width

// Summed one-bounce luminance over the wall pixels at least 1 cm above the floor: gathered and
// exact.
struct WallSums {
  double gathered = 0.0;
  double exact = 0.0;
};

WallSums wallSums(const truth::AnalyticSceneParams& p, const engine::View& view,
                  const truth::VplGatherImage& image) {
  WallSums sums;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const engine::CameraRay ray = engine::cameraRayReference(view, glm::dvec2(x + 0.5, y + 0.5));
      const std::optional<glm::dvec3> point = truth::analyticWallHit(p, ray.origin, ray.dir);
      if (!point) continue;
      const size_t i = size_t{y} * kWidth + x;
      sums.gathered += gi::luminance709(image.diffuse[i] + image.glossy[i]);
      sums.exact += gi::luminance709(truth::analyticOneBounceRadiance(p, *point, -ray.dir));
    }
  return sums;
}

// The gather's only approximation is the RSM's discretisation of the lit disc (the wall is 0.8 m
// or more from it, so each VPL's disc regularisation is negligible there): its error must fall as
// the RSM is refined, and be within the 1 % at 128^2 (2.1 cm texels).
TEST(VplGather, ApproachesAnalyticOneBounceAsTheRsmRefines) {
  const truth::AnalyticSceneParams params;
  const engine::Scene scene = truth::makeAnalyticScene(params);
  const truth::EmbreeScene rays(scene);
  const engine::View view = engine::cameraView(scene.cameras.front(), kWidth, kHeight);
  double previous = INFINITY;
  for (uint32_t size : {32u, 64u, 128u}) {
    const std::vector<truth::Vpl> vpls = truth::rsmVpls(scene, rays, 0, size);
    const truth::VplGatherImage image = truth::vplGather(scene, rays, view, vpls);
    const WallSums sums = wallSums(params, view, image);
    const double error = std::abs(sums.gathered - sums.exact) / sums.exact;
    std::printf("RSM %u^2: %zu VPLs, wall error %.4f %%, %.2f s\n", size, vpls.size(),
                100.0 * error, image.seconds);
    EXPECT_LT(error, previous) << "RSM " << size;
    previous = error;
  }
  EXPECT_LT(previous, 0.01);
}

}  // namespace

// Every VPL of each built-in scene sees the space above its own surface: the RSM's fp32 depth
// places a third of the Cornell box's texel points under their surface at 32^2, where each VPL
// shadowed itself and the gather read 10 % low; rsmVpls moves them onto the surface.
TEST(VplGather, VplsDoNotShadowThemselves) {
  for (const std::string& name : engine::builtinSceneNames()) {
    const engine::Scene scene = engine::makeBuiltinScene(name);
    const truth::EmbreeScene rays(scene);
    const std::vector<truth::Vpl> vpls = truth::rsmVpls(scene, rays, 0, 32);
    ASSERT_FALSE(vpls.empty()) << name;
    size_t shadowed = 0;
    for (const truth::Vpl& v : vpls) {
      const glm::dvec3 above = v.position + 0.01 * v.geometricNormal;  // 1 cm: clear of all else
      if (!rays.visible(truth::offsetOrigin(v.position, v.geometricNormal), above)) ++shadowed;
    }
    EXPECT_EQ(shadowed, 0u) << name << ": " << shadowed << " of " << vpls.size() << " VPLs";
  }
}
