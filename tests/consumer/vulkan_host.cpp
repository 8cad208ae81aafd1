#include "vulkan_host.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(result) + ")");
}

VKAPI_ATTR VkBool32 VKAPI_CALL countMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                            VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                            void* user) {
  ++*static_cast<uint32_t*>(user);
  std::fprintf(stderr, "validation: %s\n", data->pMessage);
  return VK_FALSE;
}

bool hasValidationLayer() {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0) return true;
  return false;
}

// An image barrier from `from` to `to`, waiting for all earlier work.
void transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

}  // namespace

VulkanHost::VulkanHost() {
  const bool validation = hasValidationLayer();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vsgl consumer";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = info.enabledExtensionCount = validation ? 1u : 0u;
  info.ppEnabledLayerNames = &layer;
  info.ppEnabledExtensionNames = &extension;
  check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  if (validation) {
    VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    m.pfnUserCallback = countMessage;
    m.pUserData = &validationMessages;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    check(create(instance, &m, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  for (VkPhysicalDevice d : devices) {
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, props.data());
    for (uint32_t f = 0; f < families && !physicalDevice; ++f)
      if (props[f].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        physicalDevice = d;
        queueFamily = f;
      }
  }
  if (!physicalDevice) throw std::runtime_error("no Vulkan device with a compute queue");

  // What gi::DeviceHandles asks for.
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.synchronization2 = VK_TRUE;
  f13.maintenance4 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  f12.shaderBufferInt64Atomics = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f12;
  features.features.shaderInt64 = VK_TRUE;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = queueFamily;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  const char* pushDescriptor = VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queue;
  deviceInfo.enabledExtensionCount = 1;
  deviceInfo.ppEnabledExtensionNames = &pushDescriptor;
  check(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), "vkCreateDevice");
  vkGetDeviceQueue(device, queueFamily, 0, &queue_);
  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.queueFamilyIndex = queueFamily;
  check(vkCreateCommandPool(device, &pool, nullptr, &pool_), "vkCreateCommandPool");
}

VulkanHost::~VulkanHost() {
  vkDeviceWaitIdle(device);
  for (VkSampler s : samplers_) vkDestroySampler(device, s, nullptr);
  for (HostImage& i : images_) {
    vkDestroyImageView(device, i.view, nullptr);
    vkDestroyImage(device, i.image, nullptr);
    vkFreeMemory(device, i.memory, nullptr);
  }
  for (HostBuffer& b : buffers_) destroy(b);
  vkDestroyCommandPool(device, pool_, nullptr);
  vkDestroyDevice(device, nullptr);
  if (messenger_) {
    auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroyMessenger(instance, messenger_, nullptr);
  }
  vkDestroyInstance(instance, nullptr);
}

VkDeviceMemory VulkanHost::allocate(VkMemoryRequirements requirements,
                                    VkMemoryPropertyFlags properties) {
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memory);
  for (uint32_t t = 0; t < memory.memoryTypeCount; ++t)
    if ((requirements.memoryTypeBits & (1u << t)) &&
        (memory.memoryTypes[t].propertyFlags & properties) == properties) {
      VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
      info.allocationSize = requirements.size;
      info.memoryTypeIndex = t;
      VkDeviceMemory result;
      check(vkAllocateMemory(device, &info, nullptr, &result), "vkAllocateMemory");
      return result;
    }
  throw std::runtime_error("no suitable memory type");
}

HostBuffer VulkanHost::staging(VkDeviceSize bytes) {
  HostBuffer b;
  b.size = bytes;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = bytes;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
               VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  check(vkCreateBuffer(device, &info, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, b.buffer, &requirements);
  b.memory = allocate(requirements,
                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  check(vkBindBufferMemory(device, b.buffer, b.memory, 0), "vkBindBufferMemory");
  return b;
}

void VulkanHost::destroy(HostBuffer& b) {
  vkDestroyBuffer(device, b.buffer, nullptr);
  vkFreeMemory(device, b.memory, nullptr);
}

HostBuffer VulkanHost::buffer(const void* data, VkDeviceSize bytes) {
  HostBuffer b = staging(bytes);
  void* mapped = nullptr;
  check(vkMapMemory(device, b.memory, 0, bytes, 0, &mapped), "vkMapMemory");
  std::memcpy(mapped, data, bytes);
  vkUnmapMemory(device, b.memory);
  buffers_.push_back(b);
  return b;
}

HostImage VulkanHost::image(VkFormat format, uint32_t width, uint32_t height,
                            VkImageUsageFlags usage, uint32_t layers, bool array) {
  HostImage i;
  i.width = width;
  i.height = height;
  i.layers = layers;
  i.aspect = format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.usage = usage | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  check(vkCreateImage(device, &info, nullptr, &i.image), "vkCreateImage");
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device, i.image, &requirements);
  i.memory = allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkBindImageMemory(device, i.image, i.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = i.image;
  view.viewType = array || layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {i.aspect, 0, 1, 0, layers};
  check(vkCreateImageView(device, &view, nullptr, &i.view), "vkCreateImageView");
  images_.push_back(i);
  return i;
}

void VulkanHost::upload(const HostImage& image, const void* texels, VkDeviceSize bytes,
                        VkImageLayout layout) {
  HostBuffer s = staging(bytes);
  void* mapped = nullptr;
  check(vkMapMemory(device, s.memory, 0, bytes, 0, &mapped), "vkMapMemory");
  std::memcpy(mapped, texels, bytes);
  vkUnmapMemory(device, s.memory);
  submit([&](VkCommandBuffer cmd) {
    transition(cmd, image.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               image.aspect);
    for (uint32_t layer = 0; layer < image.layers; ++layer) {
      VkBufferImageCopy copy{};
      copy.imageSubresource = {image.aspect, 0, layer, 1};
      copy.imageExtent = {image.width, image.height, 1};
      vkCmdCopyBufferToImage(cmd, s.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                             &copy);
    }
    transition(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout, image.aspect);
  });
  destroy(s);
}

std::vector<float> VulkanHost::readRgba32f(const HostImage& image, VkImageLayout layout) {
  const VkDeviceSize bytes = VkDeviceSize{image.width} * image.height * 16;
  HostBuffer s = staging(bytes);
  submit([&](VkCommandBuffer cmd) {
    transition(cmd, image.image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {image.width, image.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s.buffer, 1,
                           &copy);
    transition(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
  });
  std::vector<float> texels(bytes / 4);
  void* mapped = nullptr;
  check(vkMapMemory(device, s.memory, 0, bytes, 0, &mapped), "vkMapMemory");
  std::memcpy(texels.data(), mapped, bytes);
  vkUnmapMemory(device, s.memory);
  destroy(s);
  return texels;
}

VkSampler VulkanHost::sampler() {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler s;
  check(vkCreateSampler(device, &info, nullptr, &s), "vkCreateSampler");
  samplers_.push_back(s);
  return s;
}

void VulkanHost::submit(const std::function<void(VkCommandBuffer)>& work) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  check(vkAllocateCommandBuffers(device, &alloc, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  work(cmd);
  check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo submitInfo{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submitInfo.commandBufferCount = 1;
  submitInfo.pCommandBuffers = &cmd;
  check(vkQueueSubmit(queue_, 1, &submitInfo, VK_NULL_HANDLE), "vkQueueSubmit");
  check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
  vkFreeCommandBuffers(device, pool_, 1, &cmd);
}
