// The surface model of common/brdf.glsl in double: Lambert diffuse plus GGX specular with the
// height-correlated Smith visibility (Heitz 2014, Eq. 99) and Schlick's Fresnel (glTF
// metallic-roughness, alpha = r^2), with the shader's floors. The oracle of the direct light's
// and the VSGL shading's tests.
#pragma once

#include <glm/glm.hpp>

namespace engine {

// common/brdf.glsl's floors: alpha (below it alpha^4 underflows in fp32) and n . v (interpolated
// normals can face slightly away from the viewer).
constexpr double kMinAlpha = 1e-3;
constexpr double kMinNv = 1e-4;

double ggxD(double nh, double a2);
// V = G2 / (4 |n.l| |n.v|).
double smithGgxCorrelatedV(double nv, double nl, double a2);
// F0 + (F90 - F0)(1 - v.h)^5 (F90 = 1 without KHR_materials_specular).
glm::dvec3 schlickFresnel(glm::dvec3 f0, double f90, double vh);

// The GGX specular BRDF f_s(l, v) (no cosine) for unit n, v (to the viewer), l (to the light)
// and perceptual roughness r, Fresnel F0 and F90; 0 when l is below the surface.
glm::dvec3 ggxSpecular(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, glm::dvec3 f0, double f90,
                       double roughness);

}  // namespace engine
