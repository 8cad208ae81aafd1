#include "engine/program.h"

#include <utility>

namespace engine {

ComputeProgram::ComputeProgram(Context& ctx, std::string name, std::span<const uint32_t> spirv,
                               std::vector<VkDescriptorType> bindings, uint32_t pushConstantBytes,
                               std::span<const uint32_t> specialization)
    : ctx_(&ctx),
      name_(std::move(name)),
      bindingTypes_(std::move(bindings)),
      pushBytes_(pushConstantBytes) {
  VkDevice device = ctx.device();
  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  for (uint32_t i = 0; i < bindingTypes_.size(); ++i)
    layoutBindings.push_back({i, bindingTypes_[i], 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<uint32_t>(layoutBindings.size());
  setInfo.pBindings = layoutBindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout_));

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes_};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout_;
  layoutInfo.pushConstantRangeCount = pushBytes_ > 0 ? 1u : 0u;
  layoutInfo.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout_));

  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size_bytes();
  moduleInfo.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));

  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = module;
  pipelineInfo.stage.pName = "main";
  std::vector<VkSpecializationMapEntry> entries;
  for (uint32_t i = 0; i < specialization.size(); ++i)
    entries.push_back({i, i * uint32_t(sizeof(uint32_t)), sizeof(uint32_t)});
  VkSpecializationInfo specializationInfo{static_cast<uint32_t>(entries.size()), entries.data(),
                                          specialization.size_bytes(), specialization.data()};
  if (!specialization.empty()) pipelineInfo.stage.pSpecializationInfo = &specializationInfo;
  pipelineInfo.layout = layout_;
  VkResult result =
      vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline_);
  vkDestroyShaderModule(device, module, nullptr);
  VK_CHECK(result);
}

ComputeProgram::~ComputeProgram() {
  release();
}

ComputeProgram::ComputeProgram(ComputeProgram&& other) noexcept {
  *this = std::move(other);
}

ComputeProgram& ComputeProgram::operator=(ComputeProgram&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    name_ = std::move(other.name_);
    bindingTypes_ = std::move(other.bindingTypes_);
    pushBytes_ = other.pushBytes_;
    setLayout_ = std::exchange(other.setLayout_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
  }
  return *this;
}

void ComputeProgram::release() {
  if (!ctx_) return;
  VkDevice device = ctx_->device();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
}

void ComputeProgram::bind(VkCommandBuffer cmd, std::initializer_list<Binding> bindings,
                          const void* push, uint32_t pushBytes) const {
  // Mismatches are programming errors in a pass, caught on their first dispatch.
  if (bindings.size() != bindingTypes_.size() || pushBytes != pushBytes_)
    throw Error(name_ + ": dispatch with " + std::to_string(bindings.size()) + " bindings / " +
                std::to_string(pushBytes) + " push bytes, program declares " +
                std::to_string(bindingTypes_.size()) + " / " + std::to_string(pushBytes_));
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(bindings.size());
  uint32_t index = 0;
  for (const Binding& b : bindings) {
    if (b.type != bindingTypes_[index])
      throw Error(name_ + ": binding " + std::to_string(index) + " has the wrong descriptor type");
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = index++;
    w.descriptorCount = 1;
    w.descriptorType = b.type;
    if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      w.pBufferInfo = &b.buffer;
    else
      w.pImageInfo = &b.image;
    writes.push_back(w);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  ctx_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0,
                             static_cast<uint32_t>(writes.size()), writes.data());
  if (pushBytes_ > 0)
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes_, push);
}

void ComputeProgram::dispatch(VkCommandBuffer cmd, std::initializer_list<Binding> bindings,
                              const void* push, uint32_t pushBytes, uint32_t groupsX,
                              uint32_t groupsY, uint32_t groupsZ) const {
  bind(cmd, bindings, push, pushBytes);
  if (groupsX > 0 && groupsY > 0 && groupsZ > 0) {
    vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
    ctx_->countDispatch();
  }
}

}  // namespace engine
