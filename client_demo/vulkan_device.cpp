// SPDX-License-Identifier: MIT
#include "client_demo/vulkan_device.h"

#include <algorithm>

namespace demo
{
namespace
{

bool pickQueueFamily(VkPhysicalDevice pd, VkSurfaceKHR surface, uint32_t& family)
{
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
    std::vector<VkQueueFamilyProperties> props(count);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, props.data());
    for (uint32_t i = 0; i < count; ++i)
    {
        // Graphics and compute queues both support transfer (vkCmdBlitImage needs graphics).
        const VkQueueFlags want = surface != VK_NULL_HANDLE
                                      ? VkQueueFlags(VK_QUEUE_GRAPHICS_BIT)
                                      : VkQueueFlags(VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT);
        if ((props[i].queueFlags & want) == 0)
            continue;
        if (surface != VK_NULL_HANDLE)
        {
            VkBool32 present = VK_FALSE;
            if (vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface, &present) != VK_SUCCESS || !present)
                continue;
        }
        family = i;
        return true;
    }
    return false;
}

}  // namespace

bool createVulkanInstance(VulkanDevice& vk, const std::vector<const char*>& extensions, std::string& error)
{
    VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "client_demo";
    app.apiVersion = VK_API_VERSION_1_2;  // 1.1 for deviceUUID (matching the service's GPU), 1.2 for timelines
    VkInstanceCreateInfo info = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    const VkResult r = vkCreateInstance(&info, nullptr, &vk.instance);
    if (r != VK_SUCCESS)
    {
        vk.instance = VK_NULL_HANDLE;
        error = "vkCreateInstance failed (VkResult " + std::to_string(int(r)) + ")";
        return false;
    }
    return true;
}

bool canPresent(VkPhysicalDevice physicalDevice, VkSurfaceKHR surface)
{
    uint32_t family = 0;
    return pickQueueFamily(physicalDevice, surface, family);
}

bool createVulkanDevice(VulkanDevice& vk, const DeviceRequest& request, std::string& error)
{
    std::vector<VkPhysicalDevice> candidates;
    if (request.preferred != VK_NULL_HANDLE)
        candidates.push_back(request.preferred);
    else
    {
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(vk.instance, &count, nullptr);
        candidates.resize(count);
        vkEnumeratePhysicalDevices(vk.instance, &count, candidates.data());
        // Discrete GPUs first: a laptop's integrated GPU or lavapipe only when nothing better exists.
        std::stable_partition(candidates.begin(), candidates.end(), [](VkPhysicalDevice pd) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pd, &p);
            return p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
        });
    }
    for (VkPhysicalDevice pd : candidates)
    {
        uint32_t family = 0;
        if (!pickQueueFamily(pd, request.surface, family))
            continue;
        std::vector<const char*> extensions = request.extensions;
        if (request.surface != VK_NULL_HANDLE)
            extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queue.queueFamilyIndex = family;
        queue.queueCount = 1;
        queue.pQueuePriorities = &priority;
        VkDeviceCreateInfo info = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        info.queueCreateInfoCount = 1;
        info.pQueueCreateInfos = &queue;
        info.enabledExtensionCount = uint32_t(extensions.size());
        info.ppEnabledExtensionNames = extensions.data();
        if (vkCreateDevice(pd, &info, nullptr, &vk.device) != VK_SUCCESS)
        {
            vk.device = VK_NULL_HANDLE;
            continue;
        }
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(pd, &props);
        vk.deviceName = props.deviceName;
        vk.physicalDevice = pd;
        vk.queueFamily = family;
        vkGetDeviceQueue(vk.device, family, 0, &vk.queue);
        VkCommandPoolCreateInfo pool = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = family;
        DEMO_VK_CHECK(vkCreateCommandPool(vk.device, &pool, nullptr, &vk.commandPool));
        return true;
    }
    error = request.surface != VK_NULL_HANDLE ? "no Vulkan device can present to the window"
                                              : "no Vulkan device with a graphics or compute queue";
    return false;
}

void destroyVulkanDeviceOnly(VulkanDevice& vk)
{
    if (vk.device != VK_NULL_HANDLE)
    {
        vkDeviceWaitIdle(vk.device);
        vkDestroyCommandPool(vk.device, vk.commandPool, nullptr);
        vkDestroyDevice(vk.device, nullptr);
    }
    const VkInstance instance = vk.instance;
    vk = VulkanDevice{};
    vk.instance = instance;
}

void destroyVulkanDevice(VulkanDevice& vk)
{
    destroyVulkanDeviceOnly(vk);
    if (vk.instance != VK_NULL_HANDLE)
        vkDestroyInstance(vk.instance, nullptr);
    vk = VulkanDevice{};
}

uint32_t findMemoryType(VkPhysicalDevice physicalDevice, uint32_t typeBits, VkMemoryPropertyFlags properties)
{
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &mem);
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
        if ((typeBits >> i & 1u) != 0 && (mem.memoryTypes[i].propertyFlags & properties) == properties)
            return i;
    return UINT32_MAX;
}

void createHostBuffer(const VulkanDevice& vk, VkDeviceSize bytes, HostBuffer& buffer)
{
    VkBufferCreateInfo info = {VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    DEMO_VK_CHECK(vkCreateBuffer(vk.device, &info, nullptr, &buffer.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk.device, buffer.buffer, &req);
    VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = findMemoryType(vk.physicalDevice, req.memoryTypeBits,
                                           VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    DEMO_VK_CHECK(vkAllocateMemory(vk.device, &alloc, nullptr, &buffer.memory));
    DEMO_VK_CHECK(vkBindBufferMemory(vk.device, buffer.buffer, buffer.memory, 0));
    DEMO_VK_CHECK(vkMapMemory(vk.device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
    buffer.bytes = bytes;
}

void destroyHostBuffer(const VulkanDevice& vk, HostBuffer& buffer)
{
    if (buffer.buffer != VK_NULL_HANDLE)
        vkDestroyBuffer(vk.device, buffer.buffer, nullptr);
    if (buffer.memory != VK_NULL_HANDLE)
        vkFreeMemory(vk.device, buffer.memory, nullptr);
    buffer = HostBuffer{};
}

VkCommandBuffer beginOneTimeCommands(const VulkanDevice& vk)
{
    VkCommandBufferAllocateInfo alloc = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = vk.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    DEMO_VK_CHECK(vkAllocateCommandBuffers(vk.device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    DEMO_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return cmd;
}

void submitAndWait(const VulkanDevice& vk, VkCommandBuffer cmd)
{
    DEMO_VK_CHECK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fenceInfo = {VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    DEMO_VK_CHECK(vkCreateFence(vk.device, &fenceInfo, nullptr, &fence));
    VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    DEMO_VK_CHECK(vkQueueSubmit(vk.queue, 1, &submit, fence));
    DEMO_VK_CHECK(vkWaitForFences(vk.device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkDestroyFence(vk.device, fence, nullptr);
    vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &cmd);
}

}  // namespace demo
