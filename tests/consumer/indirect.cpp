#include "indirect.h"

std::unique_ptr<gi::IndirectLighting> recordIndirect(const gi::DeviceHandles& device,
                                                     const HostScene& scene, VkCommandBuffer cmd,
                                                     gi::FrameOutput* out, std::string* error) {
  // Once, after the device and the scene buffers exist. Every field of gi::Settings states its
  // default, range, unit and cost (gi/settings.h).
  gi::Settings settings;
  settings.vsglCount = 64;  // the paper's 1024 is the default; fewer is cheaper
  settings.rsmSize = 128;
  gi::Status status;
  std::unique_ptr<gi::IndirectLighting> module = gi::IndirectLighting::create(
      device, settings, scene.gbuffer.width, scene.gbuffer.height, &status);
  if (!module) {
    *error = status.message;  // one line naming the field and the problem
    return nullptr;
  }
  if (gi::Status s = module->setScene(scene.geometry); !s) {
    *error = s.message;
    return nullptr;
  }

  // Every frame, after the G-buffer pass, inside the host's command buffer: the module reads
  // the G-buffer, renders the light's view from the scene buffers and writes its two images.
  gi::FrameInput in;
  in.gbuffer = scene.gbuffer;
  in.camera = scene.camera;
  in.lights = {scene.light};  // up to gi::kMaxLights, of every KHR_lights_punctual type
  if (gi::Status s = module->record(cmd, in, out); !s) {
    *error = s.message;
    return nullptr;
  }
  // The G-buffer is now in out->gbufferLayout (GENERAL); out->indirectDiffuse and
  // out->indirectGlossy (RGBA32F radiance, GENERAL) are ready for the host's composite pass.
  return module;
}
