#include "reference/vsgl_shade_reference.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gi {

IndirectRadiance shadeReference(const ShadeReceiver& receiver, std::span<const gpu::Vsgl> vsgls,
                                bool glossy, bool planar, const VsglVisibility& visibility) {
  const double alpha = std::max(receiver.roughness * receiver.roughness, 1e-3);
  const SgGgxReceiver ggx =
      sgGgxReceiver(receiver.normal, receiver.view, alpha, receiver.f0, receiver.f90);
  glm::dvec3 diffuseSum(0.0);  // sum of E e^(l_p) D, times albedo at the end
  IndirectRadiance out;
  for (uint32_t k = 0; k < vsgls.size(); ++k) {
    const double v = visibility ? visibility(k) : 1.0;
    if (v == 0.0) continue;
    const VsglEmission emission = vsglEmission(vsgls[k], planar);
    for (const auto& [lobe, lobeEmission] : {std::pair{&vsgls[k].diffuse, &emission.diffuse},
                                             std::pair{&vsgls[k].specular, &emission.specular}}) {
      if (std::max({lobe->power.r, lobe->power.g, lobe->power.b}) <= 0.0f) continue;
      const VsglIncomingRadiance radiance =
          vsglIncomingRadiance(*lobe, receiver.position, *lobeEmission, receiver.normal);
      const glm::dvec3 e = v * radiance.scale * std::exp(radiance.sg.logAmplitude);
      diffuseSum += e * sgClampedCosineIntegralOverPi(radiance.sg.sharpness,
                                                      glm::dot(radiance.sg.axis, receiver.normal));
      if (glossy) out.glossy += e * sgGgxReflection(radiance.sg, ggx);
    }
  }
  out.diffuse = diffuseSum * receiver.albedo;
  return out;
}

}  // namespace gi
