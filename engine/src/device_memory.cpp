#include "engine/device_memory.h"

#include <map>
#include <mutex>
#include <utility>

#include "engine/vk_context.h"

namespace engine {
namespace {

struct Ledger {
  std::mutex mutex;
  // A handle is unique per device only, so the device is part of the key.
  std::map<std::pair<VkDevice, VkDeviceMemory>, VkDeviceSize> sizes;
  uint64_t inUse = 0;
};

Ledger& ledger() {
  static Ledger l;
  return l;
}

}  // namespace

VkDeviceMemory allocateDeviceMemory(VkDevice device, const VkMemoryAllocateInfo& info) {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateMemory(device, &info, nullptr, &memory));
  Ledger& l = ledger();
  std::lock_guard lock(l.mutex);
  l.sizes[{device, memory}] = info.allocationSize;
  l.inUse += info.allocationSize;
  return memory;
}

void freeDeviceMemory(VkDevice device, VkDeviceMemory memory) {
  if (!memory) return;
  {
    Ledger& l = ledger();
    std::lock_guard lock(l.mutex);
    if (auto it = l.sizes.find({device, memory}); it != l.sizes.end()) {
      l.inUse -= it->second;
      l.sizes.erase(it);
    }
  }
  vkFreeMemory(device, memory, nullptr);
}

uint64_t deviceMemoryInUse() {
  Ledger& l = ledger();
  std::lock_guard lock(l.mutex);
  return l.inUse;
}

}  // namespace engine
