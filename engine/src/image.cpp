#include "engine/image.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "engine/buffer.h"
#include "engine/commands.h"
#include "engine/device_memory.h"

namespace engine {

size_t Image::texelBytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SNORM:
    case VK_FORMAT_R16G16_SFLOAT:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      throw Error("Image: unsupported format " + std::to_string(static_cast<int>(format)));
  }
}

Image::Image(Context& ctx, const ImageDesc& desc) : device_(ctx.device()), desc_(desc) {
  texelBytes(desc.format);  // rejects formats the upload/readback paths cannot size
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = desc.mips;
  info.arrayLayers = desc.layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(device_, &info, nullptr, &image_));

  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, image_, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      ctx.findMemoryType(req.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  memory_ = allocateDeviceMemory(device_, alloc);
  VK_CHECK(vkBindImageMemory(device_, image_, memory_, 0));

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image_;
  viewInfo.viewType =
      (desc.arrayView || desc.layers > 1) ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, desc.mips, 0, desc.layers};
  VK_CHECK(vkCreateImageView(device_, &viewInfo, nullptr, &view_));
  if (desc.mips > 1 && (desc.usage & VK_IMAGE_USAGE_STORAGE_BIT)) {
    for (uint32_t level = 0; level < desc.mips; ++level) {
      viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, desc.layers};
      VkImageView view = VK_NULL_HANDLE;
      VK_CHECK(vkCreateImageView(device_, &viewInfo, nullptr, &view));
      mipViews_.push_back(view);
    }
  }
}

Image Image::borrow(VkImage image, VkImageView view, const ImageDesc& desc, VkImageLayout layout) {
  Image borrowed;  // device_ stays null: release() destroys nothing
  borrowed.image_ = image;
  borrowed.view_ = view;
  borrowed.desc_ = desc;
  borrowed.layout_ = layout;
  return borrowed;
}

Image::~Image() {
  release();
}

Image::Image(Image&& other) noexcept {
  *this = std::move(other);
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    mipViews_ = std::exchange(other.mipViews_, {});
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    desc_ = other.desc_;
    layout_ = std::exchange(other.layout_, VK_IMAGE_LAYOUT_UNDEFINED);
  }
  return *this;
}

void Image::release() {
  if (!device_) return;
  if (view_) vkDestroyImageView(device_, view_, nullptr);
  for (VkImageView v : mipViews_) vkDestroyImageView(device_, v, nullptr);
  mipViews_.clear();
  if (image_) vkDestroyImage(device_, image_, nullptr);
  freeDeviceMemory(device_, memory_);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

void Image::upload(Context& ctx, const void* data, size_t bytes) {
  const size_t texel = texelBytes(desc_.format);
  std::vector<VkBufferImageCopy> regions;
  size_t offset = 0;
  for (uint32_t layer = 0; layer < desc_.layers; ++layer) {
    for (uint32_t mip = 0; mip < desc_.mips; ++mip) {
      uint32_t w = std::max(1u, desc_.width >> mip), h = std::max(1u, desc_.height >> mip);
      VkBufferImageCopy region{};
      region.bufferOffset = offset;
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, layer, 1};
      region.imageExtent = {w, h, 1};
      regions.push_back(region);
      offset += size_t{w} * h * texel;
    }
  }
  if (offset != bytes)
    throw Error("Image::upload: expected " + std::to_string(offset) + " bytes, got " +
                std::to_string(bytes));
  Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload);
  std::memcpy(staging.mapped(), data, bytes);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, *this, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           static_cast<uint32_t>(regions.size()), regions.data());
    imageBarrier(cmd, *this, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
}

std::vector<std::byte> Image::readback(Context& ctx, uint32_t level) {
  const uint32_t width = std::max(1u, desc_.width >> level),
                 height = std::max(1u, desc_.height >> level);
  const size_t layerBytes = size_t{width} * height * texelBytes(desc_.format);
  Buffer staging(ctx, layerBytes * desc_.layers, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                 MemoryUsage::Readback);
  VkImageLayout original = layout_;
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    imageBarrier(cmd, *this, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, desc_.layers};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1,
                           &region);
    if (original != VK_IMAGE_LAYOUT_UNDEFINED) imageBarrier(cmd, *this, original);
    computeToTransferBarrier(cmd);
  });
  std::vector<std::byte> out(layerBytes * desc_.layers);
  std::memcpy(out.data(), staging.mapped(), out.size());
  return out;
}

std::vector<glm::vec4> Image::readbackRgba32f(Context& ctx, uint32_t level) {
  if (desc_.format != VK_FORMAT_R32G32B32A32_SFLOAT)
    throw Error("Image::readbackRgba32f: the image is not R32G32B32A32_SFLOAT");
  auto bytes = readback(ctx, level);
  std::vector<glm::vec4> texels(bytes.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), bytes.data(), bytes.size());
  return texels;
}

Sampler::Sampler(Context& ctx, VkSamplerAddressMode address, VkFilter filter)
    : device_(ctx.device()) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode =
      filter == VK_FILTER_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = address;
  info.addressModeV = address;
  info.addressModeW = address;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VK_CHECK(vkCreateSampler(device_, &info, nullptr, &sampler_));
}

Sampler Sampler::borrow(VkSampler sampler) {
  Sampler borrowed;  // device_ stays null: nothing is destroyed
  borrowed.sampler_ = sampler;
  return borrowed;
}

Sampler::~Sampler() {
  if (device_ && sampler_) vkDestroySampler(device_, sampler_, nullptr);
}

Sampler::Sampler(Sampler&& other) noexcept {
  *this = std::move(other);
}

Sampler& Sampler::operator=(Sampler&& other) noexcept {
  if (this != &other) {
    if (device_ && sampler_) vkDestroySampler(device_, sampler_, nullptr);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

}  // namespace engine
