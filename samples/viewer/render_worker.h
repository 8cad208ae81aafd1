// vsgl_viewer's render thread. It owns the renderer's Vulkan context, the uploaded scene, the
// host's frame (host_frame.h) and the module (one instance, two in split screen), and renders the
// latest FrameRequest, again and again while it asks for continuous frames. The window never
// waits for it: it posts requests and takes whatever result is newest.
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "engine/vk_context.h"
#include "frame_request.h"

namespace viewer {

class RenderWorker {
 public:
  // Takes `ctx` over: from now on only the render thread uses it.
  explicit RenderWorker(std::unique_ptr<engine::Context> ctx);
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  // The newest request replaces any the thread has not started.
  void post(FrameRequest request);
  // The newest finished frame, once (empty when none arrived since the last call).
  std::optional<FrameResult> take();
  // Validation messages of the renderer's device so far.
  uint32_t validationMessageCount() const;

 private:
  struct State;
  void run();

  std::unique_ptr<State> state_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<FrameRequest> pending_;
  bool pendingIsNew_ = false;
  std::optional<FrameResult> result_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace viewer
