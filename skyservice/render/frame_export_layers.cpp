// SPDX-License-Identifier: MIT
// The compositing layers of the zero-copy export (frame_export.h "Compositing layers"): their exported
// images, made once when first asked for; the copies exportFrame records for them; their descriptions.
#include "skyservice/render/frame_export.h"

#include "skyservice/render/frame_export_internal.h"

namespace sky
{

const char* exportLayerName(uint32_t layer)
{
    switch (layer)
    {
    case kExportSky: return "sky";
    case kExportClouds: return "clouds";
    case kExportDepth: return "depth";
    default: return "unknown";
    }
}

VkFormat exportLayerFormat(uint32_t layer)
{
    // The renderer's own formats (frame_images.cpp): vkCmdCopyImage then moves the values unchanged.
    return layer == kExportDepth ? VK_FORMAT_R32G32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
}

namespace
{

const Image& rendererLayer(const Renderer& r, uint32_t layer)
{
    return layer == kExportSky      ? r.composite.skyImage
           : layer == kExportClouds ? r.composite.cloudLayerImage
                                    : r.composite.depthLayerImage;
}

}  // namespace

SkyStatus ensureExportedLayers(Renderer& r, FrameExport& e, uint32_t layers)
{
    if (e.frames.empty())
        return SkyStatus::failure("frame export: not created", VK_ERROR_INITIALIZATION_FAILED);
    if (layers & ~kExportAllLayers)
        return SkyStatus::failure("frame export: unknown layer bits " + std::to_string(layers),
                                  VK_ERROR_INITIALIZATION_FAILED);
    for (uint32_t k = 0; k < kExportLayerCount; ++k)
    {
        if (!(layers & (1u << k)) || !e.layers[k].empty())
            continue;
        const VkFormat format = exportLayerFormat(k);
        SKY_TRY(exportdetail::checkExportable(r.ctx, format));
        std::vector<ExportedImage> images(e.slots);
        SkyStatus s = SkyStatus::success();
        for (uint32_t i = 0; i < e.slots && s.ok(); ++i)
        {
            const std::string name = std::string("export ") + exportLayerName(k) + " " + std::to_string(i);
            s = exportdetail::createExportedImage(r, images[i], format, e.maxWidth, e.maxHeight, name);
        }
        if (!s.ok())
        {
            for (ExportedImage& image : images)
                exportdetail::destroyExportedImage(r, image);
            return s;
        }
        e.layers[k] = std::move(images);
    }
    return SkyStatus::success();
}

namespace exportdetail
{

SkyStatus layerCopies(Renderer& r, FrameExport& e, uint32_t slot, uint32_t layers, const RenderResult& frame,
                      CopyJob* jobs, uint32_t& count)
{
    for (uint32_t k = 0; k < kExportLayerCount; ++k)
    {
        if (!(layers & (1u << k)) || e.layers[k].empty())
            continue;  // not asked for, or asked for before its images were made (the subscribe is on its way)
        const Image& source = rendererLayer(r, k);
        if (!source.image || source.extent.width != frame.width || source.extent.height != frame.height)
            return SkyStatus::failure(std::string("frame export: the frame has no ") + exportLayerName(k) +
                                          " layer on the GPU (not drawn: readback lacks its kRead/kDraw bit)",
                                      VK_ERROR_UNKNOWN);
        jobs[count++] = CopyJob{source.image, &e.layers[k][slot], frame.width, frame.height, false};
    }
    return SkyStatus::success();
}

bool describeLayers(const Context& ctx, const FrameExport& e, uint32_t layers, nlohmann::json& images,
                    std::vector<int>& fds, std::string& error)
{
    for (uint32_t i = 0; i < e.slots; ++i)
        images[i]["layers"] = nlohmann::json::object();
    for (uint32_t k = 0; k < kExportLayerCount; ++k)
    {
        if (!(layers & (1u << k)))
            continue;
        if (e.layers[k].size() != e.slots)
        {
            error = std::string("frame export: the ") + exportLayerName(k) + " layer has no exported images";
            return false;
        }
        for (uint32_t i = 0; i < e.slots; ++i)
        {
            images[i]["layers"][exportLayerName(k)] = imageJson(e.layers[k][i]);
            if (VkResult res = exportMemoryFd(ctx, e.layers[k][i], fds); res != VK_SUCCESS)
            {
                error = "vkGetMemoryFdKHR (" + e.layers[k][i].name + ") failed: " + vkResultName(res);
                return false;
            }
        }
    }
    return true;
}

void destroyLayers(Renderer& r, FrameExport& e)
{
    for (std::vector<ExportedImage>& images : e.layers)
    {
        for (ExportedImage& image : images)
            destroyExportedImage(r, image);
        images.clear();
    }
}

}  // namespace exportdetail
}  // namespace sky
