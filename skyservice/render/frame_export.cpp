// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_export.h"

#include "skyservice/render/frame_export_internal.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <mutex>

namespace sky
{
namespace
{

std::string formatName(VkFormat format)
{
    switch (format)
    {
    case VK_FORMAT_R8G8B8A8_UNORM: return "R8G8B8A8_UNORM";
    case VK_FORMAT_R32_SFLOAT: return "R32_SFLOAT";
    case VK_FORMAT_R16G16B16A16_SFLOAT: return "R16G16B16A16_SFLOAT";
    case VK_FORMAT_R32G32_SFLOAT: return "R32G32_SFLOAT";
    default: return std::to_string(int(format));
    }
}

}  // namespace

namespace exportdetail
{

// Exportable as opaque fds with this format, tiling and usage (and needing a dedicated allocation: we
// always make one, so only exportability matters).
SkyStatus checkExportable(const Context& ctx, VkFormat format)
{
    VkPhysicalDeviceExternalImageFormatInfo externalInfo = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_IMAGE_FORMAT_INFO};
    externalInfo.handleType = kMemoryHandle;
    VkPhysicalDeviceImageFormatInfo2 info = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_IMAGE_FORMAT_INFO_2};
    info.pNext = &externalInfo;
    info.format = format;
    info.type = VK_IMAGE_TYPE_2D;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = kFrameExportUsage;
    VkExternalImageFormatProperties externalProps = {VK_STRUCTURE_TYPE_EXTERNAL_IMAGE_FORMAT_PROPERTIES};
    VkImageFormatProperties2 props = {VK_STRUCTURE_TYPE_IMAGE_FORMAT_PROPERTIES_2};
    props.pNext = &externalProps;
    VkResult res = vkGetPhysicalDeviceImageFormatProperties2(ctx.physicalDevice, &info, &props);
    if (res != VK_SUCCESS)
        return SkyStatus::failure("frame export: " + formatName(format) + " images with opaque-fd memory are not "
                                  "supported by " + ctx.deviceName + " (" + vkResultName(res) + ")",
                                  res);
    VkExternalMemoryFeatureFlags features = externalProps.externalMemoryProperties.externalMemoryFeatures;
    if (!(features & VK_EXTERNAL_MEMORY_FEATURE_EXPORTABLE_BIT))
        return SkyStatus::failure("frame export: " + ctx.deviceName + " cannot export " + formatName(format) +
                                      " image memory as an opaque fd",
                                  VK_ERROR_FORMAT_NOT_SUPPORTED);
    return SkyStatus::success();
}

