// SPDX-License-Identifier: MIT
// What frame_export.cpp (the ring, the copy) and frame_export_layers.cpp (the compositing layers) share:
// making, freeing and describing one exportable image, and one copy of the export's submission.
#pragma once

#include "skyservice/render/frame_export.h"

namespace sky::exportdetail
{

constexpr VkExternalMemoryHandleTypeFlagBits kMemoryHandle = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;

/// Whether images of this format (OPTIMAL tiling, kFrameExportUsage) can be exported as opaque fds.
SkyStatus checkExportable(const Context& ctx, VkFormat format);
/// A dedicated exportable allocation with its image, registered in r.memory under `name`.
SkyStatus createExportedImage(Renderer& r, ExportedImage& out, VkFormat format, uint32_t width, uint32_t height,
                              const std::string& name);
void destroyExportedImage(Renderer& r, ExportedImage& image);
/// {allocation_bytes, memory_type_bits, vk_format, width, height, linear_tiling, row_pitch}.
nlohmann::json imageJson(const ExportedImage& image);
/// Exports the image's memory as a new opaque fd appended to `fds`.
VkResult exportMemoryFd(const Context& ctx, const ExportedImage& image, std::vector<int>& fds);

/// One image copied by exportFrame: from the renderer's `source` (GENERAL) into `target`'s top-left corner.
struct CopyJob
{
    VkImage source = VK_NULL_HANDLE;
    ExportedImage* target = nullptr;
    uint32_t width = 0, height = 0;
    bool blit = false;  ///< format conversion (the shadow map's rgba16f red channel into R32_SFLOAT)
};
/// Display, shadow map and the three layers: the most one exportFrame copies.
constexpr uint32_t kMaxCopyJobs = 2 + kExportLayerCount;

/**
 * The layer copies of one exportFrame: appends a CopyJob per layer in `layers` that has exported images.
 *
 * @return a failure naming the layer when the renderer has no image of the frame's size for it (not drawn).
 **********************************************************************/
SkyStatus layerCopies(Renderer& r, FrameExport& e, uint32_t slot, uint32_t layers, const RenderResult& frame,
                      CopyJob* jobs, uint32_t& count);

/// Adds "layers":{name: imageJson} to each slot's entry of `images` and their fds to `fds` (ExportLayer
/// order, slots 0..n-1 within a layer); a failure names the layer that has no images or the call that failed.
bool describeLayers(const Context& ctx, const FrameExport& e, uint32_t layers, nlohmann::json& images,
                    std::vector<int>& fds, std::string& error);

/// Frees the layers' images (destroyFrameExport).
void destroyLayers(Renderer& r, FrameExport& e);

}  // namespace sky::exportdetail
