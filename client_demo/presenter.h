// SPDX-License-Identifier: MIT
// Puts a composited CPU image on the screen: upload into a staging image, blit (scaled, linear filter) into
// the acquired swapchain image, present; optionally copy that swapchain image back for --screenshot.
#pragma once

#include "client_demo/swapchain.h"
#include "client_demo/vulkan_device.h"

#include "skyservice/output/image_files.h"

namespace demo
{

/// Per-window presentation state (one frame in flight: the demo is paced by the service, not the GPU).
struct Presenter
{
    VkSemaphore imageAcquired = VK_NULL_HANDLE;
    VkSemaphore renderDone = VK_NULL_HANDLE;
    VkFence frameDone = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    HostBuffer upload;        ///< the composited RGBA8 image
    HostBuffer readback;      ///< the presented image, for screenshots
    VkImage staging = VK_NULL_HANDLE;  ///< upload as an image, the blit's source
    VkDeviceMemory stagingMemory = VK_NULL_HANDLE;
    uint32_t stagingWidth = 0;
    uint32_t stagingHeight = 0;
    VkFormat stagingFormat = VK_FORMAT_UNDEFINED;
    bool outOfDate = false;   ///< the swapchain reported OUT_OF_DATE or SUBOPTIMAL: re-create it (force)
};

void createPresenter(const VulkanDevice& vk, Presenter& presenter);
void destroyPresenter(const VulkanDevice& vk, Presenter& presenter);

/**
 * Shows one image.
 *
 * @param[in] image the composited frame (any size: scaled to the window).
 * @param[out] screenshot when not null, receives the presented image (RGBA8, the swapchain's size).
 * @return Ready when presented (presenter.outOfDate may still ask for a new swapchain); Resized when the
 *   swapchain was out of date and nothing was shown (re-create it and call again); NotReady when there was
 *   nothing to show.
 **********************************************************************/
SwapchainStatus presentImage(const VulkanDevice& vk, Presenter& presenter, const Swapchain& swapchain,
                             const sky::ImageRgba8& image, sky::ImageRgba8* screenshot);

}  // namespace demo
