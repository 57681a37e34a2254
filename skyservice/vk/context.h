// SPDX-License-Identifier: MIT
// Headless Vulkan compute context: instance, debug messenger, one device with a compute queue.
// No surface, no window system (OVERVIEW.md; windows live only in client_demo/).
#pragma once

#include "skyservice/vk/check.h"

#include <atomic>
#include <string>
#include <vulkan/vulkan.h>

namespace sky
{

struct ContextOptions
{
    bool validation = false;        ///< enable VK_LAYER_KHRONOS_validation and count its messages
    std::string deviceSelector;     ///< "" = best (discrete > integrated > virtual > CPU), a number, or a name substring
    bool quiet = false;             ///< do not print the chosen device
    /// Capture the driver compiler's statistics of each pipeline (registers, spills...) into
    /// Program::statistics, where the device has VK_KHR_pipeline_executable_properties (sky-bench).
    bool pipelineStatistics = false;
    /// How shaders read their parameter blocks (Context::paramsInStorageBuffers): Auto = storage buffers
    /// on lavapipe only; the others force one variant (tests check that both draw the same).
    enum class ParamBlocks { Auto, Uniform, Storage } paramBlocks = ParamBlocks::Auto;
};

/// Everything device-wide. Owned by the Service / renderer; destroyed with destroyContext().
struct Context
{
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkPhysicalDeviceProperties properties = {};
    VkPhysicalDeviceMemoryProperties memoryProperties = {};
    double timestampPeriodNs = 0;   ///< 0 when the queue has no timestamps
    bool debugUtils = false;
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;  ///< VK_KHR_push_descriptor entry point
    std::string deviceName;
    std::string driverInfo;

    // Optional, for frame export (skyservice/render/frame_export.h): enabled when the device has them.
    bool externalMemoryFd = false;     ///< VK_KHR_external_memory_fd enabled
    bool externalSemaphoreFd = false;  ///< VK_KHR_external_semaphore_fd enabled (and timelineSemaphore on)
    bool timelineSemaphore = false;    ///< the Vulkan 1.2 timelineSemaphore feature enabled
    uint8_t deviceUUID[VK_UUID_SIZE] = {};  ///< VkPhysicalDeviceIDProperties: importers must match it
    uint8_t driverUUID[VK_UUID_SIZE] = {};
    PFN_vkGetMemoryFdKHR getMemoryFd = nullptr;        ///< when externalMemoryFd
    PFN_vkGetSemaphoreFdKHR getSemaphoreFd = nullptr;  ///< when externalSemaphoreFd

    /// Shaders read their parameter blocks from storage buffers (the `.storage.spv` variants) instead of
    /// uniform buffers: on lavapipe, whose uniform buffers through push descriptors leak (bindings.h).
    bool paramsInStorageBuffers = false;

    /// Pipelines are created with their compiler statistics captured (ContextOptions::pipelineStatistics).
    PFN_vkGetPipelineExecutablePropertiesKHR getPipelineExecutableProperties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR getPipelineExecutableStatistics = nullptr;

    /// Validation messages of severity warning or error seen so far (tests fail on any).
    std::atomic<uint32_t> validationMessages{0};
};

/// Creates the instance and device. On failure returns a message such as "no Vulkan driver found"
/// and leaves every handle in `ctx` null.
SkyStatus createContext(Context& ctx, const ContextOptions& options);
void destroyContext(Context& ctx);

/// Gives a debug name to a Vulkan object (visible in validation messages); no-op without debug utils.
void setObjectName(const Context& ctx, VkObjectType type, uint64_t handle, const char* name);

}  // namespace sky
