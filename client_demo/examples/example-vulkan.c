/* SPDX-License-Identifier: MIT */
/* Zero-copy frames: subscribe to the service's exported Vulkan images, import them into our own
 * VkDevice (the same GPU; lavapipe on CPU-only machines), copy the newest frame to host memory and print
 * its id and mean pixel.   usage: example-vulkan [SOCKET_PATH] */
#include "skyservice/client/skyclient.h"
#include "skyservice/client/vulkan/skyclient_vulkan.h"

#include <stdio.h>
#include <stdlib.h>

#define FAIL(...) do { fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); return 1; } while (0)

int main(int argc, char** argv)
{
    const char* path = argc > 1 ? argv[1] : "/tmp/skyservice-example.sock";
    SkyClient* client;
    SkyExportedFrames exported;
    if (sky_client_connect(path, "example-vulkan", &client) != SKY_OK)
        FAIL("connect %s failed", path);
    if (sky_client_subscribe_vulkan(client, &exported) != SKY_OK)
        FAIL("subscribe: %s", sky_client_last_error(client));

    VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO, NULL, "example-vulkan", 1, NULL, 0, VK_API_VERSION_1_2};
    VkInstanceCreateInfo ii = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, NULL, 0, &app, 0, NULL, 0, NULL};
    VkInstance instance;
    VkPhysicalDevice pd;
    if (vkCreateInstance(&ii, NULL, &instance) != VK_SUCCESS)
        FAIL("no Vulkan instance");
    if (sky_vulkan_find_physical_device(instance, &exported, &pd) != SKY_OK)
        FAIL("%s", sky_vulkan_last_error());
    uint32_t family = 0, families = 8, extCount;
    VkQueueFamilyProperties props[8];
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &families, props);
    while (family < families && !(props[family].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)))
        ++family;
    int semaphore = exported.timeline_semaphore_fd >= 0;
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, NULL, 0, family, 1, &priority};
    VkPhysicalDeviceVulkan12Features f12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.timelineSemaphore = semaphore ? VK_TRUE : VK_FALSE;
    const char* const* exts = sky_vulkan_required_device_extensions(semaphore, &extCount);
    VkDeviceCreateInfo di = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f12, 0, 1, &qi, 0, NULL, extCount, exts, NULL};
    VkDevice device;
    VkQueue queue;
    SkyImportedFrames imported;
    if (vkCreateDevice(pd, &di, NULL, &device) != VK_SUCCESS)
        FAIL("vkCreateDevice failed");
    vkGetDeviceQueue(device, family, 0, &queue);
    if (sky_vulkan_import_frames(pd, device, &exported, &imported) != SKY_OK)
        FAIL("import: %s", sky_vulkan_last_error());

    /* A host-visible buffer as large as a slot's image. */
    VkDeviceSize bytes = (VkDeviceSize)imported.frame[0].width * imported.frame[0].height * 4;
    VkBufferCreateInfo bi = {VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, NULL, 0, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT};
    VkBuffer buffer;
    VkMemoryRequirements req;
    VkPhysicalDeviceMemoryProperties mem;
    vkCreateBuffer(device, &bi, NULL, &buffer);
    vkGetBufferMemoryRequirements(device, buffer, &req);
    vkGetPhysicalDeviceMemoryProperties(pd, &mem);
    uint32_t type = 0, host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    while (!((req.memoryTypeBits >> type) & 1u) || (mem.memoryTypes[type].propertyFlags & host) != host)
        ++type;
    VkMemoryAllocateInfo ai = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, NULL, req.size, type};
    VkDeviceMemory memory;
    vkAllocateMemory(device, &ai, NULL, &memory);
    vkBindBufferMemory(device, buffer, memory, 0);

    uint64_t id = 0;
    SkyFrame f;
    sky_client_request_frame(client, &id);
    if (sky_client_wait_frame(client, id > 0 ? id - 1 : 0, 10000) != SKY_OK || sky_client_acquire_frame(client, &f) != SKY_OK)
        FAIL("no frame: %s", sky_client_last_error(client));
    if (imported.timeline_semaphore) /* with a semaphore the slot is complete once it reaches the frame id */
    {
        VkSemaphoreWaitInfo wi = {VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO, NULL, 0, 1, &imported.timeline_semaphore,
                                  &f.frame_id};
        vkWaitSemaphores(device, &wi, UINT64_MAX);
    }
    VkCommandPoolCreateInfo pi = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, NULL, 0, family};
    VkCommandPool pool;
    VkCommandBuffer cmd;
    vkCreateCommandPool(device, &pi, NULL, &pool);
    VkCommandBufferAllocateInfo ci = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, NULL, pool,
                                      VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    vkAllocateCommandBuffers(device, &ci, &cmd);
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    sky_vulkan_cmd_acquire(cmd, &imported.frame[f.slot], family);
    VkBufferImageCopy region = {0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {f.width, f.height, 1}};
    vkCmdCopyImageToBuffer(cmd, imported.frame[f.slot].image, VK_IMAGE_LAYOUT_GENERAL, buffer, 1, &region);
    vkEndCommandBuffer(cmd);
    VkSubmitInfo si = {VK_STRUCTURE_TYPE_SUBMIT_INFO, NULL, 0, NULL, NULL, 1, &cmd, 0, NULL};
    vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE);
    vkQueueWaitIdle(queue);
    SkyResult intact = sky_client_release_frame(client, &f); /* the copy must finish before this check */

    const uint8_t* px;
    double sum[3] = {0, 0, 0};
    vkMapMemory(device, memory, 0, bytes, 0, (void**)&px);
    for (size_t i = 0; i < (size_t)f.width * f.height; ++i)
        for (int c = 0; c < 3; ++c)
            sum[c] += px[i * 4 + (size_t)c];
    double n = (double)f.width * f.height;
    printf("frame %llu (%ux%u, slot %u%s): mean pixel R %.1f G %.1f B %.1f\n", (unsigned long long)f.frame_id,
           f.width, f.height, f.slot, intact == SKY_OK ? "" : ", TORN: discard", sum[0] / n, sum[1] / n, sum[2] / n);

    vkDestroyCommandPool(device, pool, NULL);
    vkDestroyBuffer(device, buffer, NULL);
    vkFreeMemory(device, memory, NULL);
    sky_vulkan_destroy_frames(device, &imported);
    vkDestroyDevice(device, NULL);
    vkDestroyInstance(instance, NULL);
    sky_client_close(client);
    return intact == SKY_OK ? 0 : 2;
}
