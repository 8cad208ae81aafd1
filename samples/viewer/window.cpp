#include "window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <cstring>

#include "engine/error.h"
#include "engine/vk_context.h"

namespace viewer {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string glfwProblem() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

void checkImgui(VkResult result) {
  if (result != VK_SUCCESS) engine::throwVkError("Dear ImGui's Vulkan back end", result);
}

VkImageMemoryBarrier barrier(VkImage image, VkImageLayout from, VkImageLayout to,
                             VkAccessFlags srcAccess, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  return b;
}

void pipelineBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                     const VkImageMemoryBarrier& b) {
  vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace

VkBool32 VKAPI_PTR Window::onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  auto* self = static_cast<Window*>(user);
  ++self->validationMessages_;
  self->messages_.emplace_back(data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

Window::Window(const std::string& title, uint32_t width, uint32_t height, bool validation,
               const std::array<uint8_t, VK_UUID_SIZE>& deviceUuid) {
  if (!glfwInit())
    throw engine::Error("no display: " + glfwProblem() +
                        " (run it on a desktop, or under Xvfb: xvfb-run vsgl_viewer ...)");
  if (!glfwVulkanSupported())
    throw engine::Error("no display: GLFW finds no Vulkan loader that can present");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window_) throw engine::Error("no window: " + glfwProblem());

  uint32_t glfwCount = 0;
  const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
  std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
  if (validation) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vsgl_viewer";
  app.apiVersion = VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  info.enabledLayerCount = validation ? 1u : 0u;
  info.ppEnabledLayerNames = &kValidationLayer;
  VK_CHECK(vkCreateInstance(&info, nullptr, &instance_));
  if (validation) {
    VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    m.pfnUserCallback = &Window::onDebugMessage;
    m.pUserData = this;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(instance_, &m, nullptr, &messenger_));
  }
  VK_CHECK(glfwCreateWindowSurface(instance_, window_, nullptr, &surface_));
  createDevice(deviceUuid);
  createSwapchain();

  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the panel's layout is the program's, not a file's
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = instance_;
  init.PhysicalDevice = physical_;
  init.Device = device_;
  init.QueueFamily = queueFamily_;
  init.Queue = queue_;
  init.DescriptorPool = descriptorPool_;
  init.MinImageCount = 2;
  init.ImageCount = uint32_t(images_.size());
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkImgui;
  ImGui_ImplVulkan_Init(&init, renderPass_);
  // The font atlas, uploaded once.
  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
  ImGui_ImplVulkan_CreateFontsTexture(cmd_);
  VK_CHECK(vkEndCommandBuffer(cmd_));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  VK_CHECK(vkQueueSubmit(queue_, 1, &submit, VK_NULL_HANDLE));
  VK_CHECK(vkQueueWaitIdle(queue_));
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  imguiReady_ = true;
}

