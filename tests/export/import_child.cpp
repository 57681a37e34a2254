// SPDX-License-Identifier: MIT
#include "tests/export/import_child.h"

#include "skyservice/client/vulkan/skyclient_vulkan.h"

#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace sky::exporttest
{

bool sendLineWithFds(int socket, const std::string& line, const std::vector<int>& fds)
{
    iovec iov = {const_cast<char*>(line.data()), line.size()};
    msghdr msg = {};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    std::vector<char> control(CMSG_SPACE(sizeof(int) * fds.size()));
    if (!fds.empty())
    {
        msg.msg_control = control.data();
        msg.msg_controllen = control.size();
        cmsghdr* c = CMSG_FIRSTHDR(&msg);
        c->cmsg_level = SOL_SOCKET;
        c->cmsg_type = SCM_RIGHTS;
        c->cmsg_len = CMSG_LEN(sizeof(int) * fds.size());
        std::memcpy(CMSG_DATA(c), fds.data(), sizeof(int) * fds.size());
    }
    return sendmsg(socket, &msg, MSG_NOSIGNAL) == ssize_t(line.size());
}

bool receiveLineWithFds(int socket, std::string& line, std::vector<int>& fds)
{
    std::vector<char> buffer(65536);
    iovec iov = {buffer.data(), buffer.size()};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int) * 64)];
    msghdr msg = {};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    ssize_t n = recvmsg(socket, &msg, MSG_CMSG_CLOEXEC);
    if (n <= 0)
        return false;
    line.assign(buffer.data(), size_t(n));
    fds.clear();
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS)
        {
            size_t count = (c->cmsg_len - CMSG_LEN(0)) / sizeof(int);
            const unsigned char* data = CMSG_DATA(c);
            for (size_t i = 0; i < count; ++i)
            {
                int fd;
                std::memcpy(&fd, data + i * sizeof(int), sizeof fd);
                fds.push_back(fd);
            }
        }
    return !line.empty() && line.back() == '\n' && !(msg.msg_flags & (MSG_TRUNC | MSG_CTRUNC));
}

