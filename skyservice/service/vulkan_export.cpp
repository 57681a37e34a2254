// SPDX-License-Identifier: MIT
#include "skyservice/service/vulkan_export.h"

#include "skyservice/ipc/shm_layout.h"

#if __has_include("skyservice/render/frame_export.h")
#include "skyservice/render/frame_export.h"
#define SKY_SERVICE_HAS_FRAME_EXPORT 1
#endif

namespace sky
{

#ifdef SKY_SERVICE_HAS_FRAME_EXPORT
struct VulkanExport::Impl
{
    FrameExport e;
    bool created = false;
};
#else
struct VulkanExport::Impl
{
    bool created = false;
};
#endif

VulkanExport::VulkanExport() : impl_(std::make_unique<Impl>()) {}
VulkanExport::~VulkanExport() = default;

bool VulkanExport::active() const { return impl_->created; }

#ifdef SKY_SERVICE_HAS_FRAME_EXPORT
bool VulkanExport::create(Renderer& r, uint32_t slots, uint32_t maxWidth, uint32_t maxHeight, uint32_t shadowSize,
                          std::string& error)
{
    SkyStatus status = createFrameExport(r, impl_->e, slots, maxWidth, maxHeight, shadowSize);
    if (!status.ok())
    {
        error = status.message;
        return false;
    }
    impl_->created = true;
    return true;
}

namespace
{

// SKY_LAYER_* (the protocol's order: display, sky, clouds, depth) to ExportLayer bits and back.
constexpr std::pair<uint32_t, uint32_t> kLayerMap[] = {
    {SKY_LAYER_SKY, kExportSky}, {SKY_LAYER_CLOUDS, kExportClouds}, {SKY_LAYER_DEPTH, kExportDepth}};

uint32_t exportLayersOf(uint32_t skyLayers)
{
    uint32_t bits = 0;
    for (const auto& [sky, exported] : kLayerMap)
        if (skyLayers & (1u << sky))
            bits |= 1u << exported;
    return bits;
}

}  // namespace

bool VulkanExport::exportFrame(Renderer& r, uint32_t slot, uint64_t frameId, const RenderResult& result,
                               uint32_t layers, std::string& error)
{
    SkyStatus status = sky::exportFrame(r, impl_->e, slot, frameId, result, exportLayersOf(layers));
    if (!status.ok())
        error = status.message;
    return status.ok();
}

bool VulkanExport::describe(Renderer& r, uint32_t layers, nlohmann::json& body, std::vector<int>& fds,
                            std::string& error)
{
    const uint32_t exported = exportLayersOf(layers);
    SkyStatus status = ensureExportedLayers(r, impl_->e, exported);
    if (!status.ok())
    {
        error = status.message;
        return false;
    }
    return describeFrameExport(r, impl_->e, exported, body, fds, error);
}

uint32_t VulkanExport::layersMade() const
{
    uint32_t bits = 0;
    for (const auto& [sky, exported] : kLayerMap)
        if (!impl_->e.layers[exported].empty())
            bits |= 1u << sky;
    return bits;
}

void VulkanExport::destroy(Renderer& r)
{
    if (impl_->created)
        destroyFrameExport(r, impl_->e);
    impl_->created = false;
}
#else
bool VulkanExport::create(Renderer&, uint32_t, uint32_t, uint32_t, uint32_t, std::string& error)
{
    error = "this build has no zero-copy export (skyservice/render/frame_export.h)";
    return false;
}
bool VulkanExport::exportFrame(Renderer&, uint32_t, uint64_t, const RenderResult&, uint32_t, std::string& error)
{
    error = "no zero-copy export";
    return false;
}
bool VulkanExport::describe(Renderer&, uint32_t, nlohmann::json&, std::vector<int>&, std::string& error)
{
    error = "no zero-copy export";
    return false;
}
uint32_t VulkanExport::layersMade() const { return 0; }
void VulkanExport::destroy(Renderer&) {}
#endif

}  // namespace sky
