// An analytic scene for the one-bounce references: its exact one-bounce radiance comes from a
// deterministic quadrature, with no Monte Carlo and no ray tracing, so the path tracer (and the
// VPL gather) can be checked against it to 1 %.
//
// Scene (metres, +Y up): a floor y = 0, [-L, L]^2, normal +Y; a spot light at s = (0, h, 0)
// aiming straight down with the KHR_lights_punctual smooth falloff (engine::spotFalloff); a wall
// x = a, z in [-W, W], y in [0, H], facing -X, outside the cone's lit disc (radius
// h tan(outer)), so it gets no direct light. Both surfaces are the renderer's dielectric
// (metallic 0, roughness 1, F0 = 0.04). The only light that reaches the wall has bounced once
// off the lit disc; the floor gets no indirect light (the wall it would come from is unlit, and
// a plane never lights itself), so in a render the wall's light is exactly this oracle.
//
// Integral. For a wall point x (normal n_w = -X) seen along v (unit, from x to the camera):
//   L(x -> v) = Int_disc f_w(v, w_q) cos_w cos_q / d^2 L_q(q -> x) dA(q),
//   L_q(q -> x) = f_f(w_x, l_q) (n_f . l_q) I falloff(-Y . -l_q) / |s - q|^2,
// with d = |x - q|, w_q = (q - x) / d, w_x = -w_q, cos_w = n_w . w_q, cos_q = n_f . w_x and
// l_q = (s - q) / |s - q|: the rendering equation over the floor's area (dw = cos_q dA / d^2).
// f is engine/brdf_reference.h's surface model, Lambert rho / pi plus ggxSpecular. The wall sees
// all of the disc (the disc lies at x < a) and nothing occludes it.
//
// Quadrature: polar coordinates (r, phi) around the spot axis, dA = r dr dphi (the integrand
// stays smooth at r = 0: a smooth function times r). r runs over [0, h tan(outer)] (the falloff
// is 0 beyond) in two Gauss-Legendre panels split where the falloff reaches 1 (the inner cone),
// since its derivative jumps there; phi takes one Gauss-Legendre rule over [0, 2 pi]. On each
// panel the integrand is smooth, so the error falls exponentially. Measured against 200 radial
// nodes per panel and 400 angular, at five wall points from y = 0.02 to 1.6 m: 4 + 8 nodes err
// by 1e-4 relative, 8 + 16 by 3e-8, 12 + 24 by 2e-12, and the defaults, 16 + 32, by 3e-14
// (rounding); diffuse and glossy alike. A call costs about 0.5 ms (1024 integrand evaluations).
#pragma once

#include <glm/glm.hpp>
#include <optional>

#include "engine/scene.h"

namespace truth {

// Both surfaces' BRDF parameters (engine::Material): a rough dielectric, whose GGX lobe is broad
// enough for a polynomial quadrature.
constexpr double kAnalyticRoughness = 1.0;
constexpr double kAnalyticF0 = 0.04;  // glTF's dielectric F0, metallic 0

struct AnalyticSceneParams {
  double floorHalfSize = 50.0;   // L, metres
  double floorAlbedo = 0.8;      // rho_f, grey base colour
  double lightHeight = 1.0;      // h, metres
  double intensity = 10.0;       // I, W/sr, white
  double innerConeAngle = 0.45;  // radians, in [0, outer)
  double outerConeAngle = 0.6;   // radians; the lit disc's radius is h tan(outer) = 0.68 m
  double wallX = 1.5;            // a, metres; must exceed h tan(outer) (unlit wall)
  double wallHalfWidth = 2.0;    // W, metres
  double wallHeight = 2.0;       // H, metres
  double wallAlbedo = 0.6;       // rho_w, grey base colour
  // The camera looks from eye at target; the wall fills the frame above its lower quarter
  // (up to an aspect of 1.66; 16:9 leaves thin strips beside it), which shows the floor and
  // the far third of the lit disc (x > 0.24 m).
  glm::dvec3 cameraEye{-1.0, 0.6, 0.0};
  glm::dvec3 cameraTarget{1.5, 0.6, 0.0};
  double cameraYfov = 0.9;  // radians
  // Tests only: both surfaces Lambertian (the GGX terms dropped) in the oracle; the scene's
  // materials do not change.
  bool lambertOnly = false;
  int radialNodes = 16;   // Gauss-Legendre nodes per radial panel, >= 1
  int angularNodes = 32;  // Gauss-Legendre nodes over [0, 2 pi], >= 1
};

// Two triangles each for the floor and the wall (counter-clockwise towards their normals), the
// spot as scene.lights[0], one camera. Materials: 0 = floor, 1 = wall.
engine::Scene makeAnalyticScene(const AnalyticSceneParams& p);

// The one-bounce radiance leaving wall point x towards viewDir (unit, from x to the viewer),
// split by the wall's lobe as the VSGL module's outputs are: diffuse = Lambert at the wall,
// glossy = GGX at the wall; the floor always reflects with its full BRDF. W sr^-1 m^-2.
struct OneBounceRadiance {
  glm::dvec3 diffuse{0.0};
  glm::dvec3 glossy{0.0};
};
OneBounceRadiance analyticOneBounce(const AnalyticSceneParams& p, glm::dvec3 wallPoint,
                                    glm::dvec3 viewDir);
// diffuse + glossy of analyticOneBounce.
glm::dvec3 analyticOneBounceRadiance(const AnalyticSceneParams& p, glm::dvec3 wallPoint,
                                     glm::dvec3 viewDir);

// Where the ray origin + t dir (t > 0) meets the wall, if it does at least 1 cm above the floor
// (pixels at the wall's foot may show the floor instead): the points tests score.
std::optional<glm::dvec3> analyticWallHit(const AnalyticSceneParams& p, glm::dvec3 origin,
                                          glm::dvec3 dir);

// The direct radiance leaving floor point q (y = 0) towards viewDir (unit, from q to the viewer):
// f_f (n_f . l) I falloff / |s - q|^2, closed form. W sr^-1 m^-2.
glm::dvec3 analyticFloorDirectRadiance(const AnalyticSceneParams& p, glm::dvec3 floorPoint,
                                       glm::dvec3 viewDir);

}  // namespace truth