namespace
{

VKAPI_ATTR VkBool32 VKAPI_CALL countMessages(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user)
{
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
    {
        ++*static_cast<uint32_t*>(user);
        std::fprintf(stderr, "import child: vulkan validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

bool parseHex(const std::string& text, uint8_t* out)
{
    if (text.size() != 2 * VK_UUID_SIZE)
        return false;
    for (size_t i = 0; i < VK_UUID_SIZE; ++i)
        out[i] = uint8_t(std::stoul(text.substr(2 * i, 2), nullptr, 16));
    return true;
}

void fillImage(const nlohmann::json& j, int fd, SkyExportedImage& out)
{
    out.memory_fd = fd;
    out.allocation_bytes = j.at("allocation_bytes").get<uint64_t>();
    out.memory_type_bits = j.at("memory_type_bits").get<uint32_t>();
    out.vk_format = j.at("vk_format").get<uint32_t>();
    out.width = j.at("width").get<uint32_t>();
    out.height = j.at("height").get<uint32_t>();
    out.linear_tiling = j.at("linear_tiling").get<bool>() ? 1u : 0u;
    out.row_pitch = j.at("row_pitch").get<uint64_t>();
}

// Everything the child made, destroyed in reverse order whatever happened.
struct ChildVulkan
{
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory bufferMemory = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    SkyImportedFrames imported = {};
    SkyImportedLayers importedLayers = {};
    uint32_t* messages = nullptr;  ///< outlives this: the destructor's messages count too

    ~ChildVulkan()
    {
        if (device)
        {
            vkDeviceWaitIdle(device);
            sky_vulkan_destroy_frames(device, &imported);
            sky_vulkan_destroy_layers(device, &importedLayers);
            vkDestroyCommandPool(device, pool, nullptr);
            vkDestroyBuffer(device, buffer, nullptr);
            vkFreeMemory(device, bufferMemory, nullptr);
            vkDestroyDevice(device, nullptr);
        }
        if (messenger)
            reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"))(instance, messenger, nullptr);
        if (instance)
            vkDestroyInstance(instance, nullptr);
    }
};

#define CHILD_TRY(cond, ...)                                                                                           \
    do                                                                                                                 \
    {                                                                                                                  \
        if (!(cond))                                                                                                   \
        {                                                                                                              \
            std::snprintf(report.error, sizeof report.error, __VA_ARGS__);                                             \
            return false;                                                                                              \
        }                                                                                                              \
    } while (0)

constexpr const char* kLayerNames[SKY_LAYER_COUNT] = {"display", "sky", "clouds", "depth"};

// The description line and fds (PROTOCOL.md order: frames, shadows, layers, semaphore) as SkyExportedFrames.
bool parseDescription(int socket, const ReadPlan& plan, SkyExportedFrames& frames, ChildReport& report)
{
    std::string line;
    std::vector<int> fds;
    CHILD_TRY(receiveLineWithFds(socket, line, fds), "no description line with fds arrived");
    nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    const uint32_t slots = plan.slots;
    CHILD_TRY(j.is_object() && j.contains("images") && j["images"].size() == slots, "bad description: %s",
              line.substr(0, 200).c_str());
    const nlohmann::json& images = j["images"];
    const bool shadows = !images[0]["shadow"].is_null();
    const bool semaphore = j.at("timeline_semaphore").get<bool>();
    uint32_t layerCount = 0;
    for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT; ++k)
        layerCount += (plan.layers >> k) & 1u;
    CHILD_TRY(fds.size() == slots * ((shadows ? 2u : 1u) + layerCount) + (semaphore ? 1u : 0u), "%zu fds for %u slots",
              fds.size(), slots);
    frames = SkyExportedFrames{};
    frames.slot_count = slots;
    frames.timeline_semaphore_fd = semaphore ? fds.back() : -1;
    frames.layers = plan.layers | (1u << SKY_LAYER_DISPLAY);
    size_t next = 0;
    for (uint32_t i = 0; i < slots; ++i)
        fillImage(images[i], fds[next++], frames.frame[i]);
    for (uint32_t i = 0; i < slots; ++i)
    {
        frames.shadow[i].memory_fd = -1;
        if (shadows)
            fillImage(images[i]["shadow"], fds[next++], frames.shadow[i]);
    }
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        for (uint32_t i = 0; i < slots; ++i)
        {
            frames.layer[k][i].memory_fd = -1;
            if (k == SKY_LAYER_DISPLAY || !(plan.layers & (1u << k)))
                continue;
            const nlohmann::json& layers = images[i].value("layers", nlohmann::json::object());
            CHILD_TRY(layers.contains(kLayerNames[k]), "slot %u has no %s layer", i, kLayerNames[k]);
            fillImage(layers[kLayerNames[k]], fds[next++], frames.layer[k][i]);
        }
    CHILD_TRY(parseHex(j.at("device_uuid"), frames.device_uuid) && parseHex(j.at("driver_uuid"), frames.driver_uuid),
              "bad uuids");
    return true;
}

bool importInto(SkyExportedFrames& frames, const ReadPlan& plan, ChildVulkan& vk, ChildReport& report,
                std::vector<uint8_t>& data)
{
    const uint32_t slots = plan.slots, width = plan.width, height = plan.height, shadowSize = plan.shadowSize;
    const uint64_t lastFrameId = plan.lastFrameId;
    const bool semaphore = frames.timeline_semaphore_fd >= 0;

    // A second instance and device, validation on.
    VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* debugExt = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo ii = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ii.pApplicationInfo = &app;
    ii.enabledLayerCount = 1;
    ii.ppEnabledLayerNames = &layer;
    ii.enabledExtensionCount = 1;
    ii.ppEnabledExtensionNames = &debugExt;
    CHILD_TRY(vkCreateInstance(&ii, nullptr, &vk.instance) == VK_SUCCESS, "vkCreateInstance with validation failed");
    VkDebugUtilsMessengerCreateInfoEXT mi = {VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    mi.pfnUserCallback = countMessages;
    mi.pUserData = vk.messages;
    reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(vk.instance, "vkCreateDebugUtilsMessengerEXT"))(vk.instance, &mi, nullptr, &vk.messenger);

    VkPhysicalDevice pd = VK_NULL_HANDLE;
    CHILD_TRY(sky_vulkan_find_physical_device(vk.instance, &frames, &pd) == SKY_OK, "%s", sky_vulkan_last_error());
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, families.data());
    uint32_t family = 0;
    while (family < familyCount && !(families[family].queueFlags & (VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT)))
        ++family;
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qi = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qi.queueFamilyIndex = family;
    qi.queueCount = 1;
    qi.pQueuePriorities = &priority;
    uint32_t extCount = 0;
    const char* const* exts = sky_vulkan_required_device_extensions(semaphore, &extCount);
    VkPhysicalDeviceVulkan12Features f12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.timelineSemaphore = semaphore ? VK_TRUE : VK_FALSE;
    VkDeviceCreateInfo di = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    di.pNext = &f12;
    di.queueCreateInfoCount = 1;
    di.pQueueCreateInfos = &qi;
    di.enabledExtensionCount = extCount;
    di.ppEnabledExtensionNames = exts;
    CHILD_TRY(vkCreateDevice(pd, &di, nullptr, &vk.device) == VK_SUCCESS, "vkCreateDevice failed");
    VkQueue queue;
    vkGetDeviceQueue(vk.device, family, 0, &queue);

    CHILD_TRY(sky_vulkan_import_frames(pd, vk.device, &frames, &vk.imported) == SKY_OK, "%s", sky_vulkan_last_error());
    CHILD_TRY(sky_vulkan_import_layers(pd, vk.device, &frames, &vk.importedLayers) == SKY_OK, "%s",
              sky_vulkan_last_error());

    if (vk.imported.timeline_semaphore)  // the service signals the frame id when a slot holds that frame
    {
        VkSemaphoreWaitInfo wi = {VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
        wi.semaphoreCount = 1;
        wi.pSemaphores = &vk.imported.timeline_semaphore;
        wi.pValues = &lastFrameId;
        CHILD_TRY(vkWaitSemaphores(vk.device, &wi, 10'000'000'000ull) == VK_SUCCESS, "the timeline wait failed");
        vkGetSemaphoreCounterValue(vk.device, vk.imported.timeline_semaphore, &report.timelineValue);
    }

    // One host buffer for every slot's frame, shadow map and layers.
    const VkDeviceSize total = slots * slotBytes(plan);
    VkBufferCreateInfo bi = {VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = total;
    bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    CHILD_TRY(vkCreateBuffer(vk.device, &bi, nullptr, &vk.buffer) == VK_SUCCESS, "vkCreateBuffer failed");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk.device, vk.buffer, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(pd, &mem);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    uint32_t type = 0;
    while (type < mem.memoryTypeCount &&
           !((req.memoryTypeBits & (1u << type)) && (mem.memoryTypes[type].propertyFlags & host) == host))
        ++type;
    VkMemoryAllocateInfo ai = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    CHILD_TRY(vkAllocateMemory(vk.device, &ai, nullptr, &vk.bufferMemory) == VK_SUCCESS, "buffer memory failed");
    vkBindBufferMemory(vk.device, vk.buffer, vk.bufferMemory, 0);

    VkCommandPoolCreateInfo pi = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.queueFamilyIndex = family;
    vkCreateCommandPool(vk.device, &pi, nullptr, &vk.pool);
    VkCommandBufferAllocateInfo ci = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ci.commandPool = vk.pool;
    ci.commandBufferCount = 1;
    VkCommandBuffer cmd;
    vkAllocateCommandBuffers(vk.device, &ci, &cmd);
    VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    VkDeviceSize offset = 0;
    for (uint32_t i = 0; i < slots; ++i)
    {
        struct Part
        {
            const SkyImportedImage* image;
            uint32_t width, height, pixelBytes;
        };
        std::vector<Part> parts = {{&vk.imported.frame[i], width, height, 4}};
        if (shadowSize > 0)
            parts.push_back({&vk.imported.shadow[i], shadowSize, shadowSize, 4});
        for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT; ++k)
            if (plan.layers & (1u << k))
                parts.push_back({&vk.importedLayers.image[k][i], width, height, 8});
        for (const Part& part : parts)
        {
            CHILD_TRY(part.image->image != VK_NULL_HANDLE, "slot %u: an image was not imported", i);
            sky_vulkan_cmd_acquire(cmd, part.image, family);
            VkBufferImageCopy region = {};
            region.bufferOffset = offset;
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {part.width, part.height, 1};
            vkCmdCopyImageToBuffer(cmd, part.image->image, VK_IMAGE_LAYOUT_GENERAL, vk.buffer, 1, &region);
            offset += VkDeviceSize(part.width) * part.height * part.pixelBytes;
        }
    }
    vkEndCommandBuffer(cmd);
    VkSubmitInfo si = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    CHILD_TRY(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS && vkQueueWaitIdle(queue) == VK_SUCCESS,
              "the copy failed");
    void* mapped = nullptr;
    vkMapMemory(vk.device, vk.bufferMemory, 0, total, 0, &mapped);
    data.assign(static_cast<const uint8_t*>(mapped), static_cast<const uint8_t*>(mapped) + total);
    vkUnmapMemory(vk.device, vk.bufferMemory);
    return true;
}

}  // namespace

size_t slotBytes(const ReadPlan& plan)
{
    size_t bytes = size_t(plan.width) * plan.height * 4 + size_t(plan.shadowSize) * plan.shadowSize * 4;
    for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT; ++k)
        if (plan.layers & (1u << k))
            bytes += size_t(plan.width) * plan.height * 8;
    return bytes;
}

bool importAndRead(SkyExportedFrames& frames, const ReadPlan& plan, ChildReport& report, std::vector<uint8_t>& data)
{
    uint32_t messages = 0;
    bool ok = false;
    {
        ChildVulkan vk;
        vk.messages = &messages;
        ok = importInto(frames, plan, vk, report, data);
    }  // ~ChildVulkan: its validation messages (leaks, bad frees) count too
    report.validationMessages = messages;
    report.status = ok ? 0 : 1;
    return ok;
}

int runImportChild(int socket, const ReadPlan& plan)
{
    ChildReport report;
    std::vector<uint8_t> data;
    SkyExportedFrames frames{};
    bool ok = parseDescription(socket, plan, frames, report) && importAndRead(frames, plan, report, data);
    report.status = ok ? 0 : 1;
    if (write(socket, &report, sizeof report) != ssize_t(sizeof report))
        return 2;
    for (size_t done = 0; ok && done < data.size();)
    {
        ssize_t n = write(socket, data.data() + done, data.size() - done);
        if (n <= 0)
            return 2;
        done += size_t(n);
    }
    return ok ? 0 : 1;
}

}  // namespace sky::exporttest