Window::~Window() {
  if (device_) vkDeviceWaitIdle(device_);
  if (imguiReady_) {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (device_) {
    destroyImageResources();
    if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
    if (readbackMemory_) vkFreeMemory(device_, readbackMemory_, nullptr);
    destroySwapchain();
    vkDestroyRenderPass(device_, renderPass_, nullptr);
    vkDestroyDescriptorPool(device_, descriptorPool_, nullptr);
    vkDestroySemaphore(device_, acquired_, nullptr);
    vkDestroySemaphore(device_, rendered_, nullptr);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::createDevice(const std::array<uint8_t, VK_UUID_SIZE>& deviceUuid) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &id};
    vkGetPhysicalDeviceProperties2(d, &props);
    if (std::memcmp(id.deviceUUID, deviceUuid.data(), VK_UUID_SIZE) == 0) physical_ = d;
  }
  if (!physical_) throw engine::Error("no display: the renderer's Vulkan device is not listed");
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, families.data());
  bool found = false;
  for (uint32_t i = 0; i < count && !found; ++i) {
    VkBool32 present = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(physical_, i, surface_, &present);
    if (present && (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) {
      queueFamily_ = i;
      found = true;
    }
  }
  if (!found)
    throw engine::Error("no display: the renderer's Vulkan device cannot present to the window");
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = queueFamily_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  const char* extensions[] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.enabledExtensionCount = 1;
  info.ppEnabledExtensionNames = extensions;
  VK_CHECK(vkCreateDevice(physical_, &info, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool_));
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &cmd_));
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VK_CHECK(vkCreateFence(device_, &fence, nullptr, &fence_));
  VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(device_, &semaphore, nullptr, &acquired_));
  VK_CHECK(vkCreateSemaphore(device_, &semaphore, nullptr, &rendered_));
  // The panel's font atlas is its only texture.
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool.maxSets = 4;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  VK_CHECK(vkCreateDescriptorPool(device_, &pool, nullptr, &descriptorPool_));

  // The swapchain's format: 8-bit UNORM, since the frame arrives sRGB-encoded (blits copy it
  // unchanged) and the panel's colours are meant for a non-sRGB target.
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical_, surface_, &count, formats.data());
  for (const VkSurfaceFormatKHR& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) {
      format_ = f.format;
      break;
    }
  if (format_ == VK_FORMAT_UNDEFINED)
    throw engine::Error("no display: the window offers no 8-bit UNORM swapchain format");

  VkAttachmentDescription colour{};
  colour.format = format_;
  colour.samples = VK_SAMPLE_COUNT_1_BIT;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the frame is blitted in before the panel
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 1;
  rp.pAttachments = &colour;
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  VK_CHECK(vkCreateRenderPass(device_, &rp, nullptr, &renderPass_));
}