SkyStatus createExportedImage(Renderer& r, ExportedImage& out, VkFormat format, uint32_t width, uint32_t height,
                              const std::string& name)
{
    const Context& ctx = r.ctx;
    out = ExportedImage{};
    VkExternalMemoryImageCreateInfo externalInfo = {VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_IMAGE_CREATE_INFO};
    externalInfo.handleTypes = kMemoryHandle;
    VkImageCreateInfo info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.pNext = &externalInfo;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = kFrameExportUsage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_TRY(vkCreateImage(ctx.device, &info, nullptr, &out.image));

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device, out.image, &req);
    bool found = false;
    for (uint32_t i = 0; i < ctx.memoryProperties.memoryTypeCount && !found; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (ctx.memoryProperties.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
        {
            out.memoryTypeIndex = i;
            found = true;
        }
    if (!found)
    {
        vkDestroyImage(ctx.device, out.image, nullptr);
        out = ExportedImage{};
        return SkyStatus::failure("frame export: no device-local memory type for " + name,
                                  VK_ERROR_OUT_OF_DEVICE_MEMORY);
    }
    VkMemoryDedicatedAllocateInfo dedicated = {VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.image = out.image;
    VkExportMemoryAllocateInfo exportInfo = {VK_STRUCTURE_TYPE_EXPORT_MEMORY_ALLOCATE_INFO};
    exportInfo.pNext = &dedicated;
    exportInfo.handleTypes = kMemoryHandle;
    VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = &exportInfo;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = out.memoryTypeIndex;
    VkResult res = vkAllocateMemory(ctx.device, &alloc, nullptr, &out.memory);
    if (res != VK_SUCCESS)
    {
        vkDestroyImage(ctx.device, out.image, nullptr);
        out = ExportedImage{};
        return SkyStatus::failure("out of device memory allocating " + std::to_string(req.size) + " bytes for " + name +
                                      " (" + vkResultName(res) + ")",
                                  res);
    }
    VK_CHECK(vkBindImageMemory(ctx.device, out.image, out.memory, 0));
    out.format = format;
    out.width = width;
    out.height = height;
    out.allocationBytes = req.size;
    out.memoryTypeBits = req.memoryTypeBits;
    out.name = name;
    setObjectName(ctx, VK_OBJECT_TYPE_IMAGE, uint64_t(out.image), name.c_str());
    std::lock_guard<std::mutex> lock(r.memory.mutex);
    r.memory.liveBytes[name] += req.size;
    r.memory.totalBytes += req.size;
    r.memory.peakBytes = std::max(r.memory.peakBytes, r.memory.totalBytes);
    return SkyStatus::success();
}

void destroyExportedImage(Renderer& r, ExportedImage& image)
{
    if (image.image)
        vkDestroyImage(r.ctx.device, image.image, nullptr);
    if (image.memory)
    {
        vkFreeMemory(r.ctx.device, image.memory, nullptr);
        std::lock_guard<std::mutex> lock(r.memory.mutex);
        auto it = r.memory.liveBytes.find(image.name);
        if (it != r.memory.liveBytes.end())
        {
            it->second -= std::min(it->second, image.allocationBytes);
            if (it->second == 0)
                r.memory.liveBytes.erase(it);
        }
        r.memory.totalBytes -= std::min(r.memory.totalBytes, image.allocationBytes);
    }
    image = ExportedImage{};
}

nlohmann::json imageJson(const ExportedImage& image)
{
    return {{"allocation_bytes", uint64_t(image.allocationBytes)},
            {"memory_type_bits", image.memoryTypeBits},
            {"vk_format", uint32_t(image.format)},
            {"width", image.width},
            {"height", image.height},
            {"linear_tiling", false},
            {"row_pitch", 0}};
}

VkResult exportMemoryFd(const Context& ctx, const ExportedImage& image, std::vector<int>& fds)
{
    VkMemoryGetFdInfoKHR info = {VK_STRUCTURE_TYPE_MEMORY_GET_FD_INFO_KHR};
    info.memory = image.memory;
    info.handleType = kMemoryHandle;
    int fd = -1;
    VkResult res = ctx.getMemoryFd(ctx.device, &info, &fd);
    if (res == VK_SUCCESS)
        fds.push_back(fd);
    return res;
}

}  // namespace exportdetail

namespace
{

using namespace exportdetail;

constexpr VkExternalSemaphoreHandleTypeFlagBits kSemaphoreHandle = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;

// The timeline semaphore, when the device can export one (never on lavapipe: no external_semaphore_fd).
SkyStatus createExportedTimeline(const Context& ctx, VkSemaphore& out)
{
    out = VK_NULL_HANDLE;
    if (!ctx.externalSemaphoreFd || !ctx.timelineSemaphore)
        return SkyStatus::success();
    VkSemaphoreTypeCreateInfo typeInfo = {VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    typeInfo.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    typeInfo.initialValue = 0;
    VkPhysicalDeviceExternalSemaphoreInfo query = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO};
    query.pNext = &typeInfo;
    query.handleType = kSemaphoreHandle;
    VkExternalSemaphoreProperties props = {VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
    vkGetPhysicalDeviceExternalSemaphoreProperties(ctx.physicalDevice, &query, &props);
    if (!(props.externalSemaphoreFeatures & VK_EXTERNAL_SEMAPHORE_FEATURE_EXPORTABLE_BIT))
        return SkyStatus::success();  // fall back to waiting for the fence (header comment)
    VkExportSemaphoreCreateInfo exportInfo = {VK_STRUCTURE_TYPE_EXPORT_SEMAPHORE_CREATE_INFO};
    exportInfo.handleTypes = kSemaphoreHandle;
    typeInfo.pNext = &exportInfo;
    VkSemaphoreCreateInfo info = {VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    info.pNext = &typeInfo;
    VK_TRY(vkCreateSemaphore(ctx.device, &info, nullptr, &out));
    setObjectName(ctx, VK_OBJECT_TYPE_SEMAPHORE, uint64_t(out), "export timeline");
    return SkyStatus::success();
}

struct Access
{
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
    uint32_t queueFamily;
};

VkImageMemoryBarrier2 imageBarrier(VkImage image, const Access& from, const Access& to)
{
    VkImageMemoryBarrier2 b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    b.srcStageMask = from.stage;
    b.srcAccessMask = from.access;
    b.oldLayout = from.layout;
    b.srcQueueFamilyIndex = from.queueFamily;
    b.dstStageMask = to.stage;
    b.dstAccessMask = to.access;
    b.newLayout = to.layout;
    b.dstQueueFamilyIndex = to.queueFamily;
    return b;
}

// A fixed-size list of barriers: exportFrame runs every frame and allocates nothing.
struct BarrierList
{
    std::array<VkImageMemoryBarrier2, 2 * kMaxCopyJobs> items;
    uint32_t count = 0;
    void add(const VkImageMemoryBarrier2& b) { items[count++] = b; }
    void record(VkCommandBuffer cmd) const
    {
        if (count == 0)
            return;
        VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = count;
        dep.pImageMemoryBarriers = items.data();
        vkCmdPipelineBarrier2(cmd, &dep);
    }
};

SkyStatus waitSlot(const Context& ctx, FrameExport& e, uint32_t slot)
{
    if (!e.fencePending[slot])
        return SkyStatus::success();
    VK_TRY(vkWaitForFences(ctx.device, 1, &e.fences[slot], VK_TRUE, UINT64_MAX));
    VK_TRY(vkResetFences(ctx.device, 1, &e.fences[slot]));
    e.fencePending[slot] = false;
    return SkyStatus::success();
}

std::string hex(const uint8_t* bytes, size_t count)
{
    std::string s;
    char digits[3];
    for (size_t i = 0; i < count; ++i)
    {
        std::snprintf(digits, sizeof digits, "%02x", unsigned(bytes[i]));
        s += digits;
    }
    return s;
}

}  // namespace

SkyStatus createFrameExport(Renderer& r, FrameExport& e, uint32_t slots, uint32_t maxWidth, uint32_t maxHeight,
                            uint32_t maxShadowSize)
{
    e = FrameExport{};
    const Context& ctx = r.ctx;
    if (!ctx.externalMemoryFd)
        return SkyStatus::failure("frame export needs " + std::string(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) +
                                      ", which " + ctx.deviceName + " does not offer",
                                  VK_ERROR_EXTENSION_NOT_PRESENT);
    if (slots < 1 || slots > 4 || maxWidth < 1 || maxHeight < 1)
        return SkyStatus::failure("frame export: slots must be in [1, 4] and the frame size at least 1x1",
                                  VK_ERROR_INITIALIZATION_FAILED);
    SKY_TRY(checkExportable(ctx, VK_FORMAT_R8G8B8A8_UNORM));
    if (maxShadowSize > 0)
    {
        SKY_TRY(checkExportable(ctx, VK_FORMAT_R32_SFLOAT));
        // The shadow pass writes rgba16f; the export blits its red channel (transmittance) into R32_SFLOAT.
        VkFormatProperties src, dst;
        vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, VK_FORMAT_R16G16B16A16_SFLOAT, &src);
        vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice, VK_FORMAT_R32_SFLOAT, &dst);
        if (!(src.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_SRC_BIT) ||
            !(dst.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT))
            return SkyStatus::failure("frame export: " + ctx.deviceName +
                                          " cannot blit R16G16B16A16_SFLOAT to R32_SFLOAT (shadow map export)",
                                      VK_ERROR_FORMAT_NOT_SUPPORTED);
    }

    e.slots = slots;
    e.maxWidth = maxWidth;
    e.maxHeight = maxHeight;
    e.maxShadowSize = maxShadowSize;
    e.frames.resize(slots);
    e.shadows.resize(maxShadowSize > 0 ? slots : 0);
    SkyStatus s = SkyStatus::success();
    for (uint32_t i = 0; i < slots && s.ok(); ++i)
    {
        s = createExportedImage(r, e.frames[i], VK_FORMAT_R8G8B8A8_UNORM, maxWidth, maxHeight,
                                "export frame " + std::to_string(i));
        if (s.ok() && maxShadowSize > 0)
            s = createExportedImage(r, e.shadows[i], VK_FORMAT_R32_SFLOAT, maxShadowSize, maxShadowSize,
                                    "export shadow " + std::to_string(i));
    }
    if (s.ok())
        s = createExportedTimeline(ctx, e.timeline);
    if (s.ok())
    {
        VkCommandPoolCreateInfo poolInfo = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = ctx.queueFamily;
        VkResult res = vkCreateCommandPool(ctx.device, &poolInfo, nullptr, &e.pool);
        if (res != VK_SUCCESS)
        {
            e.pool = VK_NULL_HANDLE;
            s = SkyStatus::failure(std::string("vkCreateCommandPool failed: ") + vkResultName(res), res);
        }
    }
    if (s.ok())
    {
        e.commands.resize(slots);
        VkCommandBufferAllocateInfo alloc = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = e.pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = slots;
        VK_CHECK(vkAllocateCommandBuffers(ctx.device, &alloc, e.commands.data()));
        e.fences.assign(slots, VK_NULL_HANDLE);
        e.fencePending.assign(slots, false);
        VkFenceCreateInfo fenceInfo = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        for (uint32_t i = 0; i < slots; ++i)
            VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &e.fences[i]));
    }
    if (!s.ok())
        destroyFrameExport(r, e);
    return s;
}

