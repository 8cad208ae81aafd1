// The Vulkan 1.3 instance, one compute-capable device and its queue. Knows nothing of GI.
// The device is picked by ContextOptions::device, else the VSGL_DEVICE environment variable
// (an index into the list vsgl programs print with --list-devices, or a case-insensitive
// substring of the device name), else the first discrete GPU, else any conformant device.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "engine/error.h"

// Checks every VkResult, in release builds too: a failed call on a user's machine is an
// environment problem (out of memory, lost device) that must surface as a clear error.
#define VK_CHECK(expr)                                                               \
  do {                                                                               \
    VkResult vkCheckResult_ = (expr);                                                \
    if (vkCheckResult_ != VK_SUCCESS) ::engine::throwVkError(#expr, vkCheckResult_); \
  } while (0)

namespace engine {

[[noreturn]] void throwVkError(const char* expression, VkResult result);
const char* vkResultName(VkResult result);

struct ContextOptions {
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation (also: VSGL_VALIDATION=1)
  std::string device;       // index or name substring; empty = VSGL_DEVICE or automatic
};

struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string driver;      // driver name and info, e.g. "llvmpipe" / "Mesa 22.3.6"
  std::string apiVersion;  // "1.3.230"
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::string unsuitableReason;  // empty when the device has everything we need
};

// A device that someone else created and owns (a host renderer). It must be Vulkan 1.3 with
// synchronization2 and maintenance4, VK_KHR_push_descriptor, shaderInt64 and
// shaderBufferInt64Atomics enabled (docs/integration.md).
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;  // the family of the queue the host submits our commands to
  // The feature chain the device was created with (VkDeviceCreateInfo::pNext), checked for the
  // features the module needs; null: only the physical device's support is checked.
  const VkPhysicalDeviceFeatures2* enabledFeatures = nullptr;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  // Borrows a host's device: destroys nothing, never submits or waits (submitAndWait throws),
  // and defers one-time setup commands (initial image layouts) to recordDeferredSetup().
  explicit Context(const ExternalDevice& external);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Every physical device with the reason it cannot be used, if any (for --list-devices).
  static std::vector<DeviceInfo> listDevices();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceInfo& info() const { return info_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  bool validationEnabled() const { return validation_; }

  // Validation-layer messages (warnings and errors) seen so far; tests assert this stays 0.
  uint32_t validationMessageCount() const { return validationMessages_.load(); }
  std::vector<std::string> validationMessages() const;

  // Records commands with `record`, submits them and waits. For uploads, tests and tools; a
  // frame recorded into a host command buffer never calls this (the host submits).
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);
  bool borrowed() const { return borrowed_; }

  // Moves a newly created image from UNDEFINED to `layout` over its whole range: at once with
  // submitAndWait on an owned device; on a borrowed one the barrier waits for the next
  // recordDeferredSetup (the image's tracked layout changes now, so the setup must be recorded
  // before any command that uses the image).
  void initializeLayout(VkImage image, VkImageLayout layout);
  void recordDeferredSetup(VkCommandBuffer cmd);

  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred) const;

  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

  // Compute dispatches recorded so far (engine::ComputeProgram counts them), so the profiler can
  // report how many each pass records, the figure [S3]'s Table 3 compares. Recording into one
  // Context happens on one thread.
  uint64_t dispatchCount() const { return dispatches_; }
  void countDispatch() { ++dispatches_; }

 private:
  static VkBool32 VKAPI_PTR onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT types,
                                           const VkDebugUtilsMessengerCallbackDataEXT* data,
                                           void* user);

  bool validation_ = false;
  bool borrowed_ = false;
  std::vector<VkImageMemoryBarrier2> deferredLayouts_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memoryProperties_{};

  uint64_t dispatches_ = 0;
  std::atomic<uint32_t> validationMessages_{0};
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

}  // namespace engine
