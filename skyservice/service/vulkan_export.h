// SPDX-License-Identifier: MIT
// The daemon's handle on the zero-copy transport (skyservice/render/frame_export.h): created lazily by
// the render thread on the first `subscribe` with transport "vulkan", then written each frame into the
// same slot index as the shared-memory ring. Without frame_export.h in the build every call fails with
// a message, and the service answers such subscriptions with error "failed".
#pragma once

#include "skyservice/render/renderer.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sky
{

class VulkanExport
{
public:
    VulkanExport();
    ~VulkanExport();
    VulkanExport(const VulkanExport&) = delete;
    VulkanExport& operator=(const VulkanExport&) = delete;

    bool active() const;
    /// One exported frame image (and shadow image when shadowSize > 0) per slot.
    bool create(Renderer& r, uint32_t slots, uint32_t maxWidth, uint32_t maxHeight, uint32_t shadowSize,
                std::string& error);
    /// Copies the frame just rendered into exported image `slot`.
    bool exportFrame(Renderer& r, uint32_t slot, uint64_t frameId, const RenderResult& result, std::string& error);
    /// The `subscribed` reply's images/semaphore/uuid members, and new fds the caller owns.
    bool describe(Renderer& r, nlohmann::json& body, std::vector<int>& fds, std::string& error);
    void destroy(Renderer& r);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace sky
