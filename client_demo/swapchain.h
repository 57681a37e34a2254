// SPDX-License-Identifier: MIT
// The window's swapchain (docs/style.md §15; written for this demo after niagara's swapchain.cpp shape): created
// for the surface's current size, re-created when that changes, and a SwapchainStatus that tells the
// frame loop whether it can draw.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace demo
{

struct VulkanDevice;

/// What updateSwapchain found.
enum class SwapchainStatus
{
    Ready,     ///< unchanged: draw
    Resized,   ///< re-created for a new size: draw (image count and extent may have changed)
    NotReady,  ///< the window has no area (minimised): skip this frame
};

/// A swapchain and its images. Plain struct: createSwapchain/destroySwapchain own it.
struct Swapchain
{
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    std::vector<VkImage> images;
    VkFormat format = VK_FORMAT_UNDEFINED;  ///< an 8-bit UNORM (preferred: the frames are sRGB-encoded already) or SRGB
    uint32_t width = 0;   ///< pixels
    uint32_t height = 0;  ///< pixels
    bool canReadBack = false;  ///< images allow TRANSFER_SRC (for --screenshot)
};

/**
 * Creates the swapchain (FIFO, images usable as blit/copy destinations and, where the surface allows,
 * sources).
 *
 * @param[out] swapchain the new swapchain.
 * @param[in] vk the device (its queue presents to the surface).
 * @param[in] surface the window's surface.
 * @param[in] width, height the window's framebuffer size (pixels), used when the surface leaves it open.
 * @param[in] old the swapchain this replaces (VK_NULL_HANDLE first time).
 * @return false when the surface cannot be drawn into by copies (no TRANSFER_DST usage or no 8-bit format).
 **********************************************************************/
bool createSwapchain(Swapchain& swapchain, const VulkanDevice& vk, VkSurfaceKHR surface, uint32_t width,
                     uint32_t height, VkSwapchainKHR old);

void destroySwapchain(const VulkanDevice& vk, Swapchain& swapchain);

/**
 * Re-creates the swapchain when the framebuffer size changed, or when `force` (the presentation engine said
 * OUT_OF_DATE or SUBOPTIMAL); waits for the device first.
 *
 * @param[in] width, height the window's framebuffer size now (pixels).
 **********************************************************************/
SwapchainStatus updateSwapchain(Swapchain& swapchain, const VulkanDevice& vk, VkSurfaceKHR surface, uint32_t width,
                                uint32_t height, bool force);

}  // namespace demo
