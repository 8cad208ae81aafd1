// CPU twin of the G-buffer resolve (shaders/raster/gbuffer_resolve.comp) and a decoder of the
// GPU G-buffer, both producing decoded values in double so tests compare like with like.
//
// The reference follows the shader step by step (camera ray through the pixel centre hits the
// plane of the visible triangle, barycentrics interpolate normal and UV, the normal flips to
// face the viewer by the geometric normal, glTF metallic-roughness factors times textures) but
// in double and without the storage formats' quantisation. One deliberate difference: textures
// are sampled bilinearly on mip 0 of the Scene's own Texture (sRGB base colour decoded before
// filtering, as the GPU's sRGB format does), whereas the GPU filters trilinearly, with
// ray-differential gradients, a mip chain of the texture resampled to a power-of-two square.
// The two agree exactly only for constant textures and, up to the sampler's sub-texel
// precision, for magnified power-of-two textures (mip 0 only); tests compare textured
// results only there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "engine/gbuffer.h"
#include "engine/scene.h"
#include "engine/view.h"

namespace engine {

// One G-buffer texel, decoded. Background texels (nothing visible) hold depth 1 and zeros.
struct GBufferSample {
  float depth = 1.0f;        // Vulkan NDC depth, the visibility buffer's float bits
  glm::dvec3 normal{0.0};    // world-space unit shading normal, facing the viewer
  glm::dvec3 diffuse{0.0};   // base colour * (1 - metallic)
  double roughness = 0.0;    // perceptual, GGX alpha = roughness^2
  glm::dvec3 f0{0.0};        // mix(0.04 x specular colour x strength, base colour, metallic)
  double f90 = 0.0;          // Schlick's grazing reflectance: mix(specular strength, 1, metallic)
  glm::dvec3 emission{0.0};  // emitted radiance: emissive factor x texture (0 on a black back)

  bool background() const { return depth >= 1.0f; }
};

struct GBufferData {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<GBufferSample> samples;  // row-major, row 0 at the top of the image

  const GBufferSample& at(uint32_t x, uint32_t y) const { return samples[size_t{y} * width + x]; }
};

// The resolve of `visibility` (view.width * view.height texels as the rasterizer writes them)
// computed in double.
GBufferData resolveGBufferReference(const Scene& scene, const View& view,
                                    std::span<const uint64_t> visibility,
                                    BackFaces backFaces = BackFaces::AsFront);

// Decodes the raw bytes of the G-buffer images (Image::readback, formats of
// shaders/shared/gbuffer.h); `emission` may be empty (then 0). Normals are decoded from
// RG16_SNORM and the octahedral map in double, so the only difference to the reference left is
// the storage quantisation.
GBufferData decodeGBuffer(uint32_t width, uint32_t height, std::span<const std::byte> depth,
                          std::span<const std::byte> normal, std::span<const std::byte> diffuse,
                          std::span<const std::byte> specular,
                          std::span<const std::byte> emission = {});

// Reads the five images back (blocking) and decodes them.
GBufferData readbackGBuffer(Context& ctx, GBuffer& gbuffer);

// The camera ray through `pixel` (pixel units, (0, 0) the top-left corner of the image) as
// camera_ray.glsl builds it: from the near plane through the depth-0.5 point, unit direction.
struct CameraRay {
  glm::dvec3 origin;
  glm::dvec3 dir;
};
CameraRay cameraRayReference(const View& view, glm::dvec2 pixel);

// The surface of triangle `triangle` at barycentrics (u, v) (weights of its vertices 1 and 2)
// seen along `rayDir`, as the resolve decodes it: interpolated normal, perturbed by the material's
// normal map, flipped to face the ray's origin by the geometric normal, material factors times
// bilinear textures. depth is 0 (not a
// background sample). The CPU references (path tracer, VPL gather) shade their hits with it:
// camera hits with AsFront, the surfaces that bounce the light with PerMaterial (BackFaces).
GBufferSample surfaceAt(const Scene& scene, uint32_t triangle, glm::dvec2 barycentrics,
                        glm::dvec3 rayDir, BackFaces backFaces = BackFaces::AsFront);

// A tangent-space normal map's normal (gbuffer_resolve.comp does the same in fp32). `normal` is
// the interpolated front normal, `corners` the triangle and `uvs` its corners' (transformed)
// texture coordinates, `mapped` the map's texel decoded to [-1, 1] with x and y scaled. The
// tangent frame is the triangle's, from the corners and their coordinates: T along dp/du made
// orthogonal to `normal`, and B = normal x T, which points up the image (against dp/dv: glTF's v
// runs down, and its maps' +Y is up), negated where the coordinates are mirrored (dp/du x dp/dv
// along `normal`). Returns `normal` where the coordinates give no frame (a triangle without
// texture coordinates, or one degenerate in them).
glm::dvec3 perturbedNormal(glm::dvec3 normal, const glm::dvec3 corners[3], const glm::dvec2 uvs[3],
                           glm::dvec3 mapped);

// sRGB transfer function inverse (IEC 61966-2-1), encoded [0, 1] -> linear, in double.
double srgbToLinear(double encoded);

}  // namespace engine
