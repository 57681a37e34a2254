// SPDX-License-Identifier: MIT
// The zero-copy transport on the demo's side: the service's exported frame, shadow and compositing-layer
// images imported into the demo's device (skyservice/client/vulkan/skyclient_vulkan.h), and copied from
// there into host memory for the CPU compositing (compositor.h says why the demo composites on the CPU; a real image
// generator would sample the imported image directly).
#pragma once

#include "client_demo/frame_source.h"
#include "client_demo/vulkan_device.h"

#include "skyservice/client/skyclient.h"

#include <memory>
#include <string>
#include <vector>

namespace demo
{

class VulkanFrameImport
{
public:
    /**
     * @param[in] instance the demo's instance.
     * @param[in] exported what the service sent (its fds are the caller's until import succeeds).
     * @return the service's physical device among the instance's, or null when it is not one of them.
     **********************************************************************/
    static VkPhysicalDevice findServiceDevice(VkInstance instance, const SkyExportedFrames& exported);

    /// The device extensions an importing device needs.
    static std::vector<const char*> requiredExtensions();

    /**
     * Imports every slot into vk's device (created on findServiceDevice's answer). On success the fds in
     * `exported` belong to the import; on failure they are closed.
     **********************************************************************/
    static std::unique_ptr<VulkanFrameImport> create(const VulkanDevice& vk, SkyExportedFrames& exported,
                                                     std::string& error);
    ~VulkanFrameImport();
    VulkanFrameImport(const VulkanFrameImport&) = delete;
    VulkanFrameImport& operator=(const VulkanFrameImport&) = delete;

    /**
     * Copies slot `slot`'s frame (width x height) and shadow map (shadowSize^2, 0 = none) into out.rgba and
     * out.shadowTransmittance, and the compositing layers imported into out.skyRgba/cloudsRgba/depthM (the
     * others cleared), waiting for the GPU copy to finish.
     **********************************************************************/
    bool copySlot(uint32_t slot, uint64_t frameId, uint32_t width, uint32_t height, uint32_t shadowSize,
                  LatestFrame& out, std::string& error);

private:
    explicit VulkanFrameImport(const VulkanDevice& vk);

    const VulkanDevice& vk_;
    struct Imported;
    std::unique_ptr<Imported> imported_;
    HostBuffer readback_;
};

/// Closes every fd still held by `exported` (after a failed or declined import).
void closeExportedFds(SkyExportedFrames& exported);

}  // namespace demo