void destroyFrameExport(Renderer& r, FrameExport& e)
{
    const Context& ctx = r.ctx;
    for (size_t i = 0; i < e.fences.size(); ++i)
    {
        if (e.fencePending[i])
            vkWaitForFences(ctx.device, 1, &e.fences[i], VK_TRUE, UINT64_MAX);
        vkDestroyFence(ctx.device, e.fences[i], nullptr);
    }
    if (e.pool)
        vkDestroyCommandPool(ctx.device, e.pool, nullptr);
    if (e.timeline)
        vkDestroySemaphore(ctx.device, e.timeline, nullptr);
    for (ExportedImage& image : e.frames)
        destroyExportedImage(r, image);
    for (ExportedImage& image : e.shadows)
        destroyExportedImage(r, image);
    destroyLayers(r, e);
    e = FrameExport{};
}

namespace
{

// Checks the slot, the frame id and the frame's images against the export before anything is recorded.
SkyStatus checkExportRequest(const Renderer& r, const FrameExport& e, uint32_t slot, uint64_t frameId,
                             const RenderResult& frame)
{
    if (slot >= e.slots)
        return SkyStatus::failure("frame export: slot " + std::to_string(slot) + " of " + std::to_string(e.slots),
                                  VK_ERROR_UNKNOWN);
    if (frame.width == 0 || frame.height == 0 || !r.composite.displayImage.image || frame.width != r.composite.displayImage.extent.width ||
        frame.height != r.composite.displayImage.extent.height)
        return SkyStatus::failure("frame export: no rendered frame of this size on the GPU", VK_ERROR_UNKNOWN);
    if (frame.width > e.maxWidth || frame.height > e.maxHeight)
        return SkyStatus::failure("frame export: the frame (" + std::to_string(frame.width) + "x" +
                                      std::to_string(frame.height) + ") is larger than the exported images (" +
                                      std::to_string(e.maxWidth) + "x" + std::to_string(e.maxHeight) + ")",
                                  VK_ERROR_UNKNOWN);
    const uint32_t shadowSize = frame.shadowMapSize;
    if (shadowSize > 0 && (shadowSize > e.maxShadowSize || !r.shadowPass.image.image ||
                           r.shadowPass.image.extent.width != shadowSize))
        return SkyStatus::failure("frame export: the shadow map (" + std::to_string(shadowSize) +
                                      " texels) is larger than the exported shadow images (" +
                                      std::to_string(e.maxShadowSize) + ") or not on the GPU",
                                  VK_ERROR_UNKNOWN);
    if (e.timeline && frameId <= e.lastSignalled)
        return SkyStatus::failure("frame export: frame ids must increase (timeline semaphore)", VK_ERROR_UNKNOWN);
    return SkyStatus::success();
}

// The four barrier batches around the copies, in the order they are recorded.
struct CopyBarriers
{
    BarrierList acquire, toTransfer, toGeneral, release;
};

// Ownership of the exported images: they are handed to the importers (VK_QUEUE_FAMILY_EXTERNAL) in
// GENERAL layout after each copy and taken back before the next; layout changes are separate barriers
// so that release and acquire never transition (the importers acquire GENERAL -> GENERAL). Marks every
// target as in GENERAL layout from now on.
CopyBarriers copyBarriers(uint32_t family, const CopyJob* jobs, uint32_t jobCount)
{
    const uint32_t external = VK_QUEUE_FAMILY_EXTERNAL, ignored = VK_QUEUE_FAMILY_IGNORED;
    const VkPipelineStageFlags2 transfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, all = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL, srcOpt = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        dstOpt = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    CopyBarriers b;
    for (uint32_t i = 0; i < jobCount; ++i)
    {
        const CopyJob& p = jobs[i];
        // The renderer's images: its last writes (compute, transfer) before our reads.
        b.toTransfer.add(imageBarrier(p.source, {all, VK_ACCESS_2_MEMORY_WRITE_BIT, general, ignored},
                                      {transfer, VK_ACCESS_2_TRANSFER_READ_BIT, srcOpt, ignored}));
        // Our reads before the renderer's next writes (write-after-read on the same queue).
        b.toGeneral.add(imageBarrier(p.source, {transfer, VK_ACCESS_2_NONE, srcOpt, ignored},
                                     {all, VK_ACCESS_2_NONE, general, ignored}));
        if (p.target->general)
        {
            b.acquire.add(imageBarrier(p.target->image, {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, general, external},
                                       {transfer, VK_ACCESS_2_NONE, general, family}));
            b.toTransfer.add(imageBarrier(p.target->image, {transfer, VK_ACCESS_2_NONE, general, ignored},
                                          {transfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, dstOpt, ignored}));
        }
        else  // first use: nothing to keep, nothing owned elsewhere yet
            b.toTransfer.add(imageBarrier(p.target->image, {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                                                            VK_IMAGE_LAYOUT_UNDEFINED, ignored},
                                          {transfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, dstOpt, ignored}));
        p.target->general = true;
        b.toGeneral.add(imageBarrier(p.target->image, {transfer, VK_ACCESS_2_TRANSFER_WRITE_BIT, dstOpt, ignored},
                                     {all, VK_ACCESS_2_MEMORY_READ_BIT, general, ignored}));
        b.release.add(imageBarrier(p.target->image, {all, VK_ACCESS_2_NONE, general, family},
                                   {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, general, external}));
    }
    return b;
}

// Records each job's copy, sources in TRANSFER_SRC and targets in TRANSFER_DST layout.
void recordCopies(VkCommandBuffer cmd, const CopyJob* jobs, uint32_t jobCount)
{
    const VkImageLayout srcOpt = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dstOpt = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    for (uint32_t i = 0; i < jobCount; ++i)
    {
        const CopyJob& p = jobs[i];
        if (p.blit)
        {
            // Same size, NEAREST: an exact half -> float conversion of the red channel.
            VkImageBlit blit = {};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            blit.dstSubresource = blit.srcSubresource;
            blit.srcOffsets[1] = {int32_t(p.width), int32_t(p.height), 1};
            blit.dstOffsets[1] = blit.srcOffsets[1];
            vkCmdBlitImage(cmd, p.source, srcOpt, p.target->image, dstOpt, 1, &blit, VK_FILTER_NEAREST);
            continue;
        }
        VkImageCopy copy = {};  // same format: the renderer's values exactly
        copy.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.dstSubresource = copy.srcSubresource;
        copy.extent = {p.width, p.height, 1};
        vkCmdCopyImage(cmd, p.source, srcOpt, p.target->image, dstOpt, 1, &copy);
    }
}

// Submits the slot's commands, signalling the timeline at frameId where there is one.
SkyStatus submitCopies(const Context& ctx, FrameExport& e, uint32_t slot, VkCommandBuffer cmd, uint64_t frameId)
{
    VkTimelineSemaphoreSubmitInfo timelineInfo = {VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timelineInfo.signalSemaphoreValueCount = 1;
    timelineInfo.pSignalSemaphoreValues = &frameId;
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    if (e.timeline)
    {
        submit.pNext = &timelineInfo;
        submit.signalSemaphoreCount = 1;
        submit.pSignalSemaphores = &e.timeline;
    }
    VK_TRY(vkQueueSubmit(ctx.queue, 1, &submit, e.fences[slot]));
    e.fencePending[slot] = true;
    return SkyStatus::success();
}

}  // namespace

SkyStatus exportFrame(Renderer& r, FrameExport& e, uint32_t slot, uint64_t frameId, const RenderResult& frame,
                      uint32_t layers)
{
    const Context& ctx = r.ctx;
    SKY_TRY(checkExportRequest(r, e, slot, frameId, frame));
    const uint32_t shadowSize = frame.shadowMapSize;
    std::array<CopyJob, kMaxCopyJobs> jobs;
    uint32_t jobCount = 0;
    jobs[jobCount++] = {r.composite.displayImage.image, &e.frames[slot], frame.width, frame.height, false};
    if (shadowSize > 0)  // the shadow pass writes rgba16f: its red channel (transmittance) is blitted
        jobs[jobCount++] = {r.shadowPass.image.image, &e.shadows[slot], shadowSize, shadowSize, true};
    SKY_TRY(layerCopies(r, e, slot, layers, frame, jobs.data(), jobCount));
    SKY_TRY(waitSlot(ctx, e, slot));

    VkCommandBuffer cmd = e.commands[slot];
    VK_TRY(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_TRY(vkBeginCommandBuffer(cmd, &begin));
    const CopyBarriers barriers = copyBarriers(ctx.queueFamily, jobs.data(), jobCount);
    barriers.acquire.record(cmd);
    barriers.toTransfer.record(cmd);
    recordCopies(cmd, jobs.data(), jobCount);
    barriers.toGeneral.record(cmd);
    barriers.release.record(cmd);
    VK_TRY(vkEndCommandBuffer(cmd));

    SKY_TRY(submitCopies(ctx, e, slot, cmd, frameId));
    if (e.timeline)
    {
        e.lastSignalled = frameId;
        return SkyStatus::success();  // importers wait on the semaphore
    }
    return waitSlot(ctx, e, slot);  // no exportable semaphore: complete before the ring publishes the slot
}

bool describeFrameExport(Renderer& r, const FrameExport& e, uint32_t layers, nlohmann::json& description,
                         std::vector<int>& fds, std::string& error)
{
    const Context& ctx = r.ctx;
    fds.clear();
    description = nlohmann::json::object();
    if (!ctx.getMemoryFd || e.frames.empty())
    {
        error = "frame export is not set up (needs " + std::string(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME) + ")";
        return false;
    }
    auto fail = [&](const std::string& what, VkResult res) {
        for (int fd : fds)
            close(fd);
        fds.clear();
        error = what + " failed: " + vkResultName(res);
        return false;
    };
    nlohmann::json images = nlohmann::json::array();
    for (uint32_t i = 0; i < e.slots; ++i)
    {
        nlohmann::json entry = imageJson(e.frames[i]);
        entry["shadow"] = e.shadows.empty() ? nlohmann::json(nullptr) : imageJson(e.shadows[i]);
        images.push_back(std::move(entry));
    }
    for (const ExportedImage& image : e.frames)
        if (VkResult res = exportMemoryFd(ctx, image, fds); res != VK_SUCCESS)
            return fail("vkGetMemoryFdKHR (" + image.name + ")", res);
    for (const ExportedImage& image : e.shadows)
        if (VkResult res = exportMemoryFd(ctx, image, fds); res != VK_SUCCESS)
            return fail("vkGetMemoryFdKHR (" + image.name + ")", res);
    if (!describeLayers(ctx, e, layers, images, fds, error))
    {
        for (int fd : fds)
            close(fd);
        fds.clear();
        return false;
    }
    if (e.timeline)
    {
        VkSemaphoreGetFdInfoKHR info = {VK_STRUCTURE_TYPE_SEMAPHORE_GET_FD_INFO_KHR};
        info.semaphore = e.timeline;
        info.handleType = kSemaphoreHandle;
        int fd = -1;
        VkResult res = ctx.getSemaphoreFd(ctx.device, &info, &fd);
        if (res != VK_SUCCESS)
            return fail("vkGetSemaphoreFdKHR", res);
        fds.push_back(fd);
    }
    description["images"] = std::move(images);
    description["timeline_semaphore"] = e.timeline != VK_NULL_HANDLE;
    description["device_uuid"] = hex(ctx.deviceUUID, VK_UUID_SIZE);
    description["driver_uuid"] = hex(ctx.driverUUID, VK_UUID_SIZE);
    error.clear();
    return true;
}

}  // namespace sky
