// A bare Vulkan 1.3 host for the consumer test: an instance (with the Khronos validation layer
// when it is installed, its warnings and errors counted), the first device with a compute queue
// and the features gi::DeviceHandles lists, and just enough to make buffers and images, fill
// them and read them back. Nothing of the module's own engine: a host has none of it.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <vector>

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
};

struct HostImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  uint32_t width = 0, height = 0, layers = 1;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;  // DEPTH for a D32 image
};

class VulkanHost {
 public:
  VulkanHost();
  ~VulkanHost();
  VulkanHost(const VulkanHost&) = delete;
  VulkanHost& operator=(const VulkanHost&) = delete;

  // A storage buffer in host-visible memory holding `bytes` of `data`.
  HostBuffer buffer(const void* data, VkDeviceSize bytes);
  // A 2-D image (an array view when `layers` > 1 or `array`) of one mip level.
  HostImage image(VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage,
                  uint32_t layers = 1, bool array = false);
  // Copies `texels` into every layer of `image` and leaves it in `layout`.
  void upload(const HostImage& image, const void* texels, VkDeviceSize bytes,
              VkImageLayout layout);
  // The RGBA32F texels of `image`, which is in `layout`.
  std::vector<float> readRgba32f(const HostImage& image, VkImageLayout layout);
  VkSampler sampler();
  // Records with `work`, submits and waits.
  void submit(const std::function<void(VkCommandBuffer)>& work);

  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  uint32_t validationMessages = 0;  // warnings and errors the layer reported

 private:
  VkDeviceMemory allocate(VkMemoryRequirements requirements, VkMemoryPropertyFlags properties);
  HostBuffer staging(VkDeviceSize bytes);
  void destroy(HostBuffer& b);

  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::vector<HostBuffer> buffers_;
  std::vector<HostImage> images_;
  std::vector<VkSampler> samplers_;
};
