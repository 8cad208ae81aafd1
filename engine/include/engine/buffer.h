// A VkBuffer with its own dedicated allocation (the module creates tens of resources, not
// thousands, so a sub-allocator would buy nothing). Move-only RAII.
#pragma once

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "engine/vk_context.h"

namespace engine {

enum class MemoryUsage {
  GpuOnly,   // device-local; filled by shaders or by upload()
  Upload,    // host-visible, coherent; written by the CPU every frame (uniforms, staging)
  Readback,  // host-visible, cached when possible; read by the CPU after a submit
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory);
  // A non-owning Buffer for someone else's buffer (a host's scene geometry).
  static Buffer borrow(VkBuffer buffer, VkDeviceSize size);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const {
    return mapped_;
  }  // non-null for Upload/Readback (and host-visible GpuOnly)

  // Copies bytes into the buffer: directly when it is mapped, else through a staging buffer
  // and a blocking submit (scene upload time, never inside a frame).
  void upload(Context& ctx, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  template <class T>
  void upload(Context& ctx, std::span<const T> data) {
    upload(ctx, data.data(), data.size_bytes());
  }
  // Copies the whole buffer back to the host (blocking; tests and tools only).
  std::vector<std::byte> readback(Context& ctx) const;
  template <class T>
  std::vector<T> readbackAs(Context& ctx) const {
    auto bytes = readback(ctx);
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
  }

 private:
  void release();
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

}  // namespace engine
