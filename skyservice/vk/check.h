// SPDX-License-Identifier: MIT
// The two error tiers of docs/style.md §5, never compiled out.
//  VK_CHECK(call): the call can fail only through programmer error -> log file:line, expression and
//                  VkResult name, then abort (in every build).
//  VK_TRY(call):   the call can fail at run time (allocation, device lost) -> return a SkyStatus
//                  naming the call and the VkResult to the caller.
#pragma once

#include <string>
#include <vulkan/vulkan.h>

namespace sky
{

/// Name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), for messages.
const char* vkResultName(VkResult result);

/// Outcome of a recoverable operation: ok() or a message that says what failed and why.
struct [[nodiscard]] SkyStatus
{
    VkResult result = VK_SUCCESS;
    std::string message;

    bool ok() const { return message.empty() && result == VK_SUCCESS; }
    static SkyStatus success() { return {}; }
    static SkyStatus failure(std::string text, VkResult r = VK_ERROR_UNKNOWN) { return {r, std::move(text)}; }
};

[[noreturn]] void vkCheckFailed(const char* expression, VkResult result, const char* file, int line);

}  // namespace sky

#define VK_CHECK(call)                                                                                                 \
    do                                                                                                                 \
    {                                                                                                                  \
        VkResult vkCheckResult = (call);                                                                               \
        if (vkCheckResult != VK_SUCCESS)                                                                               \
            ::sky::vkCheckFailed(#call, vkCheckResult, __FILE__, __LINE__);                                            \
    } while (0)

#define VK_TRY(call)                                                                                                   \
    do                                                                                                                 \
    {                                                                                                                  \
        VkResult vkTryResult = (call);                                                                                 \
        if (vkTryResult != VK_SUCCESS)                                                                                 \
            return ::sky::SkyStatus::failure(std::string(#call) + " failed: " + ::sky::vkResultName(vkTryResult),      \
                                             vkTryResult);                                                             \
    } while (0)

#define SKY_TRY(expr)                                                                                                  \
    do                                                                                                                 \
    {                                                                                                                  \
        ::sky::SkyStatus skyTryStatus = (expr);                                                                        \
        if (!skyTryStatus.ok())                                                                                        \
            return skyTryStatus;                                                                                       \
    } while (0)
