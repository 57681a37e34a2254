// SPDX-License-Identifier: MIT
// Zero-copy frame sharing through exported Vulkan memory (skyservice/ipc/PROTOCOL.md): a ring of
// images whose VkDeviceMemory is exported as opaque fds (VK_KHR_external_memory_fd), that a client
// imports into its own VkDevice on the same physical device (skyservice/client/vulkan/skyclient_vulkan.h).
//
// Usage (the service, once per device; slots = the shared-memory ring's slot count):
//   FrameExport e;  createFrameExport(r, e, slots, maxWidth, maxHeight, maxShadowSize)
//   per frame:      renderView(r, ...) -> exportFrame(r, e, slot, frameId, result, layers) -> publish slot in the ring
//   per subscriber: ensureExportedLayers(r, e, layers) -> describeFrameExport(r, e, layers, json, fds, error)
//                   -> sendmsg(json line + SCM_RIGHTS fds) -> close fds
//   destroyFrameExport(r, e)
//
// Images: slot i has a frame image (VK_FORMAT_R8G8B8A8_UNORM holding the display frame's sRGB-encoded
// bytes, exactly RenderResult::displayRgba8) of maxWidth x maxHeight and, when maxShadowSize > 0, a
// shadow image (VK_FORMAT_R32_SFLOAT, key-light transmittance, north row first) of maxShadowSize^2.
// A smaller frame or shadow map sits in the top-left corner; its real size travels in the ring's
// SkyShmSlot (view.width/height, shadow.size_texels). Every image has its own dedicated allocation
// (VkExportMemoryAllocateInfo OPAQUE_FD + VkMemoryDedicatedAllocateInfo), OPTIMAL tiling and usage
// kFrameExportUsage. Importers create their VkImage with the same format, extent, tiling and usage
// (identical parameters are required to import a dedicated opaque-fd allocation).
// Layout and ownership: after each copy the image is left in VK_IMAGE_LAYOUT_GENERAL and released to
// VK_QUEUE_FAMILY_EXTERNAL (no layout change in the release); importers acquire it GENERAL -> GENERAL
// from VK_QUEUE_FAMILY_EXTERNAL (sky_vulkan_cmd_acquire) and read it in GENERAL; the next exportFrame
// into the slot acquires it back before writing (in TRANSFER_DST_OPTIMAL).
//
// Synchronisation:
//  - Devices without VK_KHR_external_semaphore_fd (lavapipe, Mesa 22.3): exportFrame submits the copy and
//    waits for its fence before returning, so the slot is complete in memory before the caller publishes
//    it in the shared-memory ring; the ring's sequence lock then tells a client which slot to read and
//    whether the service came round to it while it was read (the same torn-read rule as the shm transport).
//    "timeline_semaphore" is false and no semaphore fd is sent.
//  - Devices with VK_KHR_external_semaphore_fd and timeline semaphores: one exportable timeline semaphore;
//    exportFrame's submission signals it with value frameId and returns without waiting (the slot's
//    command buffer is reused only after its fence). A client waits (vkWaitSemaphores or a submit wait)
//    for value >= frame_id before reading the slot of frame_id. A trailing barrier orders the copy's
//    reads before the renderer's next writes to its own images (same queue, submission order).
// In both cases a client must finish reading a slot within (slots - 1) frame intervals, as for shm.
//
// Compositing layers (ExportLayer): besides the display frame a slot can carry the sky, clouds and depth
// layers, each an exported image per slot at maxWidth x maxHeight, made when a subscriber first asks for
// the layer (ensureExportedLayers, off the frame path) and kept until destroyFrameExport. exportFrame
// copies the layers it is told to (the renderer drew them: kRead* or kDraw* in ViewRequest::readback)
// with vkCmdCopyImage in the same submission as the display frame: same format, exact values.
// Tested (tests/export) on both paths: fences (lavapipe) and timeline semaphores (a GPU driver), each with a
// second process importing through skyclient_vulkan and reading bytes identical to renderView's.
#pragma once

