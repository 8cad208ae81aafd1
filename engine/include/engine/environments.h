// Built-in procedural environments: equirectangular linear RGB images (width x width / 2, y up,
// theta from +y, phi from +x towards +z, row 0 at the top; the conventions of
// gi/src/reference/env_paraboloid.h), for tests, benchmarks and the sample host when no file is
// given. Every texel is the environment at the direction of its centre (point sampled, so the
// hard edges alias at small widths, as a photographed map's would not).
//
//   "sky"     a sky gradient from kSkyHorizon at the horizon to kSkyZenith overhead, a small
//             sun disc of exactly kSkySunRadiance (angular radius kSkySunAngularRadius around
//             kSkySunDirection) and a darker, uniform ground kSkyGround below the horizon.
//   "studio"  a dark room (walls 0.03, floor 0.05, ceiling 0.02) lit by three bright
//             rectangular area lights (rectangles in (phi, theta), radiance 40, 10 and 20) and a
//             band of high-frequency checker around the horizon (128 cells around, 1.2 and 0.01)
//             whose unfiltered sampling aliases, the pattern of Krivanek and Colbert 2008 Fig. 1.
//   "white"   uniform radiance 1 (the furnace test: a white Lambertian surface reflects 1).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "engine/image_io.h"

namespace engine {

// The sun of "sky": unit direction (elevation 35 degrees, azimuth 60 degrees from +x towards
// +z), angular radius [rad] (2 degrees, 3.8e-3 sr) and radiance [W / (m^2 sr)], so that the
// sun's irradiance at normal incidence is about pi r^2 L = 7.7, 7.3, 6.5.
inline const glm::vec3 kSkySunDirection{0.40957602f, 0.57357644f, 0.70940648f};
inline constexpr float kSkySunAngularRadius = 0.034906585f;
inline const glm::vec3 kSkySunRadiance{2000.0f, 1900.0f, 1700.0f};
inline const glm::vec3 kSkyZenith{0.15f, 0.30f, 0.80f};
inline const glm::vec3 kSkyHorizon{0.85f, 0.90f, 1.00f};
inline const glm::vec3 kSkyGround{0.12f, 0.10f, 0.08f};

// The names makeBuiltinEnvironment accepts, in a fixed order.
std::vector<std::string> builtinEnvironmentNames();

// The named environment as a width x width / 2 equirectangular image (alpha 1). `width`: even,
// in [4, 16384]. Throws engine::Error for an unknown name (listing the names) or a bad width.
ImageRgba32f makeBuiltinEnvironment(const std::string& name, uint32_t width = 1024);

// The radiance an equirectangular environment (the conventions above) sends back along the unit
// `direction` (from the viewer out): read bilinearly, texel centres at (i + 1/2) / width, u
// wrapping and v clamped. What a host draws where its G-buffer sees no surface.
glm::vec3 environmentRadiance(const ImageRgba32f& equirect, glm::vec3 direction);

}  // namespace engine
