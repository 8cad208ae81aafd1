// Device memory of engine::Buffer and engine::Image, allocated and freed through one place that
// keeps count, so that a test can see whether device memory stays flat: lavapipe has no
// VK_EXT_memory_budget, and what a driver allocates behind vkAllocateMemory is its own.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace engine {

// vkAllocateMemory, counted (a failure is VK_CHECK's, as before).
VkDeviceMemory allocateDeviceMemory(VkDevice device, const VkMemoryAllocateInfo& info);
// vkFreeMemory of memory from allocateDeviceMemory (null is ignored).
void freeDeviceMemory(VkDevice device, VkDeviceMemory memory);
// The bytes allocated by allocateDeviceMemory and not yet freed, over every device of the process.
uint64_t deviceMemoryInUse();

}  // namespace engine
