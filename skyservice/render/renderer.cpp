// SPDX-License-Identifier: MIT
#include "skyservice/render/renderer.h"

#include "shaders/shared/frame_params.h"
#include "shaders/shared/noise_params.h"
#include "shaders/shared/weather_window.h"
#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/render/column_bounds.h"
#include "skyservice/render/frame_images.h"
#include "skyservice/render/frame_recording.h"
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/light_volume.h"
#include "skyservice/render/shadow_map.h"
#include "skyservice/render/window_upload.h"
#include "skyservice/sky/blue_noise.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/packing.hpp>
#include <cstring>

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

SkyStatus generateNoise(Renderer& r, uint32_t seed)
{
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    vkCmdResetQueryPool(shot.cmd, recording(r).timestamps, 0, 2);
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, recording(r).timestamps, 0);
    for (Image* img : {&r.baseNoise, &r.detailNoise, &r.curlNoise, &r.linearStandIn, &r.historyStandIn, &r.depthStandIn, &r.lightVolume,
                        &r.lightVolumeFar})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    NoisePush push = {seed, BASE_NOISE_SIZE, 0, 0};
    dispatch(r.ctx, shot.cmd, r.baseNoiseProgram, BASE_NOISE_SIZE, BASE_NOISE_SIZE, BASE_NOISE_SIZE, push,
             {DescriptorInfo(r.baseNoise)});
    push.sizeTexels = DETAIL_NOISE_SIZE;
    dispatch(r.ctx, shot.cmd, r.detailNoiseProgram, DETAIL_NOISE_SIZE, DETAIL_NOISE_SIZE, DETAIL_NOISE_SIZE, push,
             {DescriptorInfo(r.detailNoise)});
    push.sizeTexels = CURL_NOISE_SIZE;
    dispatch(r.ctx, shot.cmd, r.curlNoiseProgram, CURL_NOISE_SIZE, CURL_NOISE_SIZE, 1, push,
             {DescriptorInfo(r.curlNoise)});
    computeBarrier(shot.cmd);
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, recording(r).timestamps, 1);
    SKY_TRY(endOneShot(r.ctx, shot));
    uint64_t ts[2] = {0, 0};
    if (r.ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(r.ctx.device, recording(r).timestamps, 0, 2, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
        r.noiseStartupMs = double(ts[1] - ts[0]) * r.ctx.timestampPeriodNs * 1e-6;

    std::vector<uint8_t> blue = makeBlueNoise(BLUE_NOISE_SIZE, seed);
    return uploadImage(r.ctx, r.memory, r.blueNoise, blue.data(), blue.size(), VK_IMAGE_LAYOUT_GENERAL);
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

    const std::pair<Program*, const char*> programs[] = {
        {&r.baseNoiseProgram, "base_noise"},     {&r.detailNoiseProgram, "detail_noise"},
        {&r.curlNoiseProgram, "curl_noise"},     {&r.transmittanceProgram, "transmittance_lut"},
        {&r.multiscatterProgram, "multiscatter_lut"}, {&r.skyViewProgram, "sky_view_lut"},
        {&r.aerialPerspectiveProgram, "aerial_perspective_lut"},
        {&r.cloudProgram, "cloud_march"},        {&r.compositeProgram, "composite"},
        {&r.reconstructProgram, "reconstruct"},  {&r.lightVolumeProgram, "light_volume"},
    };
    for (const auto& [program, name] : programs)
        SKY_TRY(createProgram(r.ctx, *program, name));
    SKY_TRY(createShadowMapPass(r.ctx, r.shadowPass));

    ImageDesc d;
    d.viewType = VK_IMAGE_VIEW_TYPE_3D;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = d.height = d.depth = BASE_NOISE_SIZE;
    SKY_TRY(createImage(r.ctx, r.memory, r.baseNoise, d, "base noise 128^3"));
    d.width = d.height = d.depth = DETAIL_NOISE_SIZE;
    SKY_TRY(createImage(r.ctx, r.memory, r.detailNoise, d, "detail noise 32^3"));
    d = ImageDesc{};
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.width = d.height = CURL_NOISE_SIZE;
    SKY_TRY(createImage(r.ctx, r.memory, r.curlNoise, d, "curl noise"));
    d.format = VK_FORMAT_R8_UNORM;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    d.width = d.height = BLUE_NOISE_SIZE;
    SKY_TRY(createImage(r.ctx, r.memory, r.blueNoise, d, "blue noise"));
    d = ImageDesc{};
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
    d = ImageDesc{};
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    SKY_TRY(createImage(r.ctx, r.memory, r.linearStandIn, d, "linear frame stand-in (1x1)"));
    d.format = VK_FORMAT_R16G16B16A16_UINT;
    SKY_TRY(createImage(r.ctx, r.memory, r.historyStandIn, d, "cloud history stand-in (1x1)"));
    d.format = VK_FORMAT_R32_SFLOAT;
    SKY_TRY(createImage(r.ctx, r.memory, r.depthStandIn, d, "cloud depth stand-in (1x1)"));

    SKY_TRY(createAtmosphereResources(r));
    SKY_TRY(createLightVolume(r));
    SKY_TRY(createMarchOrder(r.ctx, r.memory, r.marchOrder));
    r.marchDispatchRanges = dispatchRanges(r.ctx);
    SKY_TRY(generateNoise(r, options.noiseSeed));
    return SkyStatus::success();
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
    for (Image* img : {&r.baseNoise, &r.detailNoise, &r.curlNoise, &r.blueNoise, &r.transmittanceLut,
                       &r.multiscatterLut, &r.skyViewLut, &r.aerialInscatterLut, &r.aerialTransmittanceLut, &r.weatherWindowImage, &r.columnBoundsImage, &r.lightVolume, &r.lightVolumeFar, &r.cloudImage, &r.depthImage,
                       &r.linearImage, &r.displayImage, &r.freshCloudImage, &r.freshDepthImage, &r.history[0],
                       &r.history[1], &r.linearStandIn, &r.historyStandIn, &r.depthStandIn, &r.skyImage, &r.cloudLayerImage})
        destroyImage(r.ctx, r.memory, *img);
    destroyShadowMapPass(r.ctx, r.memory, r.shadowPass);
    destroyMarchOrder(r.ctx, r.memory, r.marchOrder);
    for (Program* p : {&r.baseNoiseProgram, &r.detailNoiseProgram, &r.curlNoiseProgram, &r.transmittanceProgram,
                       &r.multiscatterProgram, &r.skyViewProgram, &r.aerialPerspectiveProgram, &r.cloudProgram, &r.compositeProgram,
                       &r.reconstructProgram, &r.lightVolumeProgram})
        destroyProgram(r.ctx, *p);
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

void dropHistory(Renderer& r) { r.reprojection.valid = false; }

const std::string& lastHistoryDropReason(const Renderer& r) { return r.reprojection.lastDropReason; }

}  // namespace sky