#include "skyservice/render/renderer.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace sky
{

/// Usage of every exported image (the importer must create its VkImage with exactly these).
constexpr VkImageUsageFlags kFrameExportUsage =
    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

/// The compositing layers an export can carry besides the display frame (skyservice/ipc/PROTOCOL.md
/// "Compositing layers"), in the order their fds are sent. A layer set has bit (1u << k) for layer k.
enum ExportLayer : uint32_t
{
    kExportSky = 0,     ///< VK_FORMAT_R16G16B16A16_SFLOAT: the sky without clouds, linear, pre-exposed
    kExportClouds = 1,  ///< VK_FORMAT_R16G16B16A16_SFLOAT: the clouds, premultiplied linear + alpha
    kExportDepth = 2,   ///< VK_FORMAT_R32G32_SFLOAT: the cloud's front, then its weighted distance (m)
    kExportLayerCount = 3,
};
constexpr uint32_t kExportAllLayers = (1u << kExportLayerCount) - 1u;

/// "sky", "clouds", "depth" (the protocol's names); the format of the layer's images.
const char* exportLayerName(uint32_t layer);
VkFormat exportLayerFormat(uint32_t layer);

/// One exportable image with its own (dedicated, exportable) allocation.
struct ExportedImage
{
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    VkDeviceSize allocationBytes = 0;  ///< allocationSize the memory was allocated (and is imported) with
    uint32_t memoryTypeBits = 0;       ///< VkMemoryRequirements::memoryTypeBits of the image
    uint32_t memoryTypeIndex = 0;
    bool general = false;              ///< written once: in GENERAL and owned by VK_QUEUE_FAMILY_EXTERNAL
    std::string name;                  ///< MemoryTracker key
};

/// The exported ring: `slots` frame images, as many shadow images (none when maxShadowSize is 0), and
/// an exportable timeline semaphore when the device can export one.
struct FrameExport
{
    uint32_t slots = 0;
    uint32_t maxWidth = 0, maxHeight = 0, maxShadowSize = 0;
    std::vector<ExportedImage> frames;   ///< one per slot, R8G8B8A8_UNORM (sRGB-encoded bytes)
    std::vector<ExportedImage> shadows;  ///< one per slot, R32_SFLOAT; empty when maxShadowSize == 0
    /// Per ExportLayer, one image per slot (exportLayerFormat, maxWidth x maxHeight); empty until asked for.
    std::array<std::vector<ExportedImage>, kExportLayerCount> layers;
    VkSemaphore timeline = VK_NULL_HANDLE;  ///< exportable timeline semaphore, or null (lavapipe)
    uint64_t lastSignalled = 0;             ///< highest value submitted for the timeline semaphore
    VkCommandPool pool = VK_NULL_HANDLE;
    std::vector<VkCommandBuffer> commands;  ///< one per slot
    std::vector<VkFence> fences;            ///< one per slot, signalled when the slot's copy is done
    std::vector<bool> fencePending;         ///< the slot's fence belongs to a submission not yet waited for
};

/**
 * Create the exported ring.
 *
 * @param[in,out] r the renderer (its context must have been created with external memory support:
 *   r.ctx.externalMemoryFd); the allocations are registered in r.memory as "export frame i" and
 *   "export shadow i".
 * @param[out] e the ring.
 * @param[in] slots number of slots, [1, 4] (SKY_MAX_EXPORTED_SLOTS); the shared-memory ring's count.
 * @param[in] maxWidth, maxHeight the largest frame (pixels), >= 1.
 * @param[in] maxShadowSize the largest shadow map (texels per side); 0 = export no shadow maps.
 * @return success, or a failure naming what is missing ("VK_KHR_external_memory_fd", an unexportable
 *   format) or what failed; on failure `e` is left empty and nothing stays allocated.
 **********************************************************************/
SkyStatus createFrameExport(Renderer& r, FrameExport& e, uint32_t slots, uint32_t maxWidth, uint32_t maxHeight,
                            uint32_t maxShadowSize);

/// Waits for pending copies and frees everything createFrameExport made. An empty `e` is allowed.
void destroyFrameExport(Renderer& r, FrameExport& e);

/**
 * Make the exported images of compositing layers (every slot), for the layers not made yet.
 *
 * @param[in,out] r the renderer; the allocations are registered in r.memory as "export sky i" etc.
 * @param[in,out] e a created ring.
 * @param[in] layers the layer set (bit k = ExportLayer k).
 * @return success, or a failure naming the format the device cannot export; layers made before stay.
 **********************************************************************/
SkyStatus ensureExportedLayers(Renderer& r, FrameExport& e, uint32_t layers);

/**
 * Copy the last rendered frame into a slot.
 *
 * @param[in,out] r the renderer, right after renderView produced `frame` (r.composite.displayImage and, when
 *   frame.shadowMapSize > 0, r.shadowPass.image still hold it).
 * @param[in,out] e the ring.
 * @param[in] slot which slot, < e.slots.
 * @param[in] frameId the frame's id (> every earlier one): the timeline value signalled, when exportable.
 * @param[in] frame the result of that renderView (width, height, shadowMapSize).
 * @param[in] layers the compositing layers to copy as well (bit k = ExportLayer k); those without
 *   exported images yet (ensureExportedLayers) are skipped. The renderer must have drawn each of them
 *   this frame (ViewRequest::readback with kReadSky/kDrawSky etc.).
 * @return success when the copy is done (no exportable semaphore) or submitted with the signal (with
 *   one); a failure when the frame or shadow map is larger than the ring, a layer asked for was not
 *   drawn, or the GPU failed.
 **********************************************************************/
SkyStatus exportFrame(Renderer& r, FrameExport& e, uint32_t slot, uint64_t frameId, const RenderResult& frame,
                      uint32_t layers = 0);

/**
 * What one subscriber gets: the vulkan `subscribed` reply's extra fields (PROTOCOL.md) and new fds.
 *
 * @param[in] r the renderer.
 * @param[in] e the ring.
 * @param[in] layers the compositing layers this subscriber gets (bit k = ExportLayer k); each must have
 *   its images (ensureExportedLayers).
 * @param[out] description {"images":[{allocation_bytes, memory_type_bits, vk_format, width, height,
 *   linear_tiling, row_pitch, shadow:{the same fields, or null without shadow maps},
 *   layers:{"sky"|"clouds"|"depth":{the same fields}, ... the layers asked for}}, ... one per slot],
 *   "timeline_semaphore":bool, "device_uuid":"32 hex digits", "driver_uuid":"32 hex digits"}; the caller
 *   adds type/transport/shm_name/slots/total_bytes.
 * @param[out] fds freshly exported fds (vkGetMemoryFdKHR), in the SCM_RIGHTS order of PROTOCOL.md: the
 *   frame images of slots 0..n-1, the shadow images of slots 0..n-1 (when any), for each layer asked for
 *   in ExportLayer order its images of slots 0..n-1, then the semaphore (when "timeline_semaphore"). The
 *   caller sends and then closes them.
 * @param[out] error why it failed (fds already made are closed and `fds` emptied).
 * @return true on success.
 **********************************************************************/
bool describeFrameExport(Renderer& r, const FrameExport& e, uint32_t layers, nlohmann::json& description,
                         std::vector<int>& fds, std::string& error);
/// The same without compositing layers.
inline bool describeFrameExport(Renderer& r, const FrameExport& e, nlohmann::json& description, std::vector<int>& fds,
                                std::string& error)
{
    return describeFrameExport(r, e, 0u, description, fds, error);
}

}  // namespace sky
