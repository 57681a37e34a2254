// SPDX-License-Identifier: MIT
#include "client_demo/presenter.h"

#include <cstring>

namespace demo
{
namespace
{

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                  VkAccessFlags dstAccess, VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage)
{
    VkImageMemoryBarrier b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

bool isSrgb(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB; }

void destroyStaging(const VulkanDevice& vk, Presenter& p)
{
    if (p.staging != VK_NULL_HANDLE)
        vkDestroyImage(vk.device, p.staging, nullptr);
    if (p.stagingMemory != VK_NULL_HANDLE)
        vkFreeMemory(vk.device, p.stagingMemory, nullptr);
    p.staging = VK_NULL_HANDLE;
    p.stagingMemory = VK_NULL_HANDLE;
    p.stagingWidth = p.stagingHeight = 0;
}

// The staging image has the swapchain's encoding (UNORM or SRGB), so the blit passes the sRGB bytes
// through unchanged either way.
void ensureStaging(const VulkanDevice& vk, Presenter& p, uint32_t width, uint32_t height, VkFormat swapchainFormat)
{
    const VkFormat format = isSrgb(swapchainFormat) ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    if (p.staging != VK_NULL_HANDLE && p.stagingWidth == width && p.stagingHeight == height && p.stagingFormat == format)
        return;
    destroyStaging(vk, p);
    VkImageCreateInfo info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    DEMO_VK_CHECK(vkCreateImage(vk.device, &info, nullptr, &p.staging));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk.device, p.staging, &req);
    VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = findMemoryType(vk.physicalDevice, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (alloc.memoryTypeIndex == UINT32_MAX)
        alloc.memoryTypeIndex = findMemoryType(vk.physicalDevice, req.memoryTypeBits, 0);
    DEMO_VK_CHECK(vkAllocateMemory(vk.device, &alloc, nullptr, &p.stagingMemory));
    DEMO_VK_CHECK(vkBindImageMemory(vk.device, p.staging, p.stagingMemory, 0));
    p.stagingWidth = width;
    p.stagingHeight = height;
    p.stagingFormat = format;
}

void ensureBuffer(const VulkanDevice& vk, HostBuffer& buffer, VkDeviceSize bytes)
{
    if (buffer.bytes >= bytes)
        return;
    destroyHostBuffer(vk, buffer);
    createHostBuffer(vk, bytes, buffer);
}

// Copies the frame (already in p.upload) into the staging image and leaves it ready to blit from.
void recordUpload(VkCommandBuffer cmd, const Presenter& p, const sky::ImageRgba8& image)
{
    imageBarrier(cmd, p.staging, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkBufferImageCopy upload = {};
    upload.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    upload.imageExtent = {image.width, image.height, 1};
    vkCmdCopyBufferToImage(cmd, p.upload.buffer, p.staging, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &upload);
    imageBarrier(cmd, p.staging, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT);
}

// Scales the staging image onto the whole swapchain image, which is left in TRANSFER_DST layout.
void recordBlitToSwapchain(VkCommandBuffer cmd, const Presenter& p, const Swapchain& sc, const sky::ImageRgba8& image,
                           VkImage target)
{
    // The acquire semaphore is waited on at the transfer stage, so the swapchain image's transition waits too.
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkImageBlit blit = {};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(image.width), int32_t(image.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(sc.width), int32_t(sc.height), 1};
    vkCmdBlitImage(cmd, p.staging, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   1, &blit, VK_FILTER_LINEAR);
}

// Copies the swapchain image (after the blit) into p.readback; returns the layout it is left in.
VkImageLayout recordReadback(VkCommandBuffer cmd, const Presenter& p, const Swapchain& sc, VkImage target)
{
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT);
    const VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    VkBufferImageCopy copy = {};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {sc.width, sc.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, layout, p.readback.buffer, 1, &copy);
    return layout;
}

// Records the frame's commands into p.cmd: upload, blit to the swapchain image, optional readback,
// hand-over to the presentation engine.
void recordPresentCommands(const Presenter& p, const Swapchain& sc, const sky::ImageRgba8& image, VkImage target,
                           bool readBack)
{
    VkCommandBuffer cmd = p.cmd;
    DEMO_VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    DEMO_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    recordUpload(cmd, p, image);
    recordBlitToSwapchain(cmd, p, sc, image, target);
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    if (readBack)
        layout = recordReadback(cmd, p, sc, target);
    imageBarrier(cmd, target, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_ACCESS_TRANSFER_WRITE_BIT, 0,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    DEMO_VK_CHECK(vkEndCommandBuffer(cmd));
}

// Submits p.cmd after the acquire and queues swapchain image `index` for presentation after it.
VkResult submitAndPresent(const VulkanDevice& vk, Presenter& p, const Swapchain& sc, uint32_t index)
{
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &p.imageAcquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &p.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &p.renderDone;
    DEMO_VK_CHECK(vkQueueSubmit(vk.queue, 1, &submit, p.frameDone));

    VkPresentInfoKHR present = {VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &p.renderDone;
    present.swapchainCount = 1;
    present.pSwapchains = &sc.swapchain;
    present.pImageIndices = &index;
    return vkQueuePresentKHR(vk.queue, &present);
}

// Waits for the frame and copies p.readback into `screenshot` as RGBA with opaque alpha.
void readScreenshot(const VulkanDevice& vk, const Presenter& p, const Swapchain& sc, sky::ImageRgba8& screenshot)
{
    DEMO_VK_CHECK(vkWaitForFences(vk.device, 1, &p.frameDone, VK_TRUE, UINT64_MAX));
    screenshot.width = sc.width;
    screenshot.height = sc.height;
    const auto* src = static_cast<const uint8_t*>(p.readback.mapped);
    screenshot.pixels.assign(src, src + size_t(sc.width) * sc.height * 4);
    const bool bgra = sc.format == VK_FORMAT_B8G8R8A8_UNORM || sc.format == VK_FORMAT_B8G8R8A8_SRGB;
    for (size_t i = 0; i < screenshot.pixels.size(); i += 4)
    {
        if (bgra)
            std::swap(screenshot.pixels[i], screenshot.pixels[i + 2]);
        screenshot.pixels[i + 3] = 255;
    }
}

}  // namespace

void createPresenter(const VulkanDevice& vk, Presenter& p)
{
    VkSemaphoreCreateInfo sem = {VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    DEMO_VK_CHECK(vkCreateSemaphore(vk.device, &sem, nullptr, &p.imageAcquired));
    DEMO_VK_CHECK(vkCreateSemaphore(vk.device, &sem, nullptr, &p.renderDone));
    VkFenceCreateInfo fence = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    DEMO_VK_CHECK(vkCreateFence(vk.device, &fence, nullptr, &p.frameDone));
    VkCommandBufferAllocateInfo alloc = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = vk.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    DEMO_VK_CHECK(vkAllocateCommandBuffers(vk.device, &alloc, &p.cmd));
}

void destroyPresenter(const VulkanDevice& vk, Presenter& p)
{
    vkDeviceWaitIdle(vk.device);
    destroyStaging(vk, p);
    destroyHostBuffer(vk, p.upload);
    destroyHostBuffer(vk, p.readback);
    vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &p.cmd);
    vkDestroyFence(vk.device, p.frameDone, nullptr);
    vkDestroySemaphore(vk.device, p.renderDone, nullptr);
    vkDestroySemaphore(vk.device, p.imageAcquired, nullptr);
    p = Presenter{};
}

SwapchainStatus presentImage(const VulkanDevice& vk, Presenter& p, const Swapchain& sc, const sky::ImageRgba8& image,
                             sky::ImageRgba8* screenshot)
{
    if (image.width == 0 || image.height == 0 || sc.swapchain == VK_NULL_HANDLE)
        return SwapchainStatus::NotReady;
    DEMO_VK_CHECK(vkWaitForFences(vk.device, 1, &p.frameDone, VK_TRUE, UINT64_MAX));
    uint32_t index = 0;
    const VkResult acquired = vkAcquireNextImageKHR(vk.device, sc.swapchain, UINT64_MAX, p.imageAcquired,
                                                    VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR)
    {
        p.outOfDate = true;
        return SwapchainStatus::Resized;
    }
    if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR)
        DEMO_VK_CHECK(acquired);
    DEMO_VK_CHECK(vkResetFences(vk.device, 1, &p.frameDone));

    const VkDeviceSize bytes = VkDeviceSize(image.width) * image.height * 4;
    ensureBuffer(vk, p.upload, bytes);
    std::memcpy(p.upload.mapped, image.pixels.data(), size_t(bytes));
    ensureStaging(vk, p, image.width, image.height, sc.format);
    const bool readBack = screenshot != nullptr && sc.canReadBack;
    if (readBack)
        ensureBuffer(vk, p.readback, VkDeviceSize(sc.width) * sc.height * 4);
    const VkImage target = sc.images[index];

    recordPresentCommands(p, sc, image, target, readBack);
    const VkResult presented = submitAndPresent(vk, p, sc, index);
    if (readBack)
        readScreenshot(vk, p, sc, *screenshot);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR || acquired == VK_SUBOPTIMAL_KHR)
        p.outOfDate = true;
    else if (presented != VK_SUCCESS)
        DEMO_VK_CHECK(presented);
    return SwapchainStatus::Ready;
}

}  // namespace demo
