// SPDX-License-Identifier: MIT
#include "skyservice/vk/check.h"

#include <cstdio>
#include <cstdlib>

namespace sky
{

const char* vkResultName(VkResult result)
{
    switch (result)
    {
#define SKY_RESULT_CASE(r)                                                                                             \
    case r:                                                                                                            \
        return #r;
        SKY_RESULT_CASE(VK_SUCCESS)
        SKY_RESULT_CASE(VK_NOT_READY)
        SKY_RESULT_CASE(VK_TIMEOUT)
        SKY_RESULT_CASE(VK_EVENT_SET)
        SKY_RESULT_CASE(VK_EVENT_RESET)
        SKY_RESULT_CASE(VK_INCOMPLETE)
        SKY_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        SKY_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        SKY_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        SKY_RESULT_CASE(VK_ERROR_DEVICE_LOST)
        SKY_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        SKY_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        SKY_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        SKY_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        SKY_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        SKY_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        SKY_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        SKY_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
        SKY_RESULT_CASE(VK_ERROR_UNKNOWN)
        SKY_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        SKY_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        SKY_RESULT_CASE(VK_ERROR_FRAGMENTATION)
#undef SKY_RESULT_CASE
    default:
        return "VK_RESULT_(unnamed)";
    }
}

void vkCheckFailed(const char* expression, VkResult result, const char* file, int line)
{
    std::fprintf(stderr, "%s:%d: %s returned %s\n", file, line, expression, vkResultName(result));
    std::fflush(stderr);
    std::abort();
}

}  // namespace sky
