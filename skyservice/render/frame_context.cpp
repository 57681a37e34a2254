// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_context.h"

#include "shaders/shared/atmosphere_params.h"
#include "shaders/shared/frame_params.h"

#include <string>

namespace sky
{
namespace
{

VkDeviceSize aligned16(VkDeviceSize n) { return (n + 15) & ~VkDeviceSize(15); }

void runDeletions(FrameContext& frame)
{
    for (auto& destroy : frame.deletions)
        destroy();
    frame.deletions.clear();
}

}  // namespace

VkDeviceSize readbackBytes(const Image& image)
{
    return aligned16(VkDeviceSize(image.extent.width) * image.extent.height * formatBytes(image.format));
}

SkyStatus createFrameContext(const Context& ctx, MemoryTracker& memory, FrameContext& frame, uint32_t index)
{
    frame = FrameContext{};
    const std::string n = std::to_string(index);
    SKY_TRY(createCommandBuffer(ctx, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT, frame.pool, frame.cmd));
    VkFenceCreateInfo fenceInfo = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_TRY(vkCreateFence(ctx.device, &fenceInfo, nullptr, &frame.fence));
    VkQueryPoolCreateInfo queryInfo = {VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = kFrameTimestampSlots;
    VK_TRY(vkCreateQueryPool(ctx.device, &queryInfo, nullptr, &frame.timestamps));
    setObjectName(ctx, VK_OBJECT_TYPE_COMMAND_POOL, uint64_t(frame.pool), ("frame " + n + " commands").c_str());
    setObjectName(ctx, VK_OBJECT_TYPE_FENCE, uint64_t(frame.fence), ("frame " + n + " fence").c_str());
    // Usable as uniform and as storage buffer: the shaders read the parameters from uniform buffers, or
    // from storage buffers on lavapipe (shaders/shared/bindings.h PARAMS_BLOCK): with uniform buffers
    // bound through push descriptors, lavapipe (Mesa 22.3.6) grew the service's resident memory by
    // ~0.5 MB per frame (tests/service ServiceSoak, SKY_SOAK_VERBOSE=1: 232 MB to 930 MB over 1500
    // frames); with storage buffers it is flat to the kB. Both variants use std140: the same layout.
    constexpr VkBufferUsageFlags params = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    SKY_TRY(createBuffer(ctx, memory, frame.frameUniforms, sizeof(FrameParams), params, MemoryUse::HostVisible,
                         "frame uniforms"));
    SKY_TRY(createBuffer(ctx, memory, frame.atmosphereUniforms, sizeof(AtmosphereParams), params,
                         MemoryUse::HostVisible, "atmosphere uniforms"));
    return SkyStatus::success();
}

void destroyFrameContext(const Context& ctx, MemoryTracker& memory, FrameContext& frame)
{
    if (frame.submitted)
        vkWaitForFences(ctx.device, 1, &frame.fence, VK_TRUE, UINT64_MAX);
    runDeletions(frame);
    destroyBuffer(ctx, memory, frame.frameUniforms);
    destroyBuffer(ctx, memory, frame.atmosphereUniforms);
    destroyBuffer(ctx, memory, frame.readback);
    if (frame.timestamps)
        vkDestroyQueryPool(ctx.device, frame.timestamps, nullptr);
    if (frame.fence)
        vkDestroyFence(ctx.device, frame.fence, nullptr);
    if (frame.pool)
        vkDestroyCommandPool(ctx.device, frame.pool, nullptr);
    frame = FrameContext{};
}

SkyStatus beginFrameCommands(const Context& ctx, MemoryTracker& memory, FrameContext& frame,
                             VkDeviceSize readbackBytesNeeded)
{
    SKY_TRY(waitFrameCommands(ctx, frame));
    runDeletions(frame);
    if (readbackBytesNeeded > frame.readback.size)
    {
        // A larger frame or more layers than ever before: never in steady state. This context's last
        // frame is done, so its buffer can go at once.
        destroyBuffer(ctx, memory, frame.readback);
        frame.shadowMapIdHeld = 0;
        SKY_TRY(createBuffer(ctx, memory, frame.readback, readbackBytesNeeded, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             MemoryUse::HostReadback, "frame readback (host-cached)"));
    }
    frame.readbackUsed = 0;
    frame.readbackQueue.clear();
    VK_TRY(vkResetCommandPool(ctx.device, frame.pool, 0));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_TRY(vkBeginCommandBuffer(frame.cmd, &begin));
    // The previous frame (another context, submitted earlier) may still write what this one reads or
    // writes (LUTs, history, the display image): every frame starts behind everything submitted before it.
    computeBarrier(frame.cmd);
    return SkyStatus::success();
}

SkyStatus submitFrameCommands(const Context& ctx, FrameContext& frame)
{
    VK_TRY(vkEndCommandBuffer(frame.cmd));
    VK_TRY(vkResetFences(ctx.device, 1, &frame.fence));
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &frame.cmd;
    VkResult r = vkQueueSubmit(ctx.queue, 1, &submit, frame.fence);
    if (r != VK_SUCCESS)
        return SkyStatus::failure(std::string("frame submit failed: ") + vkResultName(r), r);
    frame.submitted = true;
    return SkyStatus::success();
}

SkyStatus waitFrameCommands(const Context& ctx, FrameContext& frame)
{
    if (!frame.submitted)
        return SkyStatus::success();
    VkResult r = vkWaitForFences(ctx.device, 1, &frame.fence, VK_TRUE, UINT64_MAX);
    frame.submitted = false;
    if (r != VK_SUCCESS)
        return SkyStatus::failure(std::string("GPU frame failed: ") + vkResultName(r), r);
    invalidateForHost(ctx, frame.readback);
    return SkyStatus::success();
}

ReadbackRegion reserveImageReadback(FrameContext& frame, const Image& image)
{
    ReadbackRegion region;
    region.offset = frame.readbackUsed;
    region.bytes = VkDeviceSize(image.extent.width) * image.extent.height * formatBytes(image.format);
    VK_CHECK(region.offset + readbackBytes(image) <= frame.readback.size ? VK_SUCCESS : VK_ERROR_OUT_OF_HOST_MEMORY);
    frame.readbackUsed += readbackBytes(image);
    return region;
}

void queueImageReadback(FrameContext& frame, const Image& image, const ReadbackRegion& region)
{
    frame.readbackQueue.emplace_back(&image, region.offset);
}

ReadbackRegion addImageReadback(FrameContext& frame, const Image& image)
{
    const ReadbackRegion region = reserveImageReadback(frame, image);
    queueImageReadback(frame, image, region);
    return region;
}

void recordReadbacks(FrameContext& frame)
{
    VkCommandBuffer cmd = frame.cmd;
    std::vector<VkImageMemoryBarrier2> toTransfer, toGeneral;
    for (const auto& [image, offset] : frame.readbackQueue)
    {
        VkImageMemoryBarrier2 b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image->image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        // The passes' writes before the copy...
        b.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
        b.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
        b.dstStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
        b.dstAccessMask = VK_ACCESS_2_TRANSFER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        toTransfer.push_back(b);
        // ...and the copy before the next frame's passes write the image again.
        b.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
        b.srcAccessMask = VK_ACCESS_2_NONE;
        b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
        b.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        toGeneral.push_back(b);
    }
    auto barriers = [cmd](const std::vector<VkImageMemoryBarrier2>& list) {
        if (list.empty())
            return;
        VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = uint32_t(list.size());
        dep.pImageMemoryBarriers = list.data();
        vkCmdPipelineBarrier2(cmd, &dep);
    };
    barriers(toTransfer);
    for (const auto& [image, offset] : frame.readbackQueue)
    {
        VkBufferImageCopy copy = {};
        copy.bufferOffset = offset;
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = image->extent;
        vkCmdCopyImageToBuffer(cmd, image->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, frame.readback.buffer, 1,
                               &copy);
    }
    barriers(toGeneral);
    frame.readbackQueue.clear();

    VkMemoryBarrier2 barrier = {VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace sky
