// SPDX-License-Identifier: MIT
#include "skyservice/vk/context.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace sky
{
namespace
{

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user)
{
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
        return VK_FALSE;
    auto* ctx = static_cast<Context*>(user);
    ctx->validationMessages.fetch_add(1);
    std::fprintf(stderr, "vulkan validation %s: %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "ERROR" : "warning", data->pMessage);
    return VK_FALSE;
}

bool hasLayer(const char* name)
{
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0)
            return true;
    return false;
}

bool hasInstanceExtension(const char* name)
{
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
    for (const auto& e : exts)
        if (std::strcmp(e.extensionName, name) == 0)
            return true;
    return false;
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name)
{
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> exts(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, exts.data());
    for (const auto& e : exts)
        if (std::strcmp(e.extensionName, name) == 0)
            return true;
    return false;
}

int deviceTypeRank(VkPhysicalDeviceType type)
{
    switch (type)
    {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 3;
    default:
        return 4;
    }
}

// Checks what the renderer needs; returns "" or what is missing.
std::string missingRequirements(VkPhysicalDevice pd)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    if (props.apiVersion < VK_API_VERSION_1_3)
        return "Vulkan 1.3 (device offers " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
               std::to_string(VK_API_VERSION_MINOR(props.apiVersion)) + ")";
    if (!hasDeviceExtension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        return VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &familyCount, families.data());
    for (const auto& f : families)
        if (f.queueFlags & VK_QUEUE_COMPUTE_BIT)
            return "";
    return "a compute queue";
}

