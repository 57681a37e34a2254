// SPDX-License-Identifier: MIT
#include "skyservice/render/renderer.h"

#include "shaders/shared/weather_window.h"
#include "skyservice/render/column_bounds.h"


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

SkyStatus createRenderer(Renderer& r, const RendererOptions& options)
{
    SKY_TRY(createContext(r.ctx, options.context));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, r.linearRepeat));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, r.linearClamp));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT, r.nearestRepeat));

    for (uint32_t i = 0; i < kFramesInFlight; ++i)
        SKY_TRY(createFrameContext(r.ctx, r.memory, r.frames[i], i));

    SKY_TRY(createMarchPass(r.ctx, r.memory, r.march));
    SKY_TRY(createReconstructPass(r.ctx, r.reconstruct));
    SKY_TRY(createCompositePass(r.ctx, r.memory, r.composite));
    SKY_TRY(createShadowMapPass(r.ctx, r.shadowPass));

    ImageDesc d;
    d.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;  // window_provider.h says why half floats
    d.width = d.height = WEATHER_WINDOW_SIZE;
    d.layers = WEATHER_GPU_SLICES;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    SKY_TRY(createImage(r.ctx, r.memory, r.weatherWindowImage, d, "weather window"));
    d = ImageDesc{};
    d.format = VK_FORMAT_R8G8_UINT;  // shaders/shared/column_bounds.h
    d.width = columnBoundsWidth(WEATHER_WINDOW_SIZE);
    d.height = WEATHER_WINDOW_SIZE;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    SKY_TRY(createImage(r.ctx, r.memory, r.columnBoundsImage, d, "weather column bounds"));

    SKY_TRY(createAtmospherePass(r.ctx, r.memory, r.atmosphere));
    SKY_TRY(createLightVolumePass(r.ctx, r.memory, r.lightVolume));
    return createNoiseTextures(r.ctx, r.memory, r.noise, options.noiseSeed, recording(r).timestamps);
}

void destroyRenderer(Renderer& r)
{
    if (!r.ctx.device)
    {
        destroyContext(r.ctx);
        return;
    }
    vkDeviceWaitIdle(r.ctx.device);  // shutdown only
    for (FrameContext& frame : r.frames)
        destroyFrameContext(r.ctx, r.memory, frame);
    for (Image* img : {&r.weatherWindowImage, &r.columnBoundsImage})
        destroyImage(r.ctx, r.memory, *img);
    destroyNoiseTextures(r.ctx, r.memory, r.noise);
    destroyAtmospherePass(r.ctx, r.memory, r.atmosphere);
    destroyLightVolumePass(r.ctx, r.memory, r.lightVolume);
    destroyMarchPass(r.ctx, r.memory, r.march);
    destroyReconstructPass(r.ctx, r.memory, r.reconstruct);
    destroyCompositePass(r.ctx, r.memory, r.composite);
    destroyShadowMapPass(r.ctx, r.memory, r.shadowPass);
    for (VkSampler* s : {&r.linearRepeat, &r.linearClamp, &r.nearestRepeat})
        if (*s)
            vkDestroySampler(r.ctx.device, *s, nullptr), *s = VK_NULL_HANDLE;
    destroyContext(r.ctx);
}

void setWeather(Renderer& r, const WeatherSnapshot& snapshot)
{
    r.weather = std::make_shared<const WeatherSnapshot>(snapshot);
    r.weatherVersion = ++r.weatherVersionsIssued;
    cancelStage(r.weatherStage);  // older than this one
    dropHistory(r);  // the previous frame shows other clouds
}

uint64_t stageWeather(Renderer& r, WeatherMaker make, StageSwap swap)
{
    const uint64_t version = ++r.weatherVersionsIssued;
    stage(r.weatherStage, version, std::move(make), swap);
    return version;
}

uint64_t stageWeather(Renderer& r, std::shared_ptr<const WeatherSnapshot> snapshot, StageSwap swap)
{
    return stageWeather(r, [snapshot = std::move(snapshot)] { return snapshot; }, swap);
}

void releaseStagedWeather(Renderer& r) { releaseStage(r.weatherStage); }

void cancelStagedWeather(Renderer& r) { cancelStage(r.weatherStage); }

bool weatherStagePending(const Renderer& r) { return stagePending(r.weatherStage); }

void dropHistory(Renderer& r) { r.reconstruct.reprojection.valid = false; }

const std::string& lastHistoryDropReason(const Renderer& r) { return r.reconstruct.reprojection.lastDropReason; }

}  // namespace sky
