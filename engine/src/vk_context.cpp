#include "engine/vk_context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace engine {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool envFlag(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

VkInstance createInstance(bool validation) {
  if (validation) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    bool found = std::any_of(layers.begin(), layers.end(), [](const VkLayerProperties& l) {
      return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
    if (!found)
      throw Error(std::string("Vulkan: validation requested but ") + kValidationLayer +
                  " is not installed (apt-get install vulkan-validationlayers)");
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vsgl";
  app.pEngineName = "vsgl";
  app.apiVersion = VK_API_VERSION_1_3;
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledExtensionCount = validation ? 1u : 0u;
  info.ppEnabledExtensionNames = extensions;
  info.enabledLayerCount = validation ? 1u : 0u;
  info.ppEnabledLayerNames = &kValidationLayer;
  VkInstance instance = VK_NULL_HANDLE;
  VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
    throw Error(std::string("Vulkan: no driver found (") + vkResultName(result) +
                "); install mesa-vulkan-drivers for the software device or a GPU driver");
  VK_CHECK(result);
  return instance;
}

// VSGL shading broadcasts each VSGL across a subgroup (GL_KHR_shader_subgroup_ballot).
std::string missingSubgroupOperations(VkPhysicalDevice device) {
  VkPhysicalDeviceSubgroupProperties subgroup{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
  vkGetPhysicalDeviceProperties2(device, &props);
  if (!(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) ||
      !(subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT))
    return "no subgroup ballot operations in compute shaders";
  return {};
}

// The first device feature the module needs that `features` (a VkPhysicalDeviceFeatures2 chain,
// as queried or as given to vkCreateDevice) lacks: shaderInt64 and shaderBufferInt64Atomics (the
// rasterizer's 64-bit atomics), synchronization2 and maintenance4; empty when none. The Vulkan
// 1.2/1.3 structs and the individual feature structs are both read.
std::string missingFeature(const VkPhysicalDeviceFeatures2& features) {
  bool int64Atomics = false, synchronization2 = false, maintenance4 = false;
  for (auto* s = static_cast<const VkBaseInStructure*>(features.pNext); s; s = s->pNext) {
    switch (s->sType) {
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
        int64Atomics |= reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(s)
                            ->shaderBufferInt64Atomics == VK_TRUE;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES:
        int64Atomics |= reinterpret_cast<const VkPhysicalDeviceShaderAtomicInt64Features*>(s)
                            ->shaderBufferInt64Atomics == VK_TRUE;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
        const auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
        synchronization2 |= f->synchronization2 == VK_TRUE;
        maintenance4 |= f->maintenance4 == VK_TRUE;
        break;
      }
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
        synchronization2 |= reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(s)
                                ->synchronization2 == VK_TRUE;
        break;
      case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES:
        maintenance4 |=
            reinterpret_cast<const VkPhysicalDeviceMaintenance4Features*>(s)->maintenance4 ==
            VK_TRUE;
        break;
      default:
        break;
    }
  }
  if (!features.features.shaderInt64) return "shaderInt64";
  if (!int64Atomics) return "shaderBufferInt64Atomics";
  if (!synchronization2) return "synchronization2";
  if (!maintenance4) return "maintenance4";
  return {};
}

// Everything the module relies on; a device lacking any of it is listed with the reason.
std::string unsuitableReason(VkPhysicalDevice device, uint32_t* queueFamily) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3 not supported";

  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  bool found = false;
  for (uint32_t i = 0; i < count && !found; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) {
      *queueFamily = i;
      found = true;
    }
  }
  if (!found) return "no compute queue with timestamps";

  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  bool push = std::any_of(extensions.begin(), extensions.end(), [](const auto& e) {
    return std::strcmp(e.extensionName, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) == 0;
  });
  if (!push) return "VK_KHR_push_descriptor missing";
  if (std::string missing = missingSubgroupOperations(device); !missing.empty()) return missing;

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f2.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(device, &f2);
  if (std::string missing = missingFeature(f2); !missing.empty()) return missing + " missing";
  return {};
}

DeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &props);
  DeviceInfo info;
  info.index = index;
  info.name = props.properties.deviceName;
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info.apiVersion = versionString(props.properties.apiVersion);
  info.type = props.properties.deviceType;
  uint32_t family = 0;
  info.unsuitableReason = unsuitableReason(device, &family);
  return info;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

}  // namespace

const char* vkResultName(VkResult result) {
  switch (result) {
#define CASE(x) \
  case x:       \
    return #x
    CASE(VK_SUCCESS);
    CASE(VK_NOT_READY);
    CASE(VK_TIMEOUT);
    CASE(VK_INCOMPLETE);
    CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
    CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    CASE(VK_ERROR_INITIALIZATION_FAILED);
    CASE(VK_ERROR_DEVICE_LOST);
    CASE(VK_ERROR_MEMORY_MAP_FAILED);
    CASE(VK_ERROR_LAYER_NOT_PRESENT);
    CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
    CASE(VK_ERROR_FEATURE_NOT_PRESENT);
    CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
    CASE(VK_ERROR_TOO_MANY_OBJECTS);
    CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
#undef CASE
    default:
      return "VkResult error";
  }
}

void throwVkError(const char* expression, VkResult result) {
  throw Error(std::string("Vulkan: ") + expression + " failed with " + vkResultName(result) + " (" +
              std::to_string(static_cast<int>(result)) + ")");
}

std::vector<DeviceInfo> Context::listDevices() {
  VkInstance instance = createInstance(false);
  std::vector<DeviceInfo> infos;
  auto devices = physicalDevices(instance);
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  vkDestroyInstance(instance, nullptr);
  return infos;
}

Context::Context(const ContextOptions& options) {
  validation_ = options.validation || envFlag("VSGL_VALIDATION");
  instance_ = createInstance(validation_);

  if (validation_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerCreateInfoEXT info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    info.pfnUserCallback = &Context::onDebugMessage;
    info.pUserData = this;
    VK_CHECK(create(instance_, &info, nullptr, &messenger_));
  }

  // Pick the device: explicit option, then VSGL_DEVICE, then the best-ranked suitable one.
  std::string selector = options.device;
  if (selector.empty() && std::getenv("VSGL_DEVICE")) selector = std::getenv("VSGL_DEVICE");
  auto devices = physicalDevices(instance_);
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));

  int chosen = -1;
  if (!selector.empty()) {
    bool numeric = std::all_of(selector.begin(), selector.end(),
                               [](unsigned char c) { return std::isdigit(c); });
    for (const auto& info : infos) {
      bool match = numeric ? std::to_string(info.index) == selector
                           : lower(info.name).find(lower(selector)) != std::string::npos;
      if (!match) continue;
      if (!info.unsuitableReason.empty())
        throw Error("Vulkan device '" + info.name + "' (selected by '" + selector +
                    "') cannot be used: " + info.unsuitableReason);
      chosen = static_cast<int>(info.index);
      break;
    }
    if (chosen < 0) {
      std::string names;
      for (const auto& info : infos)
        names += (names.empty() ? "" : ", ") + std::to_string(info.index) + ": " + info.name;
      throw Error("Vulkan device selector '" + selector +
                  "' matches no device (available: " + (names.empty() ? "none" : names) + ")");
    }
  } else {
    for (const auto& info : infos) {
      if (!info.unsuitableReason.empty()) continue;
      if (chosen < 0 || typeRank(info.type) < typeRank(infos[chosen].type))
        chosen = static_cast<int>(info.index);
    }
    if (chosen < 0) {
      std::string reasons;
      for (const auto& info : infos) reasons += "; " + info.name + ": " + info.unsuitableReason;
      throw Error(
          "Vulkan: no usable device" +
          (infos.empty() ? std::string(" (none found; install mesa-vulkan-drivers)") : reasons));
    }
  }
  physicalDevice_ = devices[chosen];
  info_ = infos[chosen];
  unsuitableReason(physicalDevice_, &queueFamily_);
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.synchronization2 = VK_TRUE;
  f13.maintenance4 = VK_TRUE;  // local_size_x_id under a Vulkan 1.3 target needs it
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  f12.shaderBufferInt64Atomics = VK_TRUE;
  f12.hostQueryReset = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f12;
  features.features.shaderInt64 = VK_TRUE;

  const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = 1;
  deviceInfo.ppEnabledExtensionNames = extensions;
  VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence_));
}

