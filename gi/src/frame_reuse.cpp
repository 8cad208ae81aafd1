#include "frame_reuse.h"

namespace gi {

CameraInputs cameraInputs(const FrameInput& in, uint64_t frame) {
  const GBufferImages& g = in.gbuffer;
  CameraInputs c;
  c.generation = in.gbufferGeneration;
  c.unknownIn = in.gbufferGeneration == 0 ? frame : 0;
  c.views = {g.depth.view, g.normal.view, g.diffuse.view, g.specular.view};
  c.depthEncoding = g.depthEncoding;
  c.depthFormat = g.depthFormat;
  c.normalEncoding = g.normalEncoding;
  c.view = in.camera.view;
  c.proj = in.camera.proj;
  return c;
}

SceneInputs sceneInputs(uint64_t serial, const FrameInput& in, uint64_t frame) {
  return {serial, in.sceneGeneration, in.sceneGeneration == 0 ? frame : 0};
}

}  // namespace gi
