// SPDX-License-Identifier: MIT
#include "client_demo/vulkan_import.h"

#include "skyservice/client/vulkan/skyclient_vulkan.h"

#include <glm/gtc/packing.hpp>
#include <unistd.h>

#include <algorithm>
#include <cstring>

namespace demo
{

struct VulkanFrameImport::Imported
{
    SkyImportedFrames frames{};
    SkyImportedLayers layers{};
};

namespace
{

constexpr uint32_t kCompositingLayers[] = {SKY_LAYER_SKY, SKY_LAYER_CLOUDS, SKY_LAYER_DEPTH};

// The layer images hold RGBA16F (sky, clouds) or RG32F (depth): 8 bytes a pixel; LatestFrame holds floats.
void widenLayer(const uint8_t* bytes, size_t pixels, uint32_t layer, std::vector<float>& out)
{
    if (layer == SKY_LAYER_DEPTH)
    {
        out.resize(pixels * 2);
        std::memcpy(out.data(), bytes, pixels * 8);
        return;
    }
    out.resize(pixels * 4);
    for (size_t k = 0; k < pixels * 4; ++k)
    {
        uint16_t bits = 0;
        std::memcpy(&bits, bytes + 2 * k, 2);
        out[k] = glm::unpackHalf1x16(bits);
    }
}

}  // namespace

VulkanFrameImport::VulkanFrameImport(const VulkanDevice& vk) : vk_(vk) {}

VkPhysicalDevice VulkanFrameImport::findServiceDevice(VkInstance instance, const SkyExportedFrames& exported)
{
    VkPhysicalDevice pd = VK_NULL_HANDLE;
    if (sky_vulkan_find_physical_device(instance, &exported, &pd) != SKY_OK)
        return VK_NULL_HANDLE;
    return pd;
}

std::vector<const char*> VulkanFrameImport::requiredExtensions()
{
    // The demo waits on the ring's publication, not on the semaphore: lavapipe exports none, and a GPU that
    // does publishes a slot only when it is complete as well (skyclient_vulkan.h "Synchronisation").
    uint32_t count = 0;
    const char* const* names = sky_vulkan_required_device_extensions(0, &count);
    return std::vector<const char*>(names, names + count);
}

void closeExportedFds(SkyExportedFrames& exported)
{
    for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS; ++i)
        for (SkyExportedImage* image : {&exported.frame[i], &exported.shadow[i], &exported.layer[SKY_LAYER_SKY][i],
                                        &exported.layer[SKY_LAYER_CLOUDS][i], &exported.layer[SKY_LAYER_DEPTH][i]})
            if (image->memory_fd >= 0)
            {
                ::close(image->memory_fd);
                image->memory_fd = -1;
            }
    if (exported.timeline_semaphore_fd >= 0)
    {
        ::close(exported.timeline_semaphore_fd);
        exported.timeline_semaphore_fd = -1;
    }
}

std::unique_ptr<VulkanFrameImport> VulkanFrameImport::create(const VulkanDevice& vk, SkyExportedFrames& exported,
                                                             std::string& error)
{
    // The semaphore is not imported (see requiredExtensions): close its fd first.
    if (exported.timeline_semaphore_fd >= 0)
    {
        ::close(exported.timeline_semaphore_fd);
        exported.timeline_semaphore_fd = -1;
    }
    std::unique_ptr<VulkanFrameImport> import(new VulkanFrameImport(vk));
    import->imported_ = std::make_unique<Imported>();
    if (sky_vulkan_import_frames(vk.physicalDevice, vk.device, &exported, &import->imported_->frames) != SKY_OK)
    {
        error = std::string("importing the service's frames: ") + sky_vulkan_last_error();
        import->imported_.reset();
        closeExportedFds(exported);  // sky_vulkan_import_frames closed and reset the rest already
        return nullptr;
    }
    if (sky_vulkan_import_layers(vk.physicalDevice, vk.device, &exported, &import->imported_->layers) != SKY_OK)
    {
        error = std::string("importing the service's compositing layers: ") + sky_vulkan_last_error();
        return nullptr;  // ~VulkanFrameImport destroys the frames; the layer fds were closed
    }
    VkDeviceSize bytes = 0;
    for (uint32_t i = 0; i < exported.slot_count; ++i)
    {
        const SkyImportedImage& f = import->imported_->frames.frame[i];
        const SkyImportedImage& s = import->imported_->frames.shadow[i];
        VkDeviceSize slot = VkDeviceSize(f.width) * f.height * 4 + VkDeviceSize(s.width) * s.height * 4;
        for (uint32_t layer : kCompositingLayers)
            if (import->imported_->layers.image[layer][i].image != VK_NULL_HANDLE)
                slot += VkDeviceSize(f.width) * f.height * 8;
        bytes = std::max(bytes, slot);
    }
    createHostBuffer(vk, std::max<VkDeviceSize>(bytes, 16), import->readback_);
    return import;
}

