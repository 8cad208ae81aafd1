// The --light option every sample program shares (vsgl_render, vsgl_reference, vsgl_benchmark,
// vsgl_flicker, vsgl_budget): what lights a scene whose file brings no light, or lights it
// instead of the file's own. The rules are in docs/integration.md, "A scene without lights".
#pragma once

#include <string>
#include <string_view>

#include "engine/scene.h"

namespace samples {

enum class LightChoice {
  Auto,       // the file's lights; a sun when it has none and no environment is given
  Sun,        // the default sun instead of the file's lights
  Headlight,  // a spot at the scene's camera, along its view, instead of the file's lights
  None,       // the file's lights only: a scene without them needs an environment
};

// --light auto|sun|headlight|none; anything else names the accepted words.
LightChoice parseLightChoice(std::string_view option, std::string_view text);
// The option's lines for the programs' --help (a literal, so that usage texts concatenate it).
#define SAMPLES_LIGHT_USAGE                                                                   \
  "  --light auto|sun|headlight|none  auto (default): the file's lights, a sun when it has\n" \
  "                       none and no --environment; sun or headlight: instead of the\n"      \
  "                       file's lights; none: the file's lights only\n"

// The default sun: illuminance kDefaultIlluminance, 50 degrees above the horizon (glTF's +y
// up), arriving over the left shoulder of the scene's camera (the first glTF camera or
// engine::defaultCamera): it travels along the camera's horizontal forward turned 45 degrees to
// its right, so the faces the camera sees are lit, at an angle that shows their shape.
engine::Light defaultSun(const engine::Scene& scene);
// The headlight: a spot at the camera's eye along its view whose cone reaches the corners of an
// image of `aspect` (width / height): outer half-angle 5 % past the half-diagonal of the field of
// view, at most 1.2 rad (0.5 rad for an orthographic camera), inner 80 % of it; its intensity
// kDefaultIlluminance x d^2 for d the distance from the eye to the scene's centre.
engine::Light headlight(const engine::Scene& scene, float aspect);
// W/m^2: the atrium's sun. The sample programs' PNGs are auto-exposed, so the level matters
// only for the EXRs.
constexpr float kDefaultIlluminance = 3.0f;

// Applies `choice` to `scene.lights`. Returns the one line the program prints when it added or
// replaced a light ("" when the file's lights stand as they are). With None, a scene without a
// light and without an environment (`environment` false) throws engine::Error naming the file
// and the options that would light it.
std::string applyLightChoice(engine::Scene& scene, LightChoice choice, bool environment,
                             float aspect);

}  // namespace samples
