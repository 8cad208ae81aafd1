// The CPU twin of vpl_shade.comp: the VPL baseline's instant-radiosity shading of one receiver
// (docs/techniques/vpl-baseline.md), in double. Each record is a one-texel VPL
// (VSGL_RULE_POINT): a point on its surface carrying both lobes' power, whose disc of area
// 4 pi v (v the lobes' variance) bounds the 1 / d^2 and widens both glossy lobes.
#pragma once

#include <span>

#include "reference/vsgl_shade_reference.h"
#include "shared/vsgl.h"

namespace gi {

// `glossy` false: the glossy output is 0. `diffuseLobesOnly`: the VPLs' specular power is left
// out (VSGL_SHADE_DIFFUSE_LOBES).
IndirectRadiance shadeVplsReference(const ShadeReceiver& receiver, std::span<const gpu::Vsgl> vpls,
                                    bool glossy, bool diffuseLobesOnly = false,
                                    const VsglVisibility& visibility = {});

}  // namespace gi
