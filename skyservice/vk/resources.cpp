// SPDX-License-Identifier: MIT
#include "skyservice/vk/resources.h"

#include <algorithm>
#include <cstring>

namespace sky
{
namespace
{

bool chooseMemoryType(const Context& ctx, uint32_t typeBits, VkMemoryPropertyFlags wanted, uint32_t& index)
{
    for (uint32_t i = 0; i < ctx.memoryProperties.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (ctx.memoryProperties.memoryTypes[i].propertyFlags & wanted) == wanted)
        {
            index = i;
            return true;
        }
    return false;
}

SkyStatus allocate(const Context& ctx, MemoryTracker& tracker, const VkMemoryRequirements& req, MemoryUse use,
                   const char* name, VkDeviceMemory& memory, bool* coherent = nullptr)
{
    uint32_t type = 0;
    bool found = false;
    if (use == MemoryUse::HostReadback)
        found = chooseMemoryType(ctx, req.memoryTypeBits,
                                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, type);
    if (!found)
    {
        VkMemoryPropertyFlags wanted = use == MemoryUse::DeviceLocal
                                           ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                           : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        found = chooseMemoryType(ctx, req.memoryTypeBits, wanted, type);
    }
    if (!found)
        return SkyStatus::failure(std::string("no suitable memory type for ") + name, VK_ERROR_OUT_OF_DEVICE_MEMORY);
    if (coherent)
        *coherent = (ctx.memoryProperties.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
    VkMemoryAllocateInfo info = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = req.size;
    info.memoryTypeIndex = type;
    VkResult r = vkAllocateMemory(ctx.device, &info, nullptr, &memory);
    if (r != VK_SUCCESS)
    {
        memory = VK_NULL_HANDLE;
        return SkyStatus::failure(std::string("out of device memory allocating ") + std::to_string(req.size) +
                                      " bytes for " + name + " (" + vkResultName(r) + ")",
                                  r);
    }
    std::lock_guard<std::mutex> lock(tracker.mutex);
    tracker.liveBytes[name] += req.size;
    if (use == MemoryUse::HostReadback)
        tracker.hostReadbackBytes += req.size;
    else if (use == MemoryUse::HostStaging)
        tracker.hostStagingBytes += req.size;
    else
    {
        tracker.totalBytes += req.size;
        tracker.peakBytes = std::max(tracker.peakBytes, tracker.totalBytes);
    }
    return SkyStatus::success();
}

void release(const Context& ctx, MemoryTracker& tracker, VkDeviceMemory& memory, VkDeviceSize size,
             const std::string& name, bool hostReadback = false, bool hostStaging = false)
{
    if (!memory)
        return;
    vkFreeMemory(ctx.device, memory, nullptr);
    memory = VK_NULL_HANDLE;
    std::lock_guard<std::mutex> lock(tracker.mutex);
    auto it = tracker.liveBytes.find(name);
    if (it != tracker.liveBytes.end())
    {
        it->second -= std::min(it->second, size);
        if (it->second == 0)
            tracker.liveBytes.erase(it);
    }
    VkDeviceSize& total =
        hostReadback ? tracker.hostReadbackBytes : hostStaging ? tracker.hostStagingBytes : tracker.totalBytes;
    total -= std::min(total, size);
}

}  // namespace

uint32_t formatBytes(VkFormat format)
{
    switch (format)
    {
    case VK_FORMAT_R8_UNORM:
        return 1;
    case VK_FORMAT_R8G8_UINT:
        return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32_UINT:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R16G16B16A16_UINT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 16;
    default:
        return 0;
    }
}

SkyStatus createBuffer(const Context& ctx, MemoryTracker& tracker, Buffer& out, VkDeviceSize size,
                       VkBufferUsageFlags usage, MemoryUse use, const char* name)
{
    out = Buffer{};
    VkBufferCreateInfo info = {VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    VK_TRY(vkCreateBuffer(ctx.device, &info, nullptr, &out.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device, out.buffer, &req);
    bool coherent = true;
    SkyStatus s = allocate(ctx, tracker, req, use, name, out.memory, &coherent);
    if (!s.ok())
    {
        vkDestroyBuffer(ctx.device, out.buffer, nullptr);
        out = Buffer{};
        return s;
    }
    VK_CHECK(vkBindBufferMemory(ctx.device, out.buffer, out.memory, 0));
    if (use != MemoryUse::DeviceLocal)
        VK_CHECK(vkMapMemory(ctx.device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
    out.hostCoherent = coherent;
    out.hostReadback = use == MemoryUse::HostReadback;
    out.hostStaging = use == MemoryUse::HostStaging;
    // The descriptor range must not exceed the buffer's own size (VUID-VkDescriptorBufferInfo-range-00342,
    // seen on NVIDIA where req.size is padded); the tracker counts the padded allocation.
    out.size = size;
    out.allocationBytes = req.size;
    out.name = name;
    setObjectName(ctx, VK_OBJECT_TYPE_BUFFER, uint64_t(out.buffer), name);
    return SkyStatus::success();
}

void destroyBuffer(const Context& ctx, MemoryTracker& tracker, Buffer& buffer)
{
    if (buffer.buffer)
        vkDestroyBuffer(ctx.device, buffer.buffer, nullptr);
    release(ctx, tracker, buffer.memory, buffer.allocationBytes, buffer.name, buffer.hostReadback,
            buffer.hostStaging);
    buffer = Buffer{};
}

void invalidateForHost(const Context& ctx, const Buffer& buffer)
{
    if (buffer.hostCoherent || !buffer.memory)
        return;
    VkMappedMemoryRange range = {VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = buffer.memory;
    range.size = VK_WHOLE_SIZE;
    VK_CHECK(vkInvalidateMappedMemoryRanges(ctx.device, 1, &range));
}

SkyStatus createImage(const Context& ctx, MemoryTracker& tracker, Image& out, const ImageDesc& desc, const char* name)
{
    out = Image{};
    VkImageCreateInfo info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = desc.viewType == VK_IMAGE_VIEW_TYPE_3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.width, desc.height, desc.viewType == VK_IMAGE_VIEW_TYPE_3D ? desc.depth : 1};
    info.mipLevels = 1;
    info.arrayLayers = desc.viewType == VK_IMAGE_VIEW_TYPE_2D_ARRAY ? desc.layers : 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    if (desc.sampledFormat != VK_FORMAT_UNDEFINED)
        info.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    VK_TRY(vkCreateImage(ctx.device, &info, nullptr, &out.image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device, out.image, &req);
    SkyStatus s = allocate(ctx, tracker, req, MemoryUse::DeviceLocal, name, out.memory);
    if (!s.ok())
    {
        vkDestroyImage(ctx.device, out.image, nullptr);
        out = Image{};
        return s;
    }
    VK_CHECK(vkBindImageMemory(ctx.device, out.image, out.memory, 0));

    VkImageViewCreateInfo viewInfo = {VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = out.image;
    viewInfo.viewType = desc.viewType;
    viewInfo.format = desc.format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, info.arrayLayers};
    VK_CHECK(vkCreateImageView(ctx.device, &viewInfo, nullptr, &out.view));
    if (desc.sampledFormat != VK_FORMAT_UNDEFINED)
    {
        // Sampling only: the sampled format need not support the image's storage usage.
        VkImageViewUsageCreateInfo usage = {VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
        usage.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
        viewInfo.pNext = &usage;
        viewInfo.format = desc.sampledFormat;
        VK_CHECK(vkCreateImageView(ctx.device, &viewInfo, nullptr, &out.sampledView));
        setObjectName(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(out.sampledView), name);
    }

    out.format = desc.format;
    out.viewType = desc.viewType;
    out.extent = info.extent;
    out.layers = info.arrayLayers;
    out.bytes = req.size;
    out.name = name;
    setObjectName(ctx, VK_OBJECT_TYPE_IMAGE, uint64_t(out.image), name);
    setObjectName(ctx, VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(out.view), name);
    return SkyStatus::success();
}

void destroyImage(const Context& ctx, MemoryTracker& tracker, Image& image)
{
    if (image.view)
        vkDestroyImageView(ctx.device, image.view, nullptr);
    if (image.sampledView)
        vkDestroyImageView(ctx.device, image.sampledView, nullptr);
    if (image.image)
        vkDestroyImage(ctx.device, image.image, nullptr);
    release(ctx, tracker, image.memory, image.bytes, image.name);
    image = Image{};
}

void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to)
{
    VkImageMemoryBarrier2 barrier = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image.image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
    VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void computeBarrier(VkCommandBuffer cmd)
{
    VkMemoryBarrier2 barrier = {VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
    barrier.dstAccessMask =
        VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
    VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

SkyStatus createCommandBuffer(const Context& ctx, VkCommandPoolCreateFlags flags, VkCommandPool& pool,
                              VkCommandBuffer& cmd)
{
    VkCommandPoolCreateInfo poolInfo = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = flags;
    poolInfo.queueFamilyIndex = ctx.queueFamily;
    VK_TRY(vkCreateCommandPool(ctx.device, &poolInfo, nullptr, &pool));
    VkCommandBufferAllocateInfo alloc = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_TRY(vkAllocateCommandBuffers(ctx.device, &alloc, &cmd));
    return SkyStatus::success();
}

SkyStatus beginOneShot(const Context& ctx, OneShot& shot)
{
    SKY_TRY(createCommandBuffer(ctx, VK_COMMAND_POOL_CREATE_TRANSIENT_BIT, shot.pool, shot.cmd));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(shot.cmd, &begin));
    return SkyStatus::success();
}

SkyStatus endOneShot(const Context& ctx, OneShot& shot)
{
    VK_CHECK(vkEndCommandBuffer(shot.cmd));
    VkFenceCreateInfo fenceInfo = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(ctx.device, &fenceInfo, nullptr, &fence));
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &shot.cmd;
    VkResult r = vkQueueSubmit(ctx.queue, 1, &submit, fence);
    if (r == VK_SUCCESS)
        r = vkWaitForFences(ctx.device, 1, &fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(ctx.device, fence, nullptr);
    vkDestroyCommandPool(ctx.device, shot.pool, nullptr);
    shot = OneShot{};
    if (r != VK_SUCCESS)
        return SkyStatus::failure(std::string("GPU work failed: ") + vkResultName(r), r);
    return SkyStatus::success();
}

SkyStatus uploadImage(const Context& ctx, MemoryTracker& tracker, Image& image, const void* data, size_t bytes,
                      VkImageLayout finalLayout)
{
    return uploadImages(ctx, tracker, {ImageUpload{&image, data, bytes, finalLayout}});
}

SkyStatus uploadImages(const Context& ctx, MemoryTracker& tracker, std::initializer_list<ImageUpload> uploads)
{
    // Each image's bytes start at a multiple of 16 (vkCmdCopyBufferToImage wants the texel size and 4).
    auto aligned = [](size_t n) { return (n + 15) & ~size_t(15); };
    size_t total = 0;
    for (const ImageUpload& u : uploads)
        total += aligned(u.bytes);
    Buffer staging;
    SKY_TRY(createBuffer(ctx, tracker, staging, std::max<size_t>(total, 16), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         MemoryUse::HostVisible, "staging upload"));
    size_t offset = 0;
    for (const ImageUpload& u : uploads)
    {
        std::memcpy(static_cast<uint8_t*>(staging.mapped) + offset, u.data, u.bytes);
        offset += aligned(u.bytes);
    }
    OneShot shot;
    SkyStatus s = beginOneShot(ctx, shot);
    if (s.ok())
    {
        offset = 0;
        for (const ImageUpload& u : uploads)
        {
            Image& image = *u.image;
            transitionImage(shot.cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy region = {};
            region.bufferOffset = offset;
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, image.layers};
            region.imageExtent = image.extent;
            vkCmdCopyBufferToImage(shot.cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &region);
            transitionImage(shot.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, u.finalLayout);
            offset += aligned(u.bytes);
        }
        s = endOneShot(ctx, shot);
    }
    destroyBuffer(ctx, tracker, staging);
    return s;
}

SkyStatus readbackImage(const Context& ctx, MemoryTracker& tracker, const Image& image, std::vector<uint8_t>& out)
{
    size_t bytes = size_t(image.extent.width) * image.extent.height * image.extent.depth * formatBytes(image.format);
    Buffer staging;
    SKY_TRY(createBuffer(ctx, tracker, staging, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostVisible,
                         "staging readback"));
    OneShot shot;
    SkyStatus s = beginOneShot(ctx, shot);
    if (s.ok())
    {
        transitionImage(shot.cmd, image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy region = {};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = image.extent;
        vkCmdCopyImageToBuffer(shot.cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
        transitionImage(shot.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        s = endOneShot(ctx, shot);
    }
    if (s.ok())
    {
        out.resize(bytes);
        std::memcpy(out.data(), staging.mapped, bytes);
    }
    destroyBuffer(ctx, tracker, staging);
    return s;
}

}  // namespace sky
