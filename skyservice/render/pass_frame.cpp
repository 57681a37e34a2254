// SPDX-License-Identifier: MIT
#include "skyservice/render/pass_frame.h"

namespace sky
{
namespace
{

SkyStatus createSampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode mode, VkSampler& out)
{
    VkSamplerCreateInfo info = {VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = mode;
    info.addressModeV = mode;
    info.addressModeW = mode;
    info.maxLod = 0.0f;
    VK_TRY(vkCreateSampler(ctx.device, &info, nullptr, &out));
    return SkyStatus::success();
}

}  // namespace

SkyStatus createSamplers(const Context& ctx, Samplers& s)
{
    SKY_TRY(createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, s.linearRepeat));
    SKY_TRY(createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, s.linearClamp));
    return createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT, s.nearestRepeat);
}

void destroySamplers(const Context& ctx, Samplers& s)
{
    for (VkSampler* sampler : {&s.linearRepeat, &s.linearClamp, &s.nearestRepeat})
        if (*sampler)
            vkDestroySampler(ctx.device, *sampler, nullptr), *sampler = VK_NULL_HANDLE;
}

}  // namespace sky
