// SPDX-License-Identifier: MIT
#include "client_demo/swapchain.h"

#include "client_demo/vulkan_device.h"

#include <algorithm>
#include <cstdio>

namespace demo
{
namespace
{

VkSurfaceFormatKHR pickFormat(VkPhysicalDevice pd, VkSurfaceKHR surface)
{
    uint32_t count = 0;
    DEMO_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    DEMO_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface, &count, formats.data()));
    // UNORM first: the service's bytes are sRGB-encoded already, so they go to the screen unchanged.
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_SRGB,
                          VK_FORMAT_R8G8B8A8_SRGB})
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == want)
                return f;
    return {VK_FORMAT_UNDEFINED, VK_COLOR_SPACE_SRGB_NONLINEAR_KHR};
}

}  // namespace

bool createSwapchain(Swapchain& sc, const VulkanDevice& vk, VkSurfaceKHR surface, uint32_t width, uint32_t height,
                     VkSwapchainKHR old)
{
    VkSurfaceCapabilitiesKHR caps;
    DEMO_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk.physicalDevice, surface, &caps));
    const VkSurfaceFormatKHR format = pickFormat(vk.physicalDevice, surface);
    if (format.format == VK_FORMAT_UNDEFINED || (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) == 0)
    {
        std::fprintf(stderr, "client_demo: the window surface offers no 8-bit RGBA format writable by copies\n");
        return false;
    }
    // 0xFFFFFFFF: the surface takes the swapchain's size (Wayland); else it dictates it (X11).
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX)
        extent = {std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
                  std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    VkSwapchainCreateInfoKHR info = {VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface;
    info.minImageCount = std::max(2u, caps.minImageCount);
    if (caps.maxImageCount != 0)
        info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    sc.canReadBack = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (sc.canReadBack)
        info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR) != 0
                            ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
                            : caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    for (VkCompositeAlphaFlagBitsKHR a : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                                          VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                          VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
        if ((caps.supportedCompositeAlpha & a) != 0)
        {
            info.compositeAlpha = a;
            break;
        }
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported; the frame rate is the service's anyway
    info.clipped = VK_TRUE;
    info.oldSwapchain = old;
    DEMO_VK_CHECK(vkCreateSwapchainKHR(vk.device, &info, nullptr, &sc.swapchain));
    uint32_t count = 0;
    DEMO_VK_CHECK(vkGetSwapchainImagesKHR(vk.device, sc.swapchain, &count, nullptr));
    sc.images.resize(count);
    DEMO_VK_CHECK(vkGetSwapchainImagesKHR(vk.device, sc.swapchain, &count, sc.images.data()));
    sc.format = format.format;
    sc.width = extent.width;
    sc.height = extent.height;
    return true;
}

void destroySwapchain(const VulkanDevice& vk, Swapchain& sc)
{
    if (sc.swapchain != VK_NULL_HANDLE)
        vkDestroySwapchainKHR(vk.device, sc.swapchain, nullptr);
    sc = Swapchain{};
}

SwapchainStatus updateSwapchain(Swapchain& sc, const VulkanDevice& vk, VkSurfaceKHR surface, uint32_t width,
                                uint32_t height, bool force)
{
    if (width == 0 || height == 0)
        return SwapchainStatus::NotReady;
    VkSurfaceCapabilitiesKHR caps;
    DEMO_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk.physicalDevice, surface, &caps));
    const uint32_t w = caps.currentExtent.width == UINT32_MAX ? width : caps.currentExtent.width;
    const uint32_t h = caps.currentExtent.width == UINT32_MAX ? height : caps.currentExtent.height;
    if (w == 0 || h == 0)
        return SwapchainStatus::NotReady;
    if (w == sc.width && h == sc.height && !force)
        return SwapchainStatus::Ready;
    DEMO_VK_CHECK(vkDeviceWaitIdle(vk.device));
    Swapchain fresh;
    if (!createSwapchain(fresh, vk, surface, width, height, sc.swapchain))
        return SwapchainStatus::NotReady;
    destroySwapchain(vk, sc);
    sc = fresh;
    return SwapchainStatus::Resized;
}

}  // namespace demo
