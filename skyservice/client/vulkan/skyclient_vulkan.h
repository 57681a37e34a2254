/* SPDX-License-Identifier: MIT */
/* skyclient_vulkan: imports the sky service's exported frame images (skyservice/ipc/PROTOCOL.md) into
 * the caller's own VkDevice. C API; links only Vulkan (libvulkan) and libc.
 *
 *   SkyExportedFrames frames;                       // from sky_client_subscribe_vulkan (skyclient.h)
 *   VkPhysicalDevice pd;
 *   sky_vulkan_find_physical_device(instance, &frames, &pd);   // the GPU the service renders on
 *   ... create the VkDevice on pd with sky_vulkan_required_device_extensions() enabled (and the
 *       timelineSemaphore feature when frames.timeline_semaphore_fd >= 0) ...
 *   SkyImportedFrames imported;
 *   sky_vulkan_import_frames(pd, device, &frames, &imported);  // takes ownership of the fds
 *   per frame (slot and frame id from sky_client_acquire_frame):
 *     if (imported.timeline_semaphore) wait for value >= frame_id (vkWaitSemaphores or a submit wait);
 *     record: sky_vulkan_cmd_acquire(cmd, &imported.frame[slot], queue_family) then read the image in
 *     VK_IMAGE_LAYOUT_GENERAL (copy, or sample through a view of your own);
 *     then sky_client_release_frame: SKY_ERR_TORN means the service rewrote the slot meanwhile.
 *   sky_vulkan_destroy_frames(device, &imported);
 * With compositing layers (sky_client_subscribe_vulkan_layers): sky_vulkan_import_layers(pd, device, &frames,
 * &layers) as well, read layers.image[SKY_LAYER_CLOUDS][slot] etc. like the frame, sky_vulkan_destroy_layers.
 *
 * The images have the exporter's exact creation parameters (required to import a dedicated opaque-fd
 * allocation): 2D, one mip, one layer, VK_IMAGE_TILING_OPTIMAL (or LINEAR when linear_tiling), usage
 * SKY_VULKAN_IMAGE_USAGE, exclusive sharing. A frame smaller than the image sits in its top-left corner
 * (the real size is in SkyFrame.width/height and shadow.size_texels). Frame images are
 * VK_FORMAT_R8G8B8A8_UNORM holding sRGB-encoded bytes (view them as R8G8B8A8_SRGB to sample linear
 * values: create the view with a format list of your own, or copy). Shadow images are R32_SFLOAT key-light
 * transmittance, north row first. Layer images: SKY and CLOUDS VK_FORMAT_R16G16B16A16_SFLOAT (linear,
 * pre-exposed; clouds premultiplied with alpha), DEPTH VK_FORMAT_R32G32_SFLOAT (metres: the cloud's front,
 * then its weighted distance); skyservice/ipc/shm_layout.h SKY_LAYER_* says what each holds.
 *
 * Synchronisation: without a timeline semaphore (timeline_semaphore_fd == -1, e.g. lavapipe) the
 * service finished writing a slot before it published it in the ring; with one, it is signalled with the
 * frame id when the slot holds that frame.
 *
 * Every function returns SKY_OK or SKY_ERR_ARGUMENT / SKY_ERR_VULKAN; sky_vulkan_last_error() says why
 * in one line (per thread).
 */
#ifndef SKY_CLIENT_VULKAN_H
#define SKY_CLIENT_VULKAN_H

#include <vulkan/vulkan.h>

#include "skyservice/client/skyclient.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Usage of every exported image, on both sides (TRANSFER_SRC | TRANSFER_DST | SAMPLED). */
#define SKY_VULKAN_IMAGE_USAGE \
    (VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT)

typedef struct SkyImportedImage
{
    VkImage image;          /* VK_NULL_HANDLE when the slot has no such image */
    VkDeviceMemory memory;  /* owns the imported fd */
    VkFormat format;
    uint32_t width, height;
} SkyImportedImage;

