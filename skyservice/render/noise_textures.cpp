// SPDX-License-Identifier: MIT
#include "skyservice/render/noise_textures.h"

#include "shaders/shared/noise_params.h"
#include "skyservice/sky/blue_noise.h"

#include <vector>

namespace sky
{
namespace
{

SkyStatus generateNoise(const Context& ctx, MemoryTracker& memory, NoiseTextures& n, uint32_t seed,
                        VkQueryPool timestamps)
{
    OneShot shot;
    SKY_TRY(beginOneShot(ctx, shot));
    vkCmdResetQueryPool(shot.cmd, timestamps, 0, 2);
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
    for (Image* img : {&n.base, &n.detail, &n.curl})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    NoisePush push = {seed, BASE_NOISE_SIZE, 0, 0};
    dispatch(ctx, shot.cmd, n.baseProgram, BASE_NOISE_SIZE, BASE_NOISE_SIZE, BASE_NOISE_SIZE, push,
             {DescriptorInfo(n.base)});
    push.sizeTexels = DETAIL_NOISE_SIZE;
    dispatch(ctx, shot.cmd, n.detailProgram, DETAIL_NOISE_SIZE, DETAIL_NOISE_SIZE, DETAIL_NOISE_SIZE, push,
             {DescriptorInfo(n.detail)});
    push.sizeTexels = CURL_NOISE_SIZE;
    dispatch(ctx, shot.cmd, n.curlProgram, CURL_NOISE_SIZE, CURL_NOISE_SIZE, 1, push, {DescriptorInfo(n.curl)});
    computeBarrier(shot.cmd);
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
    SKY_TRY(endOneShot(ctx, shot));
    uint64_t ts[2] = {0, 0};
    if (ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(ctx.device, timestamps, 0, 2, sizeof ts, ts, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT) ==
            VK_SUCCESS)
        n.startupMs = double(ts[1] - ts[0]) * ctx.timestampPeriodNs * 1e-6;

    std::vector<uint8_t> blue = makeBlueNoise(BLUE_NOISE_SIZE, seed);
    return uploadImage(ctx, memory, n.blue, blue.data(), blue.size(), VK_IMAGE_LAYOUT_GENERAL);
}

}  // namespace

SkyStatus createNoiseTextures(const Context& ctx, MemoryTracker& memory, NoiseTextures& n, uint32_t seed,
                              VkQueryPool timestamps)
{
    SKY_TRY(createProgram(ctx, n.baseProgram, "base_noise"));
    SKY_TRY(createProgram(ctx, n.detailProgram, "detail_noise"));
    SKY_TRY(createProgram(ctx, n.curlProgram, "curl_noise"));
    ImageDesc d;
    d.viewType = VK_IMAGE_VIEW_TYPE_3D;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = d.height = d.depth = BASE_NOISE_SIZE;
    SKY_TRY(createImage(ctx, memory, n.base, d, "base noise 128^3"));
    d.width = d.height = d.depth = DETAIL_NOISE_SIZE;
    SKY_TRY(createImage(ctx, memory, n.detail, d, "detail noise 32^3"));
    d = ImageDesc{};
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.width = d.height = CURL_NOISE_SIZE;
    SKY_TRY(createImage(ctx, memory, n.curl, d, "curl noise"));
    d.format = VK_FORMAT_R8_UNORM;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    d.width = d.height = BLUE_NOISE_SIZE;
    SKY_TRY(createImage(ctx, memory, n.blue, d, "blue noise"));
    return generateNoise(ctx, memory, n, seed, timestamps);
}

void destroyNoiseTextures(const Context& ctx, MemoryTracker& memory, NoiseTextures& n)
{
    for (Image* img : {&n.base, &n.detail, &n.curl, &n.blue})
        destroyImage(ctx, memory, *img);
    for (Program* p : {&n.baseProgram, &n.detailProgram, &n.curlProgram})
        destroyProgram(ctx, *p);
}

}  // namespace sky