// The instance, with the validation layer when asked for and debug utils when the loader has them.
SkyStatus createInstance(Context& ctx, const ContextOptions& options)
{
    uint32_t loaderVersion = 0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS || loaderVersion < VK_API_VERSION_1_3)
        return SkyStatus::failure("the Vulkan loader is missing or older than 1.3 (install libvulkan1)",
                                  VK_ERROR_INCOMPATIBLE_DRIVER);

    VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "skyservice";
    app.apiVersion = VK_API_VERSION_1_3;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (options.validation)
    {
        if (!hasLayer("VK_LAYER_KHRONOS_validation"))
            return SkyStatus::failure("--validate: VK_LAYER_KHRONOS_validation is not installed "
                                      "(apt-get install vulkan-validationlayers)",
                                      VK_ERROR_LAYER_NOT_PRESENT);
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    ctx.debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (ctx.debugUtils)
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    VkInstanceCreateInfo instanceInfo = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = uint32_t(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = uint32_t(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    VkResult r = vkCreateInstance(&instanceInfo, nullptr, &ctx.instance);
    if (r != VK_SUCCESS)
    {
        ctx.instance = VK_NULL_HANDLE;
        return SkyStatus::failure(std::string("cannot create a Vulkan instance (") + vkResultName(r) +
                                      "): no working Vulkan driver? (apt-get install mesa-vulkan-drivers)",
                                  r);
    }
    return SkyStatus::success();
}

// Routes validation warnings and errors to debugCallback, which counts them in ctx.
void createDebugMessenger(Context& ctx)
{
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerCreateInfoEXT info = {VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = debugCallback;
    info.pUserData = &ctx;
    if (create)
        VK_CHECK(create(ctx.instance, &info, nullptr, &ctx.messenger));
}

// Selection: an explicit index or name, else the best-ranked device that has what we need. Sets
// ctx.physicalDevice; on failure destroys what ctx holds and says why each device was refused.
SkyStatus choosePhysicalDevice(Context& ctx, const ContextOptions& options)
{
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(ctx.instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(ctx.instance, &count, devices.data());
    if (devices.empty())
    {
        destroyContext(ctx);
        return SkyStatus::failure("no Vulkan device found (install mesa-vulkan-drivers for the CPU device)",
                                  VK_ERROR_INCOMPATIBLE_DRIVER);
    }

    int chosen = -1;
    std::string why;
    const std::string& sel = options.deviceSelector;
    bool numeric = !sel.empty() && sel.find_first_not_of("0123456789") == std::string::npos;
    for (uint32_t i = 0; i < count; ++i)
    {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(devices[i], &props);
        bool wanted = sel.empty() || (numeric ? std::stoul(sel) == i : std::strstr(props.deviceName, sel.c_str()) != nullptr);
        if (!wanted)
            continue;
        std::string missing = missingRequirements(devices[i]);
        if (!missing.empty())
        {
            why += std::string("\n  device ") + std::to_string(i) + " (" + props.deviceName + ") lacks " + missing;
            continue;
        }
        if (chosen < 0)
        {
            chosen = int(i);
            continue;
        }
        VkPhysicalDeviceProperties best;
        vkGetPhysicalDeviceProperties(devices[uint32_t(chosen)], &best);
        if (deviceTypeRank(props.deviceType) < deviceTypeRank(best.deviceType))
            chosen = int(i);
    }
    if (chosen < 0)
    {
        destroyContext(ctx);
        if (!sel.empty() && why.empty())
            return SkyStatus::failure("--device " + sel + ": no such device (" + std::to_string(count) + " found)",
                                      VK_ERROR_INITIALIZATION_FAILED);
        return SkyStatus::failure("no Vulkan device has what the renderer needs:" + why, VK_ERROR_FEATURE_NOT_PRESENT);
    }
    ctx.physicalDevice = devices[uint32_t(chosen)];
    return SkyStatus::success();
}

// The chosen device's properties, driver, identity (for the frame-export UUID match) and compute
// queue family.
void readDeviceProperties(Context& ctx, const ContextOptions& options)
{
    vkGetPhysicalDeviceProperties(ctx.physicalDevice, &ctx.properties);
    vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice, &ctx.memoryProperties);
    ctx.deviceName = ctx.properties.deviceName;

    VkPhysicalDeviceIDProperties idProps = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceDriverProperties driverProps = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    driverProps.pNext = &idProps;
    VkPhysicalDeviceProperties2 props2 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props2.pNext = &driverProps;
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice, &props2);
    ctx.driverInfo = std::string(driverProps.driverName) + " " + driverProps.driverInfo;
    ctx.paramsInStorageBuffers = options.paramBlocks == ContextOptions::ParamBlocks::Auto
                                     ? driverProps.driverID == VK_DRIVER_ID_MESA_LLVMPIPE
                                     : options.paramBlocks == ContextOptions::ParamBlocks::Storage;
    std::memcpy(ctx.deviceUUID, idProps.deviceUUID, VK_UUID_SIZE);
    std::memcpy(ctx.driverUUID, idProps.driverUUID, VK_UUID_SIZE);

    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice, &familyCount, families.data());
    for (uint32_t i = 0; i < familyCount; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)
        {
            ctx.queueFamily = i;
            if (families[i].timestampValidBits > 0)
                ctx.timestampPeriodNs = double(ctx.properties.limits.timestampPeriod);
            break;
        }
}

// The features and extensions the device is created with. The structs point at each other through
// pNext, so the chain is built in place and never copied.
struct DeviceFeatureChain
{
    DeviceFeatureChain() = default;
    DeviceFeatureChain(const DeviceFeatureChain&) = delete;
    DeviceFeatureChain& operator=(const DeviceFeatureChain&) = delete;

    std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    VkPhysicalDeviceVulkan13Features features13 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features features12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableFeatures = {
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    bool pipelineStatistics = false;
};

// Optional frame-export support (frame_export.h): external memory, timeline semaphores, and
// exportable semaphores when the device has them; a device without them still renders.
void chooseExportFeatures(Context& ctx, DeviceFeatureChain& chain)
{
    {
        VkPhysicalDeviceVulkan12Features supported12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        VkPhysicalDeviceFeatures2 supported = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        supported.pNext = &supported12;
        vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &supported);
        ctx.timelineSemaphore = supported12.timelineSemaphore == VK_TRUE;
        chain.features12.timelineSemaphore = supported12.timelineSemaphore;
    }
    ctx.externalMemoryFd = hasDeviceExtension(ctx.physicalDevice, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    if (ctx.externalMemoryFd)
        chain.extensions.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    ctx.externalSemaphoreFd =
        ctx.timelineSemaphore && hasDeviceExtension(ctx.physicalDevice, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
    if (ctx.externalSemaphoreFd)
        chain.extensions.push_back(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
}

// Pipeline executable statistics (register counts in the bench), only when asked for and offered.
void choosePipelineStatistics(const Context& ctx, const ContextOptions& options, DeviceFeatureChain& chain)
{
    bool pipelineStatistics = options.pipelineStatistics &&
                              hasDeviceExtension(ctx.physicalDevice, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    if (pipelineStatistics)
    {
        VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR supportedExecutable = {
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
        VkPhysicalDeviceFeatures2 supported = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        supported.pNext = &supportedExecutable;
        vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &supported);
        pipelineStatistics = supportedExecutable.pipelineExecutableInfo == VK_TRUE;
    }
    if (pipelineStatistics)
    {
        chain.extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
        chain.executableFeatures.pipelineExecutableInfo = VK_TRUE;
        chain.executableFeatures.pNext = chain.features13.pNext;
        chain.features13.pNext = &chain.executableFeatures;
    }
    chain.pipelineStatistics = pipelineStatistics;
}

// The extension entry points the context uses; an extension whose functions are missing counts as
// absent.
void loadDeviceFunctions(Context& ctx, bool pipelineStatistics)
{
    ctx.cmdPushDescriptorSet =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(ctx.device, "vkCmdPushDescriptorSetKHR"));
    if (ctx.externalMemoryFd)
        ctx.getMemoryFd = reinterpret_cast<PFN_vkGetMemoryFdKHR>(vkGetDeviceProcAddr(ctx.device, "vkGetMemoryFdKHR"));
    if (ctx.externalSemaphoreFd)
        ctx.getSemaphoreFd =
            reinterpret_cast<PFN_vkGetSemaphoreFdKHR>(vkGetDeviceProcAddr(ctx.device, "vkGetSemaphoreFdKHR"));
    if (pipelineStatistics)
    {
        ctx.getPipelineExecutableProperties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            vkGetDeviceProcAddr(ctx.device, "vkGetPipelineExecutablePropertiesKHR"));
        ctx.getPipelineExecutableStatistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            vkGetDeviceProcAddr(ctx.device, "vkGetPipelineExecutableStatisticsKHR"));
        if (!ctx.getPipelineExecutableProperties || !ctx.getPipelineExecutableStatistics)
            ctx.getPipelineExecutableProperties = nullptr;
    }
    ctx.externalMemoryFd = ctx.getMemoryFd != nullptr;
    ctx.externalSemaphoreFd = ctx.getSemaphoreFd != nullptr;
}

// The logical device with one compute queue; on failure destroys what ctx holds.
SkyStatus createLogicalDevice(Context& ctx, const ContextOptions& options)
{
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = ctx.queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    DeviceFeatureChain chain;
    chain.features13.synchronization2 = VK_TRUE;
    chain.features13.maintenance4 = VK_TRUE;  // glslang's SPIR-V 1.6 uses LocalSizeId, which needs it
    chain.features12.pNext = &chain.features13;
    chain.features12.hostQueryReset = VK_TRUE;
    chain.features.pNext = &chain.features12;
    chooseExportFeatures(ctx, chain);
    choosePipelineStatistics(ctx, options, chain);

    VkDeviceCreateInfo deviceInfo = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &chain.features;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = uint32_t(chain.extensions.size());
    deviceInfo.ppEnabledExtensionNames = chain.extensions.data();
    VkResult r = vkCreateDevice(ctx.physicalDevice, &deviceInfo, nullptr, &ctx.device);
    if (r != VK_SUCCESS)
    {
        ctx.device = VK_NULL_HANDLE;
        std::string name = ctx.deviceName;
        destroyContext(ctx);
        return SkyStatus::failure("cannot create the Vulkan device on " + name + ": " + vkResultName(r), r);
    }
    vkGetDeviceQueue(ctx.device, ctx.queueFamily, 0, &ctx.queue);
    loadDeviceFunctions(ctx, chain.pipelineStatistics);
    return SkyStatus::success();
}

}  // namespace

SkyStatus createContext(Context& ctx, const ContextOptions& options)
{
    SkyStatus status = createInstance(ctx, options);
    if (!status.ok())
        return status;
    if (options.validation && ctx.debugUtils)
        createDebugMessenger(ctx);
    status = choosePhysicalDevice(ctx, options);
    if (!status.ok())
        return status;
    readDeviceProperties(ctx, options);
    status = createLogicalDevice(ctx, options);
    if (!status.ok())
        return status;
    if (!options.quiet)
        std::fprintf(stderr, "skyservice: Vulkan device %s (%s)\n", ctx.deviceName.c_str(), ctx.driverInfo.c_str());
    return SkyStatus::success();
}

void destroyContext(Context& ctx)
{
    if (ctx.device)
        vkDestroyDevice(ctx.device, nullptr);
    if (ctx.messenger)
    {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy)
            destroy(ctx.instance, ctx.messenger, nullptr);
    }
    if (ctx.instance)
        vkDestroyInstance(ctx.instance, nullptr);
    ctx.device = VK_NULL_HANDLE;
    ctx.messenger = VK_NULL_HANDLE;
    ctx.instance = VK_NULL_HANDLE;
    ctx.physicalDevice = VK_NULL_HANDLE;
    ctx.queue = VK_NULL_HANDLE;
    ctx.getMemoryFd = nullptr;
    ctx.getSemaphoreFd = nullptr;
}

void setObjectName(const Context& ctx, VkObjectType type, uint64_t handle, const char* name)
{
    if (!ctx.debugUtils || !handle)
        return;
    auto fn = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkSetDebugUtilsObjectNameEXT"));
    if (!fn)
        return;
    VkDebugUtilsObjectNameInfoEXT info = {VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    fn(ctx.device, &info);
}

}  // namespace sky