VulkanFrameImport::~VulkanFrameImport()
{
    if (imported_)
    {
        vkDeviceWaitIdle(vk_.device);
        sky_vulkan_destroy_frames(vk_.device, &imported_->frames);
        sky_vulkan_destroy_layers(vk_.device, &imported_->layers);
    }
    destroyHostBuffer(vk_, readback_);
}

bool VulkanFrameImport::copySlot(uint32_t slot, uint64_t /*frameId*/, uint32_t width, uint32_t height,
                                 uint32_t shadowSize, LatestFrame& out, std::string& error)
{
    const SkyImportedFrames& frames = imported_->frames;
    if (slot >= frames.slot_count || frames.frame[slot].image == VK_NULL_HANDLE ||
        width > frames.frame[slot].width || height > frames.frame[slot].height)
    {
        error = "slot " + std::to_string(slot) + " has no imported image of " + std::to_string(width) + "x" +
                std::to_string(height);
        return false;
    }
    const SkyImportedImage& shadow = frames.shadow[slot];
    if (shadow.image == VK_NULL_HANDLE || shadowSize > shadow.width || shadowSize > shadow.height)
        shadowSize = 0;
    const VkDeviceSize frameBytes = VkDeviceSize(width) * height * 4;

    VkCommandBuffer cmd = beginOneTimeCommands(vk_);
    sky_vulkan_cmd_acquire(cmd, &frames.frame[slot], vk_.queueFamily);
    // A frame smaller than the image sits in its top-left corner (skyclient_vulkan.h).
    VkBufferImageCopy region = {};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, frames.frame[slot].image, VK_IMAGE_LAYOUT_GENERAL, readback_.buffer, 1, &region);
    if (shadowSize > 0)
    {
        sky_vulkan_cmd_acquire(cmd, &shadow, vk_.queueFamily);
        VkBufferImageCopy shadowRegion = {};
        shadowRegion.bufferOffset = frameBytes;
        shadowRegion.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        shadowRegion.imageExtent = {shadowSize, shadowSize, 1};
        vkCmdCopyImageToBuffer(cmd, shadow.image, VK_IMAGE_LAYOUT_GENERAL, readback_.buffer, 1, &shadowRegion);
    }
    // The compositing layers (those imported), after the shadow map, 8 bytes a pixel each.
    const VkDeviceSize layerBytes = VkDeviceSize(width) * height * 8;
    VkDeviceSize layerOffset[SKY_LAYER_COUNT] = {};
    VkDeviceSize next = frameBytes + VkDeviceSize(shadowSize) * shadowSize * 4;
    for (uint32_t layer : kCompositingLayers)
    {
        const SkyImportedImage& image = imported_->layers.image[layer][slot];
        if (image.image == VK_NULL_HANDLE)
            continue;
        sky_vulkan_cmd_acquire(cmd, &image, vk_.queueFamily);
        VkBufferImageCopy layerRegion = {};
        layerRegion.bufferOffset = layerOffset[layer] = next;
        layerRegion.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        layerRegion.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_GENERAL, readback_.buffer, 1, &layerRegion);
        next += layerBytes;
    }
    VkMemoryBarrier toHost = {VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                         nullptr);
    submitAndWait(vk_, cmd);

    const auto* bytes = static_cast<const uint8_t*>(readback_.mapped);
    out.width = width;
    out.height = height;
    out.rgba.assign(bytes, bytes + frameBytes);
    out.shadowSize = shadowSize;
    out.shadowTransmittance.resize(size_t(shadowSize) * shadowSize);
    if (shadowSize > 0)
        std::memcpy(out.shadowTransmittance.data(), bytes + frameBytes, out.shadowTransmittance.size() * sizeof(float));
    std::vector<float>* targets[SKY_LAYER_COUNT] = {nullptr, &out.skyRgba, &out.cloudsRgba, &out.depthM};
    for (uint32_t layer : kCompositingLayers)
    {
        if (imported_->layers.image[layer][slot].image == VK_NULL_HANDLE)
            targets[layer]->clear();
        else
            widenLayer(bytes + layerOffset[layer], size_t(width) * height, layer, *targets[layer]);
    }
    return true;
}

}  // namespace demo
