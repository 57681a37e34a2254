/* SPDX-License-Identifier: MIT */
#include "skyservice/client/vulkan/skyclient_vulkan.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static _Thread_local char g_error[256];

static SkyResult fail(SkyResult result, const char* format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(g_error, sizeof g_error, format, args);
    va_end(args);
    return result;
}

static SkyResult ok(void)
{
    g_error[0] = '\0';
    return SKY_OK;
}

const char* sky_vulkan_last_error(void)
{
    return g_error;
}

const char* const* sky_vulkan_required_device_extensions(int with_semaphore, uint32_t* count)
{
    static const char* const names[2] = {VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME,
                                         VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME};
    if (count)
        *count = with_semaphore ? 2u : 1u;
    return names;
}

SkyResult sky_vulkan_find_physical_device(VkInstance instance, const SkyExportedFrames* frames,
                                          VkPhysicalDevice* out_physical_device)
{
    if (!instance || !frames || !out_physical_device)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_find_physical_device: null argument");
    *out_physical_device = VK_NULL_HANDLE;
    VkPhysicalDevice devices[16];
    uint32_t count = 16;
    VkResult r = vkEnumeratePhysicalDevices(instance, &count, devices);
    if (r != VK_SUCCESS && r != VK_INCOMPLETE)
        return fail(SKY_ERR_VULKAN, "vkEnumeratePhysicalDevices failed (%d)", (int)r);
    for (uint32_t i = 0; i < count; ++i)
    {
        VkPhysicalDeviceIDProperties id = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
        VkPhysicalDeviceProperties2 props = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        props.pNext = &id;
        vkGetPhysicalDeviceProperties2(devices[i], &props);
        if (memcmp(id.deviceUUID, frames->device_uuid, VK_UUID_SIZE) == 0 &&
            memcmp(id.driverUUID, frames->driver_uuid, VK_UUID_SIZE) == 0)
        {
            *out_physical_device = devices[i];
            return ok();
        }
    }
    return fail(SKY_ERR_VULKAN, "none of the %u Vulkan devices has the service's device and driver UUID", count);
}