void Window::createSwapchain() {
  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical_, surface_, &caps));
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  extent_ =
      caps.currentExtent.width != UINT32_MAX
          ? caps.currentExtent
          : VkExtent2D{
                std::clamp(uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width),
                std::clamp(uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
  if (extent_.width == 0 || extent_.height == 0) return;  // minimised: nothing to show
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if ((caps.supportedUsageFlags & usage) != usage)
    throw engine::Error("no display: the window's images cannot be blitted to and read back");
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = std::max(2u, caps.minImageCount);
  if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
  info.imageFormat = format_;
  info.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = usage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available; the panel runs at the display
  info.clipped = VK_TRUE;
  VK_CHECK(vkCreateSwapchainKHR(device_, &info, nullptr, &swapchain_));
  uint32_t count = 0;
  vkGetSwapchainImagesKHR(device_, swapchain_, &count, nullptr);
  images_.resize(count);
  vkGetSwapchainImagesKHR(device_, swapchain_, &count, images_.data());
  for (VkImage image : images_) {
    VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    v.image = image;
    v.viewType = VK_IMAGE_VIEW_TYPE_2D;
    v.format = format_;
    v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VK_CHECK(vkCreateImageView(device_, &v, nullptr, &view));
    views_.push_back(view);
    VkFramebufferCreateInfo f{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    f.renderPass = renderPass_;
    f.attachmentCount = 1;
    f.pAttachments = &view;
    f.width = extent_.width;
    f.height = extent_.height;
    f.layers = 1;
    VkFramebuffer framebuffer;
    VK_CHECK(vkCreateFramebuffer(device_, &f, nullptr, &framebuffer));
    framebuffers_.push_back(framebuffer);
  }
}

void Window::destroySwapchain() {
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(device_, f, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(device_, v, nullptr);
  framebuffers_.clear();
  views_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

uint32_t Window::memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical_, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw engine::Error("no display: no Vulkan memory type for the window's frame");
}

void Window::createHostBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkBuffer& buffer,
                              VkDeviceMemory& memory) {
  VkBufferCreateInfo b{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  b.size = bytes;
  b.usage = usage;
  VK_CHECK(vkCreateBuffer(device_, &b, nullptr, &buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, buffer, &req);
  VkMemoryAllocateInfo a{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  a.allocationSize = req.size;
  a.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                         VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VK_CHECK(vkAllocateMemory(device_, &a, nullptr, &memory));
  VK_CHECK(vkBindBufferMemory(device_, buffer, memory, 0));
}

void Window::createImageResources(uint32_t width, uint32_t height) {
  destroyImageResources();
  imageWidth_ = width;
  imageHeight_ = height;
  createHostBuffer(VkDeviceSize{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging_,
                   stagingMemory_);
  VK_CHECK(vkMapMemory(device_, stagingMemory_, 0, VK_WHOLE_SIZE, 0, &stagingMapped_));

  VkMemoryRequirements req;
  VkMemoryAllocateInfo a{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  VkImageCreateInfo i{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  i.imageType = VK_IMAGE_TYPE_2D;
  i.format = VK_FORMAT_R8G8B8A8_UNORM;
  i.extent = {width, height, 1};
  i.mipLevels = 1;
  i.arrayLayers = 1;
  i.samples = VK_SAMPLE_COUNT_1_BIT;
  i.tiling = VK_IMAGE_TILING_OPTIMAL;
  i.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  VK_CHECK(vkCreateImage(device_, &i, nullptr, &image_));
  vkGetImageMemoryRequirements(device_, image_, &req);
  a.allocationSize = req.size;
  a.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VK_CHECK(vkAllocateMemory(device_, &a, nullptr, &imageMemory_));
  VK_CHECK(vkBindImageMemory(device_, image_, imageMemory_, 0));
  imageInitialised_ = false;
}

void Window::destroyImageResources() {
  if (staging_) vkDestroyBuffer(device_, staging_, nullptr);
  if (stagingMemory_) vkFreeMemory(device_, stagingMemory_, nullptr);
  if (image_) vkDestroyImage(device_, image_, nullptr);
  if (imageMemory_) vkFreeMemory(device_, imageMemory_, nullptr);
  staging_ = VK_NULL_HANDLE;
  stagingMemory_ = imageMemory_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  stagingMapped_ = nullptr;
  imageWidth_ = imageHeight_ = 0;
}

bool Window::shouldClose() const {
  return glfwWindowShouldClose(window_);
}

std::array<int, 2> Window::size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

void Window::beginPanel() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Window::setImage(std::span<const uint8_t> rgba, uint32_t width, uint32_t height) {
  // The previous present may still read the staging buffer.
  VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  if (width != imageWidth_ || height != imageHeight_) createImageResources(width, height);
  std::memcpy(stagingMapped_, rgba.data(),
              std::min<size_t>(rgba.size(), size_t{width} * height * 4));
  imageDirty_ = true;
}

void Window::record(VkCommandBuffer cmd, uint32_t index, const Rect& area, bool capture) {
  VkImage target = images_[index];
  const VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const VkPipelineStageFlags top = VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT;
  if (imageDirty_ && image_) {
    pipelineBarrier(
        cmd, imageInitialised_ ? transfer : top, transfer,
        barrier(
            image_,
            imageInitialised_ ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
            imageInitialised_ ? VK_ACCESS_TRANSFER_READ_BIT : 0, VK_ACCESS_TRANSFER_WRITE_BIT));
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {imageWidth_, imageHeight_, 1};
    vkCmdCopyBufferToImage(cmd, staging_, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    pipelineBarrier(
        cmd, transfer, transfer,
        barrier(image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT));
    imageDirty_ = false;
    imageInitialised_ = true;
  }
  // The submit waits for the acquire at the transfer stage, which this barrier chains after.
  pipelineBarrier(cmd, transfer, transfer,
                  barrier(target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          0, VK_ACCESS_TRANSFER_WRITE_BIT));
  VkClearColorValue grey{{0.08f, 0.08f, 0.08f, 1.0f}};
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &range);
  if (imageInitialised_ && area.width > 0 && area.height > 0) {
    // Scaled to fit the area, centred; nearest filtering keeps the pixels the renderer wrote
    // when the scale is 1 (a screenshot of the window shows the frame's own values).
    const double scale =
        std::min(double(area.width) / imageWidth_, double(area.height) / imageHeight_);
    const int w = std::max(1, int(imageWidth_ * scale)), h = std::max(1, int(imageHeight_ * scale));
    const int x = area.x + (area.width - w) / 2, y = area.y + (area.height - h) / 2;
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(imageWidth_), int32_t(imageHeight_), 1};
    blit.dstOffsets[0] = {std::max(x, 0), std::max(y, 0), 0};
    blit.dstOffsets[1] = {std::min(x + w, int(extent_.width)), std::min(y + h, int(extent_.height)),
                          1};
    pipelineBarrier(
        cmd, transfer, transfer,
        barrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_WRITE_BIT));
    vkCmdBlitImage(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   scale == 1.0 ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  }
  pipelineBarrier(
      cmd, transfer, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
      barrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
              VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT));
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = renderPass_;
  rp.framebuffer = framebuffers_[index];
  rp.renderArea.extent = extent_;
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
  if (capture) {
    pipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, transfer,
                    barrier(target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT));
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent_.width, extent_.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_, 1, &copy);
    pipelineBarrier(cmd, transfer, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                    barrier(target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_ACCESS_TRANSFER_READ_BIT, 0));
  } else {
    pipelineBarrier(
        cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
        barrier(target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0));
  }
}

void Window::present(const Rect& area, bool capture) {
  ImGui::Render();
  if (!swapchain_) {  // minimised, or out of date: try again at this size
    createSwapchain();
    if (!swapchain_) return;
  }
  VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  uint32_t index = 0;
  VkResult acquired =
      vkAcquireNextImageKHR(device_, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    VK_CHECK(vkDeviceWaitIdle(device_));
    destroySwapchain();
    return;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);
  if (capture) {
    const VkDeviceSize bytes = VkDeviceSize{extent_.width} * extent_.height * 4;
    if (bytes > readbackBytes_) {
      if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
      if (readbackMemory_) vkFreeMemory(device_, readbackMemory_, nullptr);
      createHostBuffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, readback_, readbackMemory_);
      readbackBytes_ = bytes;
    }
  }
  VK_CHECK(vkResetFences(device_, 1, &fence_));
  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
  record(cmd_, index, area, capture);
  VK_CHECK(vkEndCommandBuffer(cmd_));
  const VkPipelineStageFlags wait = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &acquired_;
  submit.pWaitDstStageMask = &wait;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &rendered_;
  VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence_));
  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &rendered_;
  present.swapchainCount = 1;
  present.pSwapchains = &swapchain_;
  present.pImageIndices = &index;
  VkResult presented = vkQueuePresentKHR(queue_, &present);
  if (capture) {
    VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
    void* mapped = nullptr;
    VK_CHECK(vkMapMemory(device_, readbackMemory_, 0, VK_WHOLE_SIZE, 0, &mapped));
    const size_t pixels = size_t{extent_.width} * extent_.height;
    captured_.assign(static_cast<const uint8_t*>(mapped),
                     static_cast<const uint8_t*>(mapped) + pixels * 4);
    vkUnmapMemory(device_, readbackMemory_);
    if (format_ == VK_FORMAT_B8G8R8A8_UNORM)
      for (size_t i = 0; i < pixels; ++i) std::swap(captured_[4 * i], captured_[4 * i + 2]);
    capturedSize_ = {int(extent_.width), int(extent_.height)};
  }
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
      extent_.width != uint32_t(size()[0]) || extent_.height != uint32_t(size()[1])) {
    VK_CHECK(vkDeviceWaitIdle(device_));
    destroySwapchain();  // resized: a new one at the next present
    return;
  }
  VK_CHECK(presented);
}

}  // namespace viewer
