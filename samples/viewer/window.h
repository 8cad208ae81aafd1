// vsgl_viewer's window: GLFW for the window and input, a Vulkan swapchain, and Dear ImGui for the
// panel. The window has a logical device of its own on the same physical device as the renderer
// (render_worker.h): the frame is rendered there on another thread, and this device only shows
// the last finished frame and draws the panel, so the panel never waits for a slow frame (one
// queue would serialise the two; docs/viewer.md).
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

struct GLFWwindow;

namespace viewer {

// Where the frame is shown, in window pixels (x, y from the top left).
struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
};

class Window {
 public:
  // Opens a width x height window. `deviceUuid` (VkPhysicalDeviceIDProperties::deviceUUID) picks
  // the renderer's physical device. Throws engine::Error with one line when there is no display
  // or the device cannot present to it.
  Window(const std::string& title, uint32_t width, uint32_t height, bool validation,
         const std::array<uint8_t, VK_UUID_SIZE>& deviceUuid);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* glfw() const { return window_; }
  bool shouldClose() const;
  // The window's size in pixels (the framebuffer's).
  std::array<int, 2> size() const;

  // Starts the panel's frame (ImGui::NewFrame); the caller builds the panel, then present().
  void beginPanel();
  // Replaces the frame shown: width x height RGBA8, sRGB-encoded (the tone-mapped frame).
  void setImage(std::span<const uint8_t> rgba, uint32_t width, uint32_t height);
  // Draws the frame into `area` (scaled to fit, centred), then the panel, and presents. With
  // `capture`, the window's pixels (panel included) are read back into captured().
  void present(const Rect& area, bool capture);
  // The last capture: RGBA8, top row first, of capturedSize().
  const std::vector<uint8_t>& captured() const { return captured_; }
  std::array<int, 2> capturedSize() const { return capturedSize_; }

  uint32_t validationMessageCount() const { return validationMessages_; }
  const std::vector<std::string>& validationMessages() const { return messages_; }

 private:
  static VkBool32 VKAPI_PTR onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT types,
                                           const VkDebugUtilsMessengerCallbackDataEXT* data,
                                           void* user);
  void createDevice(const std::array<uint8_t, VK_UUID_SIZE>& deviceUuid);
  void createSwapchain();
  void destroySwapchain();
  void createImageResources(uint32_t width, uint32_t height);
  void destroyImageResources();
  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
  // A host-visible, coherent buffer of `bytes` bound to new memory.
  void createHostBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkBuffer& buffer,
                        VkDeviceMemory& memory);
  void record(VkCommandBuffer cmd, uint32_t imageIndex, const Rect& area, bool capture);

  GLFWwindow* window_ = nullptr;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE, rendered_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;

  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  bool imguiReady_ = false;

  // The frame shown: a host-visible staging buffer and an image it is copied into.
  uint32_t imageWidth_ = 0, imageHeight_ = 0;
  bool imageDirty_ = false;
  VkBuffer staging_ = VK_NULL_HANDLE;
  VkDeviceMemory stagingMemory_ = VK_NULL_HANDLE;
  void* stagingMapped_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory imageMemory_ = VK_NULL_HANDLE;
  bool imageInitialised_ = false;

  // Window capture: a host-visible buffer the swapchain image is copied into.
  VkBuffer readback_ = VK_NULL_HANDLE;
  VkDeviceMemory readbackMemory_ = VK_NULL_HANDLE;
  VkDeviceSize readbackBytes_ = 0;
  std::vector<uint8_t> captured_;
  std::array<int, 2> capturedSize_{0, 0};

  uint32_t validationMessages_ = 0;
  std::vector<std::string> messages_;
};

}  // namespace viewer