Context::Context(const ExternalDevice& external) : borrowed_(true) {
  if (!external.instance || !external.physicalDevice || !external.device)
    throw Error("ExternalDevice: instance, physicalDevice and device must all be set");
  instance_ = external.instance;
  physicalDevice_ = external.physicalDevice;
  device_ = external.device;
  queueFamily_ = external.queueFamily;
  info_ = describe(physicalDevice_, 0);
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  if (properties_.apiVersion < VK_API_VERSION_1_3)
    throw Error("ExternalDevice: '" + info_.name + "' is not a Vulkan 1.3 device");
  if (std::string missing = missingSubgroupOperations(physicalDevice_); !missing.empty())
    throw Error("ExternalDevice: '" + info_.name + "' has " + missing);
  // Vulkan cannot say which features a device was created with: the host's chain when given,
  // else what the physical device supports.
  if (external.enabledFeatures) {
    if (std::string missing = missingFeature(*external.enabledFeatures); !missing.empty())
      throw Error("ExternalDevice: " + missing +
                  " is not enabled in the device's features (DeviceHandles::enabledFeatures)");
  } else {
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.pNext = &f13;
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supported.pNext = &f12;
    vkGetPhysicalDeviceFeatures2(physicalDevice_, &supported);
    if (std::string missing = missingFeature(supported); !missing.empty())
      throw Error("ExternalDevice: '" + info_.name + "' does not support " + missing);
  }
  cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!cmdPushDescriptorSet)
    throw Error("ExternalDevice: VK_KHR_push_descriptor is not enabled on the device");
}

Context::~Context() {
  if (borrowed_) return;  // the host destroys its own device and instance
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, commandPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

VkBool32 VKAPI_PTR Context::onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                           VkDebugUtilsMessageTypeFlagsEXT,
                                           const VkDebugUtilsMessengerCallbackDataEXT* data,
                                           void* user) {
  auto* self = static_cast<Context*>(user);
  const char* level =
      (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
  std::string message = std::string("validation ") + level + ": " +
                        (data->pMessage ? data->pMessage : "(no message)");
  std::fprintf(stderr, "%s\n", message.c_str());
  self->validationMessages_.fetch_add(1);
  std::lock_guard<std::mutex> lock(self->messagesMutex_);
  self->messages_.push_back(std::move(message));
  return VK_FALSE;
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard<std::mutex> lock(messagesMutex_);
  return messages_;
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  if (borrowed_)
    throw Error("internal: submitAndWait on a host's device (the module only records commands)");
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = commandPool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  VK_CHECK(vkQueueSubmit2(queue_, 1, &submit, fence_));
  VK_CHECK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  VK_CHECK(vkResetFences(device_, 1, &fence_));
  vkFreeCommandBuffers(device_, commandPool_, 1, &cmd);
}

void Context::initializeLayout(VkImage image, VkImageLayout layout) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  barrier.newLayout = layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0,
                              VK_REMAINING_ARRAY_LAYERS};
  deferredLayouts_.push_back(barrier);
  if (!borrowed_) submitAndWait([&](VkCommandBuffer cmd) { recordDeferredSetup(cmd); });
}

void Context::recordDeferredSetup(VkCommandBuffer cmd) {
  if (deferredLayouts_.empty()) return;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = static_cast<uint32_t>(deferredLayouts_.size());
  dep.pImageMemoryBarriers = deferredLayouts_.data();
  vkCmdPipelineBarrier2(cmd, &dep);
  deferredLayouts_.clear();
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
    for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
      if ((typeBits & (1u << i)) && (memoryProperties_.memoryTypes[i].propertyFlags & want) == want)
        return i;
    }
  }
  throw Error("Vulkan: no memory type with the required properties");
}

}  // namespace engine
