#include "embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/alpha_cutout.h"
#include "engine/error.h"

namespace truth {

// What the alpha test of a hit needs (engine/alpha_cutout.h), kept beside the BVH.
struct Cutouts {
  engine::AlphaCutouts test;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> triangleMaterial;

  Cutouts(engine::AlphaCutouts cutouts, const engine::Scene& scene)
      : test(std::move(cutouts)),
        uvs(scene.uvs),
        indices(scene.indices),
        triangleMaterial(scene.triangleMaterial) {
    uvs.resize(scene.positions.size(), glm::vec2(0.0f));
  }

  // Whether the surface exists at barycentrics (u, v) of `triangle` (the alpha test's rule).
  bool keeps(uint32_t triangle, float u, float v) const {
    const glm::vec2 corners[3] = {uvs[indices[3 * size_t{triangle}]],
                                  uvs[indices[3 * size_t{triangle} + 1]],
                                  uvs[indices[3 * size_t{triangle} + 2]]};
    return test.opaqueAt(triangleMaterial[triangle], corners, glm::vec2(u, v));
  }
};

namespace {

// Embree's intersection and occlusion filter: a hit where an alpha test cuts the surface is no
// hit, and traversal goes on behind it.
void cutoutFilter(const RTCFilterFunctionNArguments* args) {
  const auto* cutouts = static_cast<const Cutouts*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (!cutouts->keeps(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                        RTCHitN_v(args->hit, args->N, i)))
      args->valid[i] = 0;
  }
}

}  // namespace

struct EmbreeScene::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::unique_ptr<Cutouts> cutouts;  // alpha-tested scenes only
};

EmbreeScene::EmbreeScene(const engine::Scene& scene) : handles_(std::make_unique<Handles>()) {
  if (scene.triangleCount() == 0) throw engine::Error("Embree: the scene has no triangles");
  handles_->device = rtcNewDevice(nullptr);
  if (!handles_->device)
    throw engine::Error("Embree: cannot create a device (error " +
                        std::to_string(rtcGetDeviceError(nullptr)) + ")");
  handles_->scene = rtcNewScene(handles_->device);
  // Robust traversal: rays through shared edges and vertices of the closed built-in scenes must
  // not slip between triangles (a leak would light a closed box from outside).
  rtcSetSceneFlags(handles_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(handles_->scene, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geometry = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               scene.positions.size()));
  for (size_t i = 0; i < scene.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = scene.positions[i][k];
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(uint32_t), scene.triangleCount()));
  std::copy(scene.indices.begin(), scene.indices.end(), indices);
  if (engine::AlphaCutouts cutouts(scene); cutouts.any()) {
    handles_->cutouts = std::make_unique<Cutouts>(std::move(cutouts), scene);
    rtcSetGeometryUserData(geometry, handles_->cutouts.get());
    rtcSetGeometryIntersectFilterFunction(geometry, cutoutFilter);
    rtcSetGeometryOccludedFilterFunction(geometry, cutoutFilter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(handles_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(handles_->scene);
  if (RTCError e = rtcGetDeviceError(handles_->device); e != RTC_ERROR_NONE)
    throw engine::Error("Embree: building the scene failed (error " + std::to_string(e) + ")");
}

EmbreeScene::~EmbreeScene() {
  if (handles_->scene) rtcReleaseScene(handles_->scene);
  if (handles_->device) rtcReleaseDevice(handles_->device);
}

namespace {

RTCRay makeRay(glm::dvec3 origin, glm::dvec3 dir, double tnear, double tfar) {
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x);
  ray.org_y = static_cast<float>(origin.y);
  ray.org_z = static_cast<float>(origin.z);
  ray.dir_x = static_cast<float>(dir.x);
  ray.dir_y = static_cast<float>(dir.y);
  ray.dir_z = static_cast<float>(dir.z);
  ray.tnear = static_cast<float>(tnear);
  ray.tfar = std::isinf(tfar) ? std::numeric_limits<float>::infinity() : static_cast<float>(tfar);
  ray.mask = ~0u;
  return ray;
}

}  // namespace

RayHit EmbreeScene::intersect(glm::dvec3 origin, glm::dvec3 dir, double tnear, double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayHit{};
  rayHit.ray = makeRay(origin, dir, tnear, tfar);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(handles_->scene, &context, &rayHit);
  RayHit r;
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return r;
  r.hit = true;
  r.t = rayHit.ray.tfar;
  r.triangle = rayHit.hit.primID;
  r.barycentrics = glm::dvec2(rayHit.hit.u, rayHit.hit.v);
  return r;
}

bool EmbreeScene::occluded(glm::dvec3 origin, glm::dvec3 dir, double tnear, double tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = makeRay(origin, dir, tnear, tfar);
  rtcOccluded1(handles_->scene, &context, &ray);
  // Embree marks an occluded ray by setting tfar to -inf.
  return ray.tfar < 0.0f;
}

bool EmbreeScene::visible(glm::dvec3 from, glm::dvec3 to) const {
  const glm::dvec3 d = to - from;
  const double length = glm::length(d);
  return length <= 0.0 || !occluded(from, d / length, 0.0, length);
}

glm::dvec3 offsetOrigin(glm::dvec3 p, glm::dvec3 ng) {
  const double scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1.0});
  return p + ng * (scale * 0x1p-16);
}

}  // namespace truth
