// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_frame_wait.h"

#include "skyservice/client/vulkan/skyclient_vulkan.h"

#include <unistd.h>

namespace sky
{
namespace
{

void closeFd(int& fd)
{
    if (fd >= 0)
        ::close(fd);
    fd = -1;
}

} // namespace

FrameCompletionWait::~FrameCompletionWait()
{
    if (semaphore_ != VK_NULL_HANDLE)
        vkDestroySemaphore(device_, semaphore_, nullptr);
    if (device_ != VK_NULL_HANDLE)
        vkDestroyDevice(device_, nullptr);
    if (instance_ != VK_NULL_HANDLE)
        vkDestroyInstance(instance_, nullptr);
}

bool FrameCompletionWait::open(SkyExportedFrames& frames, std::string& error)
{
    for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS && i < frames.slot_count; ++i)
    {
        closeFd(frames.frame[i].memory_fd);
        closeFd(frames.shadow[i].memory_fd);
        for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
            closeFd(frames.layer[k][i].memory_fd);
    }
    if (frames.timeline_semaphore_fd < 0)
        return true;

    VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "sky-service-bench";
    app.apiVersion = VK_API_VERSION_1_2; // timeline semaphores and deviceUUID are core in 1.2
    VkInstanceCreateInfo ii = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ii.pApplicationInfo = &app;
    VkResult vr = vkCreateInstance(&ii, nullptr, &instance_);
    if (vr != VK_SUCCESS)
    {
        closeFd(frames.timeline_semaphore_fd);
        error = "vkCreateInstance for the timeline semaphore failed (VkResult " + std::to_string(int(vr)) + ")";
        return false;
    }
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    if (sky_vulkan_find_physical_device(instance_, &frames, &physical) != SKY_OK)
    {
        closeFd(frames.timeline_semaphore_fd);
        error = std::string("the service's GPU for its timeline semaphore: ") + sky_vulkan_last_error();
        return false;
    }
    // One queue of any family: a device needs one, the bench never submits to it.
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = 0;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    uint32_t extensionCount = 0;
    const char* const* extensions = sky_vulkan_required_device_extensions(1, &extensionCount);
    VkPhysicalDeviceVulkan12Features features12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    features12.timelineSemaphore = VK_TRUE;
    VkDeviceCreateInfo di = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.pNext = &features12;
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    di.enabledExtensionCount = extensionCount;
    di.ppEnabledExtensionNames = extensions;
    vr = vkCreateDevice(physical, &di, nullptr, &device_);
    if (vr != VK_SUCCESS)
    {
        closeFd(frames.timeline_semaphore_fd);
        error = "vkCreateDevice (external semaphore fd, timeline semaphores) failed (VkResult " +
                std::to_string(int(vr)) + ")";
        return false;
    }
    if (sky_vulkan_import_semaphore(device_, &frames.timeline_semaphore_fd, &semaphore_) != SKY_OK)
    {
        closeFd(frames.timeline_semaphore_fd);
        error = std::string("importing the service's timeline semaphore: ") + sky_vulkan_last_error();
        return false;
    }
    return true;
}

bool FrameCompletionWait::wait(uint64_t frameId, uint64_t timeoutNs, std::string& error)
{
    if (semaphore_ == VK_NULL_HANDLE)
        return true;
    VkSemaphoreWaitInfo wi = {VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    wi.semaphoreCount = 1;
    wi.pSemaphores = &semaphore_;
    wi.pValues = &frameId;
    VkResult vr = vkWaitSemaphores(device_, &wi, timeoutNs);
    if (vr == VK_SUCCESS)
        return true;
    error = vr == VK_TIMEOUT
                ? "the service's timeline semaphore did not reach frame " + std::to_string(frameId) + " in time"
                : "vkWaitSemaphores failed (VkResult " + std::to_string(int(vr)) + ")";
    return false;
}

} // namespace sky
