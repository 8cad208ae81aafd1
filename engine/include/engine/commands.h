// Synchronization2 barriers for compute work. Passes in this project run back to back on one
// queue, so the common case is a global compute->compute memory barrier; image barriers also
// move the layout and record it in the Image.
#pragma once

#include "engine/buffer.h"
#include "engine/image.h"

namespace engine {

// A global memory dependency from (srcStage, srcAccess) to (dstStage, dstAccess).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Makes shader writes of everything recorded before visible to shaders recorded after.
void computeBarrier(VkCommandBuffer cmd);

// Transfer writes (fill/copy/update) -> compute reads and writes; also covers indirect args.
void transferToComputeBarrier(VkCommandBuffer cmd);

// Compute or transfer writes -> transfer reads (readback copies) and host reads.
void computeToTransferBarrier(VkCommandBuffer cmd);

// Moves `image` to `layout` with a full compute/transfer dependency and records the layout.
void imageBarrier(VkCommandBuffer cmd, Image& image, VkImageLayout layout);

// Gives a newly created image its first layout (Context::initializeLayout: immediately on an
// owned device, at the next recordDeferredSetup on a host's) and records it in the Image.
void initialLayout(Context& ctx, Image& image, VkImageLayout layout);

// Fills a buffer range with a 32-bit pattern (vkCmdFillBuffer), ordered after earlier shader
// accesses and made visible to later compute and indirect reads.
void fillBuffer(VkCommandBuffer cmd, const Buffer& buffer, uint32_t pattern,
                VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE);

// Writes up to 65536 bytes inline (vkCmdUpdateBuffer) with the same ordering as fillBuffer.
void updateBuffer(VkCommandBuffer cmd, const Buffer& buffer, const void* data, VkDeviceSize bytes);

}  // namespace engine
