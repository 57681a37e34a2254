// SPDX-License-Identifier: MIT
// The daemon's handle on the zero-copy transport (skyservice/render/frame_export.h): created lazily by
// the render thread on the first `subscribe` with transport "vulkan", then written each frame into the
// same slot index as the shared-memory ring. Compositing layers (a set of 1u << SKY_LAYER_*, shm_layout.h;
// the display bit is the frame image, always there) get their exported images when first asked for.
// Without frame_export.h in the build every call fails with a message, and the service answers such
// subscriptions with error "failed".
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
    /// Copies the frame just rendered into exported image `slot`, with the compositing layers of `layers`
    /// that have exported images (the renderer drew them this frame).
    bool exportFrame(Renderer& r, uint32_t slot, uint64_t frameId, const RenderResult& result, uint32_t layers,
                     std::string& error);
    /// The `subscribed` reply's images/semaphore/uuid members for a subscriber of `layers`, and new fds the
    /// caller owns; makes the layers' exported images first when they are new (allocation: off the frame path).
    bool describe(Renderer& r, uint32_t layers, nlohmann::json& body, std::vector<int>& fds, std::string& error);
    /// The compositing layers that have exported images.
    uint32_t layersMade() const;
    void destroy(Renderer& r);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace sky
