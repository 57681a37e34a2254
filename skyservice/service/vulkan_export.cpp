// SPDX-License-Identifier: MIT
#include "skyservice/service/vulkan_export.h"

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

bool VulkanExport::exportFrame(Renderer& r, uint32_t slot, uint64_t frameId, const RenderResult& result,
                               std::string& error)
{
    SkyStatus status = sky::exportFrame(r, impl_->e, slot, frameId, result);
    if (!status.ok())
        error = status.message;
    return status.ok();
}

bool VulkanExport::describe(Renderer& r, nlohmann::json& body, std::vector<int>& fds, std::string& error)
{
    return describeFrameExport(r, impl_->e, body, fds, error);
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
bool VulkanExport::exportFrame(Renderer&, uint32_t, uint64_t, const RenderResult&, std::string& error)
{
    error = "no zero-copy export";
    return false;
}
bool VulkanExport::describe(Renderer&, nlohmann::json&, std::vector<int>&, std::string& error)
{
    error = "no zero-copy export";
    return false;
}
void VulkanExport::destroy(Renderer&) {}
#endif

}  // namespace sky