SkyResult sky_vulkan_import_image(VkPhysicalDevice physical_device, VkDevice device, SkyExportedImage* image,
                                  SkyImportedImage* out_image)
{
    if (!physical_device || !device || !image || !out_image)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_import_image: null argument");
    memset(out_image, 0, sizeof *out_image);
    if (image->memory_fd < 0 || image->width == 0 || image->height == 0 || image->allocation_bytes == 0)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_import_image: no fd or an empty image");

    VkExternalMemoryImageCreateInfo external = {VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_IMAGE_CREATE_INFO};
    external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkImageCreateInfo info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.pNext = &external;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = (VkFormat)image->vk_format;
    info.extent.width = image->width;
    info.extent.height = image->height;
    info.extent.depth = 1;
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = image->linear_tiling ? VK_IMAGE_TILING_LINEAR : VK_IMAGE_TILING_OPTIMAL;
    info.usage = SKY_VULKAN_IMAGE_USAGE;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage vkImage = VK_NULL_HANDLE;
    VkResult r = vkCreateImage(device, &info, NULL, &vkImage);
    if (r != VK_SUCCESS)
        return fail(SKY_ERR_VULKAN, "vkCreateImage (format %u, %ux%u) failed (%d)", image->vk_format, image->width,
                    image->height, (int)r);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, vkImage, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(physical_device, &mem);
    /* The same kind of memory as the exporter's: a type both allow, device-local first. */
    uint32_t allowed = req.memoryTypeBits & (image->memory_type_bits ? image->memory_type_bits : ~0u);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < mem.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((allowed & (1u << i)) && (mem.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = i;
    for (uint32_t i = 0; i < mem.memoryTypeCount && type == UINT32_MAX; ++i)
        if (allowed & (1u << i))
            type = i;
    if (type == UINT32_MAX || req.size > image->allocation_bytes)
    {
        vkDestroyImage(device, vkImage, NULL);
        return fail(SKY_ERR_VULKAN, "the imported image needs %llu bytes of memory types 0x%x; the export has %llu "
                    "bytes of types 0x%x (not the same device or driver?)",
                    (unsigned long long)req.size, req.memoryTypeBits, (unsigned long long)image->allocation_bytes,
                    image->memory_type_bits);
    }

    VkMemoryDedicatedAllocateInfo dedicated = {VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.image = vkImage;
    VkImportMemoryFdInfoKHR import = {VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR};
    import.pNext = &dedicated;
    import.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    import.fd = image->memory_fd;
    VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.pNext = &import;
    alloc.allocationSize = image->allocation_bytes;
    alloc.memoryTypeIndex = type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    r = vkAllocateMemory(device, &alloc, NULL, &memory);
    if (r != VK_SUCCESS)
    {
        vkDestroyImage(device, vkImage, NULL);
        return fail(SKY_ERR_VULKAN, "vkAllocateMemory importing fd %d (%llu bytes) failed (%d)", image->memory_fd,
                    (unsigned long long)image->allocation_bytes, (int)r);
    }
    image->memory_fd = -1; /* the memory owns it now */
    r = vkBindImageMemory(device, vkImage, memory, 0);
    if (r != VK_SUCCESS)
    {
        vkDestroyImage(device, vkImage, NULL);
        vkFreeMemory(device, memory, NULL);
        return fail(SKY_ERR_VULKAN, "vkBindImageMemory failed (%d)", (int)r);
    }
    out_image->image = vkImage;
    out_image->memory = memory;
    out_image->format = info.format;
    out_image->width = image->width;
    out_image->height = image->height;
    return ok();
}

void sky_vulkan_destroy_image(VkDevice device, SkyImportedImage* image)
{
    if (!device || !image)
        return;
    if (image->image)
        vkDestroyImage(device, image->image, NULL);
    if (image->memory)
        vkFreeMemory(device, image->memory, NULL);
    memset(image, 0, sizeof *image);
}

SkyResult sky_vulkan_import_semaphore(VkDevice device, int* fd, VkSemaphore* out_semaphore)
{
    if (!device || !fd || *fd < 0 || !out_semaphore)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_import_semaphore: null argument or no fd");
    *out_semaphore = VK_NULL_HANDLE;
    PFN_vkImportSemaphoreFdKHR importFd =
        (PFN_vkImportSemaphoreFdKHR)vkGetDeviceProcAddr(device, "vkImportSemaphoreFdKHR");
    if (!importFd)
        return fail(SKY_ERR_VULKAN, "the device was created without " VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
    VkSemaphoreTypeCreateInfo type = {VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo info = {VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    info.pNext = &type;
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VkResult r = vkCreateSemaphore(device, &info, NULL, &semaphore);
    if (r != VK_SUCCESS)
        return fail(SKY_ERR_VULKAN, "vkCreateSemaphore (timeline) failed (%d)", (int)r);
    VkImportSemaphoreFdInfoKHR import = {VK_STRUCTURE_TYPE_IMPORT_SEMAPHORE_FD_INFO_KHR};
    import.semaphore = semaphore;
    import.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
    import.fd = *fd;
    r = importFd(device, &import);
    if (r != VK_SUCCESS)
    {
        vkDestroySemaphore(device, semaphore, NULL);
        return fail(SKY_ERR_VULKAN, "vkImportSemaphoreFdKHR failed (%d)", (int)r);
    }
    *fd = -1;
    *out_semaphore = semaphore;
    return ok();
}

static void close_fd(int* fd)
{
    if (*fd >= 0)
        close(*fd);
    *fd = -1;
}

SkyResult sky_vulkan_import_frames(VkPhysicalDevice physical_device, VkDevice device, SkyExportedFrames* frames,
                                   SkyImportedFrames* out_frames)
{
    if (!physical_device || !device || !frames || !out_frames || frames->slot_count == 0 ||
        frames->slot_count > SKY_MAX_EXPORTED_SLOTS)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_import_frames: null argument or bad slot count");
    memset(out_frames, 0, sizeof *out_frames);
    out_frames->slot_count = frames->slot_count;
    SkyResult result = SKY_OK;
    for (uint32_t i = 0; i < frames->slot_count && result == SKY_OK; ++i)
    {
        result = sky_vulkan_import_image(physical_device, device, &frames->frame[i], &out_frames->frame[i]);
        if (result == SKY_OK && frames->shadow[i].memory_fd >= 0)
            result = sky_vulkan_import_image(physical_device, device, &frames->shadow[i], &out_frames->shadow[i]);
    }
    if (result == SKY_OK && frames->timeline_semaphore_fd >= 0)
        result = sky_vulkan_import_semaphore(device, &frames->timeline_semaphore_fd, &out_frames->timeline_semaphore);
    if (result != SKY_OK)
    {
        char saved[sizeof g_error];
        memcpy(saved, g_error, sizeof saved);
        sky_vulkan_destroy_frames(device, out_frames);
        for (uint32_t i = 0; i < frames->slot_count; ++i)
        {
            close_fd(&frames->frame[i].memory_fd);
            close_fd(&frames->shadow[i].memory_fd);
        }
        close_fd(&frames->timeline_semaphore_fd);
        memcpy(g_error, saved, sizeof saved);
        return result;
    }
    return ok();
}

void sky_vulkan_destroy_frames(VkDevice device, SkyImportedFrames* frames)
{
    if (!device || !frames)
        return;
    for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS; ++i)
    {
        sky_vulkan_destroy_image(device, &frames->frame[i]);
        sky_vulkan_destroy_image(device, &frames->shadow[i]);
    }
    if (frames->timeline_semaphore)
        vkDestroySemaphore(device, frames->timeline_semaphore, NULL);
    memset(frames, 0, sizeof *frames);
}

SkyResult sky_vulkan_import_layers(VkPhysicalDevice physical_device, VkDevice device, SkyExportedFrames* frames,
                                   SkyImportedLayers* out_layers)
{
    if (!physical_device || !device || !frames || !out_layers || frames->slot_count > SKY_MAX_EXPORTED_SLOTS)
        return fail(SKY_ERR_ARGUMENT, "sky_vulkan_import_layers: null argument or bad slot count");
    memset(out_layers, 0, sizeof *out_layers);
    SkyResult result = SKY_OK;
    for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT && result == SKY_OK; ++k)
    {
        if (!(frames->layers & (1u << k)))
            continue;
        for (uint32_t i = 0; i < frames->slot_count && result == SKY_OK; ++i)
            if (frames->layer[k][i].memory_fd >= 0)
                result = sky_vulkan_import_image(physical_device, device, &frames->layer[k][i],
                                                 &out_layers->image[k][i]);
        if (result == SKY_OK)
            out_layers->layers |= 1u << k;
    }
    if (result != SKY_OK)
    {
        char saved[sizeof g_error];
        memcpy(saved, g_error, sizeof saved);
        sky_vulkan_destroy_layers(device, out_layers);
        for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
            for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS; ++i)
                close_fd(&frames->layer[k][i].memory_fd);
        memcpy(g_error, saved, sizeof saved);
        return result;
    }
    return ok();
}

void sky_vulkan_destroy_layers(VkDevice device, SkyImportedLayers* layers)
{
    if (!device || !layers)
        return;
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS; ++i)
            sky_vulkan_destroy_image(device, &layers->image[k][i]);
    memset(layers, 0, sizeof *layers);
}

void sky_vulkan_cmd_acquire(VkCommandBuffer cmd, const SkyImportedImage* image, uint32_t queue_family)
{
    if (!cmd || !image || !image->image)
        return;
    VkImageMemoryBarrier barrier = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
    barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    barrier.dstQueueFamilyIndex = queue_family;
    barrier.image = image->image;
    barrier.subresourceRange.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    barrier.subresourceRange.levelCount = 1;
    barrier.subresourceRange.layerCount = 1;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, NULL, 0,
                         NULL, 1, &barrier);
}
