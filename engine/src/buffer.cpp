#include "engine/buffer.h"

#include <utility>

#include "engine/device_memory.h"

namespace engine {

Buffer::Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory)
    : device_(ctx.device()), size_(size) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer_));

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, buffer_, &req);
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (memory) {
    case MemoryUsage::GpuOnly:
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  uint32_t type = ctx.findMemoryType(req.memoryTypeBits, required, preferred);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  memory_ = allocateDeviceMemory(device_, alloc);
  VK_CHECK(vkBindBufferMemory(device_, buffer_, memory_, 0));

  // Keep host-visible memory mapped: on unified-memory devices (lavapipe, integrated GPUs)
  // device-local memory is host-visible too, and uploads then skip the staging copy.
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &props);
  VkMemoryPropertyFlags flags = props.memoryTypes[type].propertyFlags;
  if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) &&
      (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
    VK_CHECK(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

Buffer::~Buffer() {
  release();
}

Buffer::Buffer(Buffer&& other) noexcept {
  *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

Buffer Buffer::borrow(VkBuffer buffer, VkDeviceSize size) {
  Buffer borrowed;  // device_ stays null: release() destroys nothing
  borrowed.buffer_ = buffer;
  borrowed.size_ = size;
  return borrowed;
}

void Buffer::release() {
  if (!device_) return;
  if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
  freeDeviceMemory(device_, memory_);  // unmaps implicitly
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

void Buffer::upload(Context& ctx, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (bytes == 0) return;
  if (offset + bytes > size_) throw Error("Buffer::upload: write past the end of the buffer");
  if (mapped_) {
    std::memcpy(static_cast<std::byte*>(mapped_) + offset, data, bytes);
    return;
  }
  Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload);
  std::memcpy(staging.mapped(), data, bytes);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, bytes};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
  });
}

std::vector<std::byte> Buffer::readback(Context& ctx) const {
  std::vector<std::byte> out(size_);
  if (mapped_) {
    std::memcpy(out.data(), mapped_, size_);
    return out;
  }
  Buffer staging(ctx, size_, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, size_};
    vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
  });
  std::memcpy(out.data(), staging.mapped(), size_);
  return out;
}

}  // namespace engine
