// SPDX-License-Identifier: MIT
// Buffers and images: plain structs plus create/destroy functions (docs/style.md §6). A handful of large
// allocations, so plain vkAllocateMemory with one memory-type chooser; every allocation is tracked by
// name and size in a MemoryTracker so that totals can be reported and leaks detected at shutdown.
#pragma once

#include "skyservice/vk/context.h"

#include <initializer_list>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace sky
{

/// Device allocations by name (bytes), for status replies and the zero-at-shutdown check.
struct MemoryTracker
{
    std::mutex mutex;
    std::map<std::string, VkDeviceSize> liveBytes;
    VkDeviceSize totalBytes = 0;
    VkDeviceSize peakBytes = 0;
    VkDeviceSize hostReadbackBytes = 0;  ///< MemoryUse::HostReadback buffers (system RAM), not in totalBytes
    VkDeviceSize hostStagingBytes = 0;   ///< MemoryUse::HostStaging buffers (system RAM), not in totalBytes
};

struct Buffer
{
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;  ///< non-null for host-visible buffers (persistently mapped)
    bool hostCoherent = true;  ///< false: the CPU must invalidate before it reads (invalidateForHost)
    bool hostReadback = false; ///< made with MemoryUse::HostReadback (counted in hostReadbackBytes)
    bool hostStaging = false;  ///< made with MemoryUse::HostStaging (counted in hostStagingBytes)
    VkDeviceSize size = 0;             ///< bytes asked for: the range a descriptor of the whole buffer covers
    VkDeviceSize allocationBytes = 0;  ///< bytes of device memory behind it (size rounded up by the driver)
    std::string name;
};

struct Image
{
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    /// A second view in ImageDesc::sampledFormat for sampling (null without one): the texture unit
    /// decodes and filters a format the shaders write as plain bits through `view`.
    VkImageView sampledView = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
    VkExtent3D extent = {0, 0, 0};
    uint32_t layers = 1;
    VkDeviceSize bytes = 0;
    std::string name;
};

enum class MemoryUse
{
    DeviceLocal,   ///< GPU only
    HostVisible,   ///< mapped, coherent: uniforms, staging and one-shot readback
    /// Mapped and cached for the CPU (HOST_CACHED where the device has it, else coherent): the frame's
    /// persistent readback buffers. On NVIDIA host-visible memory without HOST_CACHED is read uncached, at
    /// tens of MB/s. Counted apart from device memory (MemoryTracker::hostReadbackBytes): it is system RAM.
    HostReadback,
    /// Mapped, coherent: the persistent source of an upload (the weather window's staging). On a discrete
    /// GPU host-visible memory without DEVICE_LOCAL is system RAM; counted apart from device memory
    /// (MemoryTracker::hostStagingBytes).
    HostStaging,
};

/// Creates a buffer. On failure returns the error and leaves `out` empty.
SkyStatus createBuffer(const Context& ctx, MemoryTracker& tracker, Buffer& out, VkDeviceSize size,
                       VkBufferUsageFlags usage, MemoryUse use, const char* name);
void destroyBuffer(const Context& ctx, MemoryTracker& tracker, Buffer& buffer);
/// Makes the GPU's writes to a mapped buffer visible to the CPU (a no-op for coherent memory). Call after the
/// fence of the work that wrote it.
void invalidateForHost(const Context& ctx, const Buffer& buffer);

struct ImageDesc
{
    VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;  ///< 2D, 2D_ARRAY or 3D
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
    uint32_t width = 1, height = 1, depth = 1;  ///< depth only for 3D
    uint32_t layers = 1;                         ///< only for 2D_ARRAY
    VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    /// A format of the same size class as `format` to sample the image as (Image::sampledView; the image
    /// is then made with VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT), or UNDEFINED for none.
    VkFormat sampledFormat = VK_FORMAT_UNDEFINED;
};

/// Creates an image and its view (layout UNDEFINED). On failure returns the error and leaves `out` empty.
SkyStatus createImage(const Context& ctx, MemoryTracker& tracker, Image& out, const ImageDesc& desc, const char* name);
void destroyImage(const Context& ctx, MemoryTracker& tracker, Image& image);

/// Bytes per texel of the formats we use.
uint32_t formatBytes(VkFormat format);

/// Records a full-image layout transition (all mips, all layers) with a conservative compute barrier.
void transitionImage(VkCommandBuffer cmd, const Image& image, VkImageLayout from, VkImageLayout to);
/// A compute->compute memory barrier covering every image and buffer (our passes are few and large).
void computeBarrier(VkCommandBuffer cmd);

/// A command pool (`flags`) on the queue's family and one primary command buffer from it.
SkyStatus createCommandBuffer(const Context& ctx, VkCommandPoolCreateFlags flags, VkCommandPool& pool,
                              VkCommandBuffer& cmd);

/// A one-shot command buffer submitted and waited for: start-up uploads and readbacks.
struct OneShot
{
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
};
SkyStatus beginOneShot(const Context& ctx, OneShot& shot);
SkyStatus endOneShot(const Context& ctx, OneShot& shot);  ///< submits, waits, frees

/// Copies host data into an image (whole image, every layer) through a staging buffer, and leaves the
/// image in `finalLayout`.
SkyStatus uploadImage(const Context& ctx, MemoryTracker& tracker, Image& image, const void* data, size_t bytes,
                      VkImageLayout finalLayout);

/// One image of uploadImages: its whole contents (every layer) from `data`.
struct ImageUpload
{
    Image* image = nullptr;
    const void* data = nullptr;
    size_t bytes = 0;
    VkImageLayout finalLayout = VK_IMAGE_LAYOUT_GENERAL;
};
/// Uploads several images through one staging buffer and one submit (one wait on the frame path, not one
/// per image).
SkyStatus uploadImages(const Context& ctx, MemoryTracker& tracker, std::initializer_list<ImageUpload> uploads);
/// Copies a whole image (layer 0) back to the host. The image must be in GENERAL layout.
SkyStatus readbackImage(const Context& ctx, MemoryTracker& tracker, const Image& image, std::vector<uint8_t>& out);

}  // namespace sky
