// SPDX-License-Identifier: MIT
#include "skyservice/weather/window_copy.h"

#include <cstring>
#include <string>

namespace sky
{
namespace
{

/// Each image's bytes start at a multiple of 16 (vkCmdCopyBufferToImage wants the texel size and 4).
size_t aligned(size_t n) { return (n + 15) & ~size_t(15); }

void recordCopy(VkCommandBuffer cmd, const Buffer& staging, const Image& image, VkDeviceSize offset)
{
    // UNDEFINED: the old texels are discarded; the barrier's source scope (all commands) holds the reads
    // of the frames submitted before, which the copy must not overtake.
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region = {};
    region.bufferOffset = offset;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, image.layers};
    region.imageExtent = image.extent;
    vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
}

}  // namespace

SkyStatus createWindowCopy(const Context& ctx, WindowCopy& copy)
{
    SKY_TRY(createCommandBuffer(ctx, VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, copy.pool, copy.cmd));
    VkFenceCreateInfo fenceInfo = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_TRY(vkCreateFence(ctx.device, &fenceInfo, nullptr, &copy.fence));
    setObjectName(ctx, VK_OBJECT_TYPE_FENCE, uint64_t(copy.fence), "weather window copy");
    return SkyStatus::success();
}

void destroyWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy)
{
    if (copy.inFlight)
        vkWaitForFences(ctx.device, 1, &copy.fence, VK_TRUE, UINT64_MAX);
    if (copy.fence)
        vkDestroyFence(ctx.device, copy.fence, nullptr);
    if (copy.pool)
        vkDestroyCommandPool(ctx.device, copy.pool, nullptr);
    destroyBuffer(ctx, memory, copy.staging);
    copy = WindowCopy{};
}

SkyStatus startWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy, const PreparedWindow& window,
                          const Image& windowImage, const Image& columnBoundsImage)
{
    const std::vector<uint16_t>& texels = window.gpuTexelsHalf;
    const std::vector<uint8_t>& bounds = window.columnBounds;
    const size_t texelBytes = texels.size() * sizeof(uint16_t);
    const size_t total = aligned(texelBytes) + aligned(bounds.size());
    if (copy.staging.size < total)
    {
        destroyBuffer(ctx, memory, copy.staging);  // no copy in flight reads it
        SKY_TRY(createBuffer(ctx, memory, copy.staging, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             MemoryUse::HostStaging, "weather window staging"));
    }
    std::memcpy(copy.staging.mapped, texels.data(), texelBytes);
    std::memcpy(static_cast<uint8_t*>(copy.staging.mapped) + aligned(texelBytes), bounds.data(), bounds.size());

    VK_TRY(vkResetCommandBuffer(copy.cmd, 0));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_TRY(vkBeginCommandBuffer(copy.cmd, &begin));
    recordCopy(copy.cmd, copy.staging, windowImage, 0);
    recordCopy(copy.cmd, copy.staging, columnBoundsImage, aligned(texelBytes));
    VK_TRY(vkEndCommandBuffer(copy.cmd));
    VK_TRY(vkResetFences(ctx.device, 1, &copy.fence));
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &copy.cmd;
    const VkResult r = vkQueueSubmit(ctx.queue, 1, &submit, copy.fence);
    if (r != VK_SUCCESS)
        return SkyStatus::failure(std::string("weather window copy submit failed: ") + vkResultName(r), r);
    copy.inFlight = true;
    return SkyStatus::success();
}

bool windowCopyDone(const Context& ctx, WindowCopy& copy)
{
    if (copy.inFlight && vkGetFenceStatus(ctx.device, copy.fence) == VK_SUCCESS)
        copy.inFlight = false;
    return !copy.inFlight;
}

SkyStatus waitWindowCopy(const Context& ctx, WindowCopy& copy)
{
    if (!copy.inFlight)
        return SkyStatus::success();
    const VkResult r = vkWaitForFences(ctx.device, 1, &copy.fence, VK_TRUE, UINT64_MAX);
    copy.inFlight = false;
    if (r != VK_SUCCESS)
        return SkyStatus::failure(std::string("weather window copy failed: ") + vkResultName(r), r);
    return SkyStatus::success();
}

}  // namespace sky
