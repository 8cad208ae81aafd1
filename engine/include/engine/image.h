// A 2-D (array) image with one view covering every layer and mip, plus its current layout,
// which the barrier helpers in commands.h keep up to date. Move-only RAII.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

#include "engine/vk_context.h"

namespace engine {

struct ImageDesc {
  uint32_t width = 1;
  uint32_t height = 1;
  uint32_t layers = 1;
  uint32_t mips = 1;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT;
  bool arrayView =
      false;  // view as 2D_ARRAY (texture arrays) rather than 2D; implied by layers > 1
};

class Image {
 public:
  Image() = default;
  Image(Context& ctx, const ImageDesc& desc);
  // A non-owning Image for someone else's image (a host's G-buffer): nothing is destroyed with
  // it. `view` must cover the image's one level; `layout` is its current layout.
  static Image borrow(VkImage image, VkImageView view, const ImageDesc& desc, VkImageLayout layout);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  // A view of one mip level (storage writes need one level per view); index 0 = base level.
  // A single-level image's own view serves as its level 0.
  VkImageView mipView(uint32_t level) const {
    return desc_.mips == 1 && level == 0 ? view_ : mipViews_.at(level);
  }
  const ImageDesc& desc() const { return desc_; }
  VkImageLayout layout() const { return layout_; }
  void setLayout(VkImageLayout layout) { layout_ = layout; }

  // Uploads tightly packed texels: for each layer, mip 0..mips-1 in order. Leaves the image in
  // SHADER_READ_ONLY_OPTIMAL. Blocking (scene upload time).
  void upload(Context& ctx, const void* data, size_t bytes);
  // Copies one mip level of every layer back, tightly packed (blocking; tests and tools). The
  // image is returned to the layout it had.
  std::vector<std::byte> readback(Context& ctx, uint32_t level = 0);
  // The same for R32G32B32A32_SFLOAT images, as vec4 texels (throws for any other format).
  std::vector<glm::vec4> readbackRgba32f(Context& ctx, uint32_t level = 0);

  static size_t texelBytes(VkFormat format);

 private:
  void release();
  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> mipViews_;  // only for storage images with more than one level
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  ImageDesc desc_;
  VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
};

// A trilinear, repeat-addressed sampler (glTF's default wrap) with anisotropy off.
class Sampler {
 public:
  Sampler() = default;
  explicit Sampler(Context& ctx, VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                   VkFilter filter = VK_FILTER_LINEAR);
  static Sampler borrow(VkSampler sampler);  // non-owning, like Image::borrow
  ~Sampler();
  Sampler(Sampler&& other) noexcept;
  Sampler& operator=(Sampler&& other) noexcept;
  VkSampler handle() const { return sampler_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace engine