typedef struct SkyImportedFrames
{
    uint32_t slot_count;
    SkyImportedImage frame[SKY_MAX_EXPORTED_SLOTS];
    SkyImportedImage shadow[SKY_MAX_EXPORTED_SLOTS];
    VkSemaphore timeline_semaphore; /* VK_NULL_HANDLE when the service exports none */
} SkyImportedFrames;

/* The compositing layers, imported: image[SKY_LAYER_*][slot]. VK_NULL_HANDLE where not exported, and
 * always in image[SKY_LAYER_DISPLAY] (the display layer is SkyImportedFrames.frame). */
typedef struct SkyImportedLayers
{
    uint32_t layers; /* bit k = SKY_LAYER_k: the layers imported */
    SkyImportedImage image[SKY_LAYER_COUNT][SKY_MAX_EXPORTED_SLOTS];
} SkyImportedLayers;

/* One line: why the last call of this thread failed ("" after success). */
const char* sky_vulkan_last_error(void);

/* The device extensions the importing VkDevice must enable: *count is set to 1 (external memory fd), or
 * 2 when with_semaphore (external semaphore fd too). */
const char* const* sky_vulkan_required_device_extensions(int with_semaphore, uint32_t* count);

/* The physical device of `instance` whose deviceUUID equals frames->device_uuid (and whose driverUUID
 * equals frames->driver_uuid: opaque fds only import into the same driver). Needs Vulkan 1.1. */
SkyResult sky_vulkan_find_physical_device(VkInstance instance, const SkyExportedFrames* frames,
                                          VkPhysicalDevice* out_physical_device);

/* Imports one exported image: creates the VkImage (VkExternalMemoryImageCreateInfo, the exporter's
 * format, extent, tiling, usage), allocates its memory from image->memory_fd (VkImportMemoryFdInfoKHR +
 * VkMemoryDedicatedAllocateInfo) and binds it. On success the fd belongs to the memory and
 * image->memory_fd is set to -1; on failure the fd is left to the caller. */
SkyResult sky_vulkan_import_image(VkPhysicalDevice physical_device, VkDevice device, SkyExportedImage* image,
                                  SkyImportedImage* out_image);
void sky_vulkan_destroy_image(VkDevice device, SkyImportedImage* image);

/* Imports the timeline semaphore (an opaque fd) into a new timeline VkSemaphore. The device must have
 * VK_KHR_external_semaphore_fd and the timelineSemaphore feature. On success *fd is set to -1. */
SkyResult sky_vulkan_import_semaphore(VkDevice device, int* fd, VkSemaphore* out_semaphore);

/* Imports every image of every slot (and the semaphore when there is one). On success all fds in
 * `frames` belong to the imported objects (set to -1); on failure whatever was imported is destroyed and
 * the remaining fds (not yet imported) are closed. */
SkyResult sky_vulkan_import_frames(VkPhysicalDevice physical_device, VkDevice device, SkyExportedFrames* frames,
                                   SkyImportedFrames* out_frames);
void sky_vulkan_destroy_frames(VkDevice device, SkyImportedFrames* frames);

/* Imports the compositing layers' images of `frames` (frames->layer, from sky_client_subscribe_vulkan_layers);
 * sky_vulkan_import_frames imports the rest. On success their fds belong to the imported objects (set to
 * -1); on failure whatever was imported is destroyed and the remaining layer fds are closed. */
SkyResult sky_vulkan_import_layers(VkPhysicalDevice physical_device, VkDevice device, SkyExportedFrames* frames,
                                   SkyImportedLayers* out_layers);
void sky_vulkan_destroy_layers(VkDevice device, SkyImportedLayers* layers);

/* Records the barrier that takes an imported image from the service (queue family
 * VK_QUEUE_FAMILY_EXTERNAL, layout GENERAL) for reading by transfer, compute and fragment stages on
 * queue_family, in layout GENERAL. Record it before every read of a newly published slot. */
void sky_vulkan_cmd_acquire(VkCommandBuffer cmd, const SkyImportedImage* image, uint32_t queue_family);

#ifdef __cplusplus
}
#endif

#endif /* SKY_CLIENT_VULKAN_H */
