// The consumer's use of the module (docs/integration.md shows this file): everything a host
// writes for vsgl::gi, given its device, scene buffers and G-buffer.
#pragma once

#include <gi/indirect_lighting.h>

#include <string>

struct HostScene {
  gi::SceneGeometry geometry;  // buffers, counts, texture views, sampler, bounds
  gi::GBufferImages gbuffer;   // in SHADER_READ_ONLY_OPTIMAL or GENERAL
  gi::Camera camera;
  gi::Light light;
};

// Creates the module, gives it the scene and records one frame into `cmd` (the host submits
// it). Returns the module (its outputs live as long as it does), or null with `error` set.
std::unique_ptr<gi::IndirectLighting> recordIndirect(const gi::DeviceHandles& device,
                                                     const HostScene& scene, VkCommandBuffer cmd,
                                                     gi::FrameOutput* out, std::string* error);
