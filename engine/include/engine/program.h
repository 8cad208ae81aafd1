// A compute pipeline built from embedded SPIR-V whose resources are bound with push descriptors
// (one set, bindings 0..n-1 in declaration order) and whose parameters travel as push constants.
// dispatch() checks the bindings and push-constant size against what the program declared.
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "engine/buffer.h"
#include "engine/image.h"

namespace engine {

struct Binding {
  VkDescriptorType type;
  VkDescriptorBufferInfo buffer{};
  VkDescriptorImageInfo image{};

  static Binding storage(const Buffer& b, VkDeviceSize offset = 0,
                         VkDeviceSize range = VK_WHOLE_SIZE) {
    return {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, {b.handle(), offset, range}, {}};
  }
  static Binding uniform(const Buffer& b) {
    return {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, {b.handle(), 0, VK_WHOLE_SIZE}, {}};
  }
  // A storage image in its current layout (must be GENERAL).
  static Binding storageImage(const Image& i) {
    return {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, {}, {VK_NULL_HANDLE, i.view(), i.layout()}};
  }
  // One mip level of a storage image with several levels.
  static Binding storageImage(const Image& i, uint32_t level) {
    return {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, {}, {VK_NULL_HANDLE, i.mipView(level), i.layout()}};
  }
  static Binding sampled(const Image& i, VkSampler sampler) {
    return {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {}, {sampler, i.view(), i.layout()}};
  }
};

class ComputeProgram {
 public:
  ComputeProgram() = default;
  // `specialization` gives the shader's 32-bit specialization constants by constant_id 0, 1, ...
  // (a variant compiled without the code that a constant switches off).
  ComputeProgram(Context& ctx, std::string name, std::span<const uint32_t> spirv,
                 std::vector<VkDescriptorType> bindings, uint32_t pushConstantBytes,
                 std::span<const uint32_t> specialization = {});
  ~ComputeProgram();
  ComputeProgram(ComputeProgram&& other) noexcept;
  ComputeProgram& operator=(ComputeProgram&& other) noexcept;
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  const std::string& name() const { return name_; }

  // Binds the pipeline, pushes descriptors and constants, and dispatches `groups` work groups.
  void dispatch(VkCommandBuffer cmd, std::initializer_list<Binding> bindings, const void* push,
                uint32_t pushBytes, uint32_t groupsX, uint32_t groupsY = 1,
                uint32_t groupsZ = 1) const;
  template <class Push>
  void dispatch(VkCommandBuffer cmd, std::initializer_list<Binding> bindings, const Push& push,
                uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) const {
    dispatch(cmd, bindings, &push, sizeof(Push), groupsX, groupsY, groupsZ);
  }
  // Same, with the group counts read from `args` (VkDispatchIndirectCommand at `offset`).
  template <class Push>
  void dispatchIndirect(VkCommandBuffer cmd, std::initializer_list<Binding> bindings,
                        const Push& push, const Buffer& args, VkDeviceSize offset) const {
    bind(cmd, bindings, &push, sizeof(Push));
    vkCmdDispatchIndirect(cmd, args.handle(), offset);
    ctx_->countDispatch();
  }

 private:
  void bind(VkCommandBuffer cmd, std::initializer_list<Binding> bindings, const void* push,
            uint32_t pushBytes) const;
  void release();

  Context* ctx_ = nullptr;
  std::string name_;
  std::vector<VkDescriptorType> bindingTypes_;
  uint32_t pushBytes_ = 0;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Number of work groups of `groupSize` threads needed to cover `count` items.
constexpr uint32_t groupCount(uint32_t count, uint32_t groupSize) {
  return (count + groupSize - 1) / groupSize;
}

}  // namespace engine
