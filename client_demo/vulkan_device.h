// SPDX-License-Identifier: MIT
// The demo's own Vulkan instance and device (one queue that can present and copy), plus the two helpers
// everything else needs: a host-visible buffer and a one-time command buffer. The demo does not use
// skyservice/vk: a client of the service brings its own device, as an image generator would.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

/// A Vulkan call that can fail only through programmer error: print and abort (docs/style.md §5), in every build.
#define DEMO_VK_CHECK(call)                                                                                            \
    do                                                                                                                 \
    {                                                                                                                  \
        VkResult demoVkResult = (call);                                                                                \
        if (demoVkResult != VK_SUCCESS)                                                                                \
        {                                                                                                              \
            std::fprintf(stderr, "%s:%d: %s failed: VkResult %d\n", __FILE__, __LINE__, #call, int(demoVkResult));    \
            std::abort();                                                                                              \
        }                                                                                                              \
    } while (0)

namespace demo
{

/// Instance, device, queue and a command pool. Plain struct: createVulkan*/destroyVulkanDevice own it.
struct VulkanDevice
{
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    std::string deviceName;
};

/**
 * Creates the instance (Vulkan 1.2).
 *
 * @param[in,out] vk gets its instance.
 * @param[in] extensions instance extensions (e.g. the surface extensions GLFW asks for; empty headless).
 * @param[out] error why it failed.
 * @return false when no Vulkan instance can be made (no loader, no driver, missing extension).
 **********************************************************************/
bool createVulkanInstance(VulkanDevice& vk, const std::vector<const char*>& extensions, std::string& error);

/// What the device must do.
struct DeviceRequest
{
    VkPhysicalDevice preferred = VK_NULL_HANDLE;  ///< use this one (the service's GPU); null = pick one
    VkSurfaceKHR surface = VK_NULL_HANDLE;        ///< the queue must present to it (and VK_KHR_swapchain is on)
    std::vector<const char*> extensions;          ///< further device extensions (external memory import)
};

/**
 * Creates the device on `request.preferred`, or else on the first physical device (a discrete GPU
 * first) with a graphics or compute queue that can present to the surface.
 *
 * @return false (error says why) when no device fits; vk's device fields stay null then.
 **********************************************************************/
bool createVulkanDevice(VulkanDevice& vk, const DeviceRequest& request, std::string& error);

/// True when some queue family of `physicalDevice` can present to `surface` and copy.
bool canPresent(VkPhysicalDevice physicalDevice, VkSurfaceKHR surface);

/// Destroys the device and the instance (waits for the device to be idle first).
void destroyVulkanDevice(VulkanDevice& vk);
/// Destroys the device only (the instance stays, for another try on another physical device).
void destroyVulkanDeviceOnly(VulkanDevice& vk);

/// A buffer in host-visible, coherent memory, mapped for its whole life.
struct HostBuffer
{
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
    VkDeviceSize bytes = 0;
};

/// Creates a TRANSFER_SRC | TRANSFER_DST buffer of `bytes` bytes (> 0); aborts on failure (demo sizes).
void createHostBuffer(const VulkanDevice& vk, VkDeviceSize bytes, HostBuffer& buffer);
void destroyHostBuffer(const VulkanDevice& vk, HostBuffer& buffer);

/// A memory type of `typeBits` with all of `properties` (UINT32_MAX when none).
uint32_t findMemoryType(VkPhysicalDevice physicalDevice, uint32_t typeBits, VkMemoryPropertyFlags properties);

/// Allocates a primary command buffer from vk's pool and begins it (one-time submit).
VkCommandBuffer beginOneTimeCommands(const VulkanDevice& vk);
/// Ends, submits and waits for it (fence), then frees it.
void submitAndWait(const VulkanDevice& vk, VkCommandBuffer cmd);

}  // namespace demo
