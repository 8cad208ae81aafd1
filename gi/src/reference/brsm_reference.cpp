#include "reference/brsm_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "reference/sg_math.h"
#include "shared/brsm.h"

namespace gi {

namespace {

// A lobe's SG (axis, Banerjee sharpness) from the sums of one cell.
SgLobe cellLobe(const glm::dvec4& power, const glm::dvec4& position, const glm::dvec4& axis) {
  const gpu::VsglLobe lobe = buildVsglLobe({power, position, axis}, glm::dvec3(0.0));
  return {glm::dvec3(lobe.axisSharpness), lobe.axisSharpness.w};
}

}  // namespace

double reflectedImportance(const std::vector<gpu::Vsgl>& importance, glm::dvec3 receiver,
                           const SgLobe& lobe, bool specular) {
  // The cell lobe as a vMF: an SG whose integral over the sphere is 1.
  const Sg vmf{lobe.axis, lobe.sharpness, -std::log(sgIntegral(lobe.sharpness))};
  double sum = 0.0;
  for (const gpu::Vsgl& v : importance)
    for (int l = 0; l < (specular ? 2 : 1); ++l) {
      gpu::VsglLobe camera = l == 0 ? v.diffuse : v.specular;
      if (!(camera.power.a > 0.0f)) continue;
      camera.power = glm::vec4(camera.power.a);  // the scalar importance weight
      const VsglIncomingRadiance incoming = vsglIncomingRadiance(camera, receiver);
      sum += incoming.scale.x * sgInnerProduct(incoming.sg, vmf);
    }
  return std::min(sum, double(BRSM_MAX_IMPORTANCE));
}

std::vector<glm::dvec4> brsmCellsReference(const AttributePyramids& light, glm::dvec3 origin,
                                           const std::vector<gpu::Vsgl>& importance,
                                           uint32_t gridSize, bool specular) {
  const uint32_t level = uint32_t(std::countr_zero(light[0].size / gridSize));
  std::vector<glm::dvec4> cells(size_t{gridSize} * gridSize, glm::dvec4(0.0));
  for (uint32_t y = 0; y < gridSize; ++y)
    for (uint32_t x = 0; x < gridSize; ++x) {
      auto at = [&](int attribute) { return light[size_t(attribute)].at(level, x, y); };
      const glm::dvec4 diffusePower = at(VSGL_ATTR_DIFFUSE_POWER);
      const glm::dvec4 specularPower = at(VSGL_ATTR_SPECULAR_POWER);
      const double wd = diffusePower.a, ws = specularPower.a;
      if (!(wd + ws > 0.0)) continue;
      const glm::dvec3 receiver = origin + (glm::dvec3(at(VSGL_ATTR_DIFFUSE_POSITION)) +
                                            glm::dvec3(at(VSGL_ATTR_SPECULAR_POSITION))) /
                                               (wd + ws);
      const double id = reflectedImportance(
          importance, receiver,
          cellLobe(diffusePower, at(VSGL_ATTR_DIFFUSE_POSITION), at(VSGL_ATTR_DIFFUSE_AXIS)),
          specular);
      const double is =
          specular ? reflectedImportance(importance, receiver,
                                         cellLobe(specularPower, at(VSGL_ATTR_SPECULAR_POSITION),
                                                  at(VSGL_ATTR_SPECULAR_AXIS)))
                   : 0.0;
      cells[size_t{y} * gridSize + x] = {id, is, id * wd + is * ws, 0.0};
    }
  return cells;
}

std::vector<double> brsmPdfReference(const AttributePyramids& light,
                                     const std::vector<glm::dvec4>& cells, uint32_t gridSize,
                                     double fluxMix) {
  const uint32_t size = light[0].size, shift = uint32_t(std::countr_zero(size / gridSize));
  const VectorPyramid& diffuse = light[VSGL_ATTR_DIFFUSE_POWER];
  const VectorPyramid& specular = light[VSGL_ATTR_SPECULAR_POWER];
  const double meanW = diffuse.levels.back()[0].a + specular.levels.back()[0].a;
  double meanB = 0.0;
  for (const glm::dvec4& c : cells) meanB += c.b;
  meanB /= double(cells.size());
  std::vector<double> pdf(size_t{size} * size, 0.0);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const double wd = diffuse.at(0, x, y).a, ws = specular.at(0, x, y).a;
      const glm::dvec4& cell = cells[size_t{y >> shift} * gridSize + (x >> shift)];
      const double flux = meanW > 0.0 ? (wd + ws) / meanW : 0.0;
      const double brsm = meanB > 0.0 ? (cell.r * wd + cell.g * ws) / meanB : flux;
      pdf[size_t{y} * size + x] = (1.0 - fluxMix) * brsm + fluxMix * flux;
    }
  return pdf;
}

}  // namespace gi
