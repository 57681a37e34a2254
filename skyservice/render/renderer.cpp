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
    vkCmdResetQueryPool(shot.cmd, r.timestamps, 0, kTsCount);
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r.timestamps, 0);
    for (Image* img : {&r.baseNoise, &r.detailNoise, &r.curlNoise, &r.linearStandIn, &r.historyStandIn, &r.lightVolume,
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
    vkCmdWriteTimestamp(shot.cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, r.timestamps, 1);
    SKY_TRY(endOneShot(r.ctx, shot));
    uint64_t ts[2] = {0, 0};
    if (r.ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(r.ctx.device, r.timestamps, 0, 2, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
        r.noiseStartupMs = double(ts[1] - ts[0]) * r.ctx.timestampPeriodNs * 1e-6;

    std::vector<uint8_t> blue = makeBlueNoise(BLUE_NOISE_SIZE, seed);
    return uploadImage(r.ctx, r.memory, r.blueNoise, blue.data(), blue.size(), VK_IMAGE_LAYOUT_GENERAL);
}

SkyStatus checkRequest(const ViewRequest& req)
{
    std::string error;
    if (!validateEyePose(req.pose, error))
        return SkyStatus::failure(error, VK_ERROR_INITIALIZATION_FAILED);
    if (req.width < 8 || req.height < 8 || req.width > 8192 || req.height > 8192)
        return SkyStatus::failure("image size " + std::to_string(req.width) + "x" + std::to_string(req.height) +
                                      " outside 8..8192",
                                  VK_ERROR_INITIALIZATION_FAILED);
    if (!(req.fovYDeg > 1.0 && req.fovYDeg < 170.0))
        return SkyStatus::failure("vertical field of view " + std::to_string(req.fovYDeg) + " outside (1, 170) degrees",
                                  VK_ERROR_INITIALIZATION_FAILED);
    return SkyStatus::success();
}

double halton(uint32_t index, uint32_t base)
{
    double f = 1.0, r = 0.0;
    for (uint32_t i = index; i > 0; i /= base)
    {
        f /= base;
        r += f * double(i % base);
    }
    return r;
}

void accumulate(const std::vector<uint16_t>& halves, std::vector<double>& sum)
{
    sum.resize(halves.size());
    for (size_t i = 0; i < halves.size(); ++i)
        sum[i] += double(glm::unpackHalf1x16(halves[i]));
}

std::vector<uint16_t> average(const std::vector<double>& sum, uint32_t frames)
{
    std::vector<uint16_t> out(sum.size());
    for (size_t i = 0; i < sum.size(); ++i)
        out[i] = glm::packHalf1x16(float(sum[i] / frames));
    return out;
}

}  // namespace

SkyStatus createRenderer(Renderer& r, const RendererOptions& options)
{
    SKY_TRY(createContext(r.ctx, options.context));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, r.linearRepeat));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, r.linearClamp));
    SKY_TRY(createSampler(r.ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_REPEAT, r.nearestRepeat));

    VkQueryPoolCreateInfo queryInfo = {VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = kTsCount;
    VK_TRY(vkCreateQueryPool(r.ctx.device, &queryInfo, nullptr, &r.timestamps));

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

    // Usable as uniform and as storage buffer: the shaders read the parameters from uniform buffers, or
    // from storage buffers on lavapipe (shaders/shared/bindings.h PARAMS_BLOCK): with uniform buffers
    // bound through push descriptors, lavapipe (Mesa 22.3.6) grew the service's resident memory by
    // ~0.5 MB per frame (tests/service ServiceSoak, SKY_SOAK_VERBOSE=1: 232 MB to 930 MB over 1500
    // frames); with storage buffers it is flat to the kB. Both variants use std140: the same layout.
    SKY_TRY(createBuffer(r.ctx, r.memory, r.frameUniforms, sizeof(FrameParams),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                         MemoryUse::HostVisible, "frame uniforms"));
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
    for (Image* img : {&r.baseNoise, &r.detailNoise, &r.curlNoise, &r.blueNoise, &r.transmittanceLut,
                       &r.multiscatterLut, &r.skyViewLut, &r.aerialInscatterLut, &r.aerialTransmittanceLut, &r.weatherWindowImage, &r.columnBoundsImage, &r.lightVolume, &r.lightVolumeFar, &r.cloudImage, &r.depthImage,
                       &r.linearImage, &r.displayImage, &r.freshCloudImage, &r.freshDepthImage, &r.history[0],
                       &r.history[1], &r.linearStandIn, &r.historyStandIn})
        destroyImage(r.ctx, r.memory, *img);
    destroyShadowMapPass(r.ctx, r.memory, r.shadowPass);
    destroyBuffer(r.ctx, r.memory, r.frameUniforms);
    destroyMarchOrder(r.ctx, r.memory, r.marchOrder);
    destroyBuffer(r.ctx, r.memory, r.atmosphereUniforms);
    for (Program* p : {&r.baseNoiseProgram, &r.detailNoiseProgram, &r.curlNoiseProgram, &r.transmittanceProgram,
                       &r.multiscatterProgram, &r.skyViewProgram, &r.aerialPerspectiveProgram, &r.cloudProgram, &r.compositeProgram,
                       &r.reconstructProgram, &r.lightVolumeProgram})
        destroyProgram(r.ctx, *p);
    for (VkSampler* s : {&r.linearRepeat, &r.linearClamp, &r.nearestRepeat})
        if (*s)
            vkDestroySampler(r.ctx.device, *s, nullptr), *s = VK_NULL_HANDLE;
    if (r.timestamps)
        vkDestroyQueryPool(r.ctx.device, r.timestamps, nullptr);
    r.timestamps = VK_NULL_HANDLE;
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

SkyStatus renderView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, RenderResult& result)
{
    SKY_TRY(checkRequest(request));
    std::string error;
    if (!validateNoisePeriods(quality, error) || !validateShadowMapRequest(request, quality, error))
        return SkyStatus::failure(error, VK_ERROR_INITIALIZATION_FAILED);
    auto cpuStart = std::chrono::steady_clock::now();

    CameraFrame camera = computeCameraFrame(request.pose);
    SunMoon sunMoon = computeSunMoon(request.unixTimeS, camera.eye.latDeg, camera.eye.lonDeg, camera.eye.altitudeM);
    SKY_TRY(updateWeatherWindow(r, camera, quality));  // swaps a staged weather in when it is ready
    const WeatherWindow& window = r.window->window;
    const EyeOnWindow eyeOnWindow =
        placeEyeOnWindow(window.centreLatDeg, window.centreLonDeg, camera.eye.latDeg, camera.eye.lonDeg);
    SKY_TRY(ensureOutputImages(r, request.width, request.height, !quality.reprojected, quality.linearOutput));
    if (quality.reprojected)
    {
        r.reprojection.block =
            chooseMarchBlock(window, camera.eye.altitudeM, eyeOnWindow.offsetM, quality.insideCloudBlockPx);
        SKY_TRY(ensureReprojectionImages(r, request.width, request.height, r.reprojection.block.blockPx));
    }

    FrameInputs in;
    in.camera = &camera;
    in.sunMoon = &sunMoon;
    in.window = &window;
    in.summary = &r.window->summary;
    in.eyeOnWindow = eyeOnWindow;
    in.request = &request;
    in.quality = &quality;
    in.animationTimeS = double(request.unixTimeS - r.weather->validTimeUnixS);
    {
        // The drift frame is anchored at the weather grid's centre: the same on every machine and for
        // every eye position (multi-channel seams, no sliding when flying).
        const LatLonGrid& g = r.weather->grid;
        EyePose anchor;
        anchor.latDeg = std::clamp(g.lat0Deg + 0.5 * g.dLatDeg * double(g.nLat > 0 ? g.nLat - 1 : 0), -90.0, 90.0);
        anchor.lonDeg = g.lon0Deg + 0.5 * g.dLonDeg * double(g.nLon > 0 ? g.nLon - 1 : 0);
        in.driftEnuToEcef = computeCameraFrame(anchor).enuToEcef;
    }
    LightingEstimate light = estimateLighting(r, camera, sunMoon, r.window->summary);
    // Pre-exposure: every light source is scaled by the exposure before it reaches the GPU, so that the
    // half-float images hold values near 1 by day and by moonlight alike (a full-moon sky is ~1e-7
    // W m^-2 sr^-1 nm^-1, below half precision). Linear outputs are divided by `exposure` for absolute units.
    in.sunIrradiance = light.sunIrradiance * light.exposure;
    in.ambientSkyRadiance = light.ambientSkyRadiance * light.exposure;
    in.groundIrradiance = light.groundIrradiance * light.exposure;
    in.groundAlbedo = light.groundAlbedo;
    in.exposure = 1.0;
    FrameParams params = makeFrameParams(in);
    bool useHistory = false;
    if (quality.reprojected)
    {
        std::string why;
        useHistory = historyUsable(r.reprojection, request, camera, why);
        r.reprojection.lastDropReason = useHistory ? "" : why;
        fillReprojectionParams(params, r.reprojection, request, camera, useHistory);
    }
    placeLightVolume(quality, params);  // after the march block is known: it counts the rays
    result.cpuSetupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();

    // Accumulation: each frame has new march jitter (frame index) and a sub-pixel offset (Halton 2,3);
    // the frames are averaged on the host. One frame is the plain render.
    // Reprojected frames keep the march jitter of frame 0 (image.z): a pixel marched again gives the same
    // value, so a still view converges to exactly the full-resolution image.
    uint32_t frames = quality.reprojected ? 1u : std::max(1u, quality.accumulationFrames);
    result.gpuMs.clear();
    result.width = request.width;
    result.height = request.height;
    std::vector<double> cloudSum, linearSum, displaySum, depthSum, depthWeight;
    for (uint32_t k = 0; k < frames; ++k)
    {
        params.image.z = k;
        params.exposure.z = frames > 1 ? float(halton(k + 1, 2) - 0.5) : 0.0f;
        params.exposure.w = frames > 1 ? float(halton(k + 1, 3) - 0.5) : 0.0f;
        std::memcpy(r.frameUniforms.mapped, &params, sizeof params);
        RenderResult one;
        SkyStatus status = renderOnce(r, request, camera, sunMoon, in, params, one);
        if (!status.ok())
        {
            r.atmosphereRadiusM = 0;  // the LUTs recorded for this frame may never have been computed
            r.lightVolumeKey.valid = false;  // nor the light volume
            r.skyViewInputsValid = false;
            return status;
        }
        for (const auto& [pass, ms] : one.gpuMs)
            result.gpuMs[pass] += ms / frames;
        result.marchRowOrder = std::move(one.marchRowOrder);  // the last frame's
        result.marchRowLookups = std::move(one.marchRowLookups);
        accumulate(one.cloudRgbaHalf, cloudSum);
        accumulate(one.linearRgbaHalf, linearSum);
        displaySum.resize(one.displayRgba8.size());
        for (size_t i = 0; i < one.displayRgba8.size(); ++i)
            displaySum[i] += one.displayRgba8[i];
        depthSum.resize(one.cloudDepthM.size());
        depthWeight.resize(one.cloudDepthM.size());
        for (size_t i = 0; i < one.cloudDepthM.size(); ++i)
        {
            double a = glm::unpackHalf1x16(one.cloudRgbaHalf[i * 4 + 3]);
            depthSum[i] += a * double(one.cloudDepthM[i]);
            depthWeight[i] += a;
        }
        if (frames == 1)
        {
            result.cloudRgbaHalf = std::move(one.cloudRgbaHalf);
            result.linearRgbaHalf = std::move(one.linearRgbaHalf);
            result.displayRgba8 = std::move(one.displayRgba8);
            result.cloudDepthM = std::move(one.cloudDepthM);
        }
    }
    if (frames > 1)
    {
        result.cloudRgbaHalf = average(cloudSum, frames);
        result.linearRgbaHalf = average(linearSum, frames);
        result.displayRgba8.resize(displaySum.size());
        for (size_t i = 0; i < displaySum.size(); ++i)
            result.displayRgba8[i] = uint8_t(std::lround(displaySum[i] / frames));
        result.cloudDepthM.resize(depthSum.size());
        for (size_t i = 0; i < depthSum.size(); ++i)
            result.cloudDepthM[i] = depthWeight[i] > 1e-6 ? float(depthSum[i] / depthWeight[i]) : 0.0f;
    }

    if (quality.reprojected)
    {
        ReprojectionHistory& h = r.reprojection;
        h.valid = true;
        h.current ^= 1u;
        h.frameIndex++;
        h.lastView = request;
        h.lastCamera = camera;
    }

    result.sunAzimuthDeg = sunMoon.sun.azimuthDeg;
    result.sunElevationDeg = sunMoon.sun.elevationDeg;
    result.moonAzimuthDeg = sunMoon.moon.azimuthDeg;
    result.moonElevationDeg = sunMoon.moon.elevationDeg;
    result.moonIlluminatedFraction = sunMoon.moonIlluminatedFraction;
    result.exposure = light.exposure;
    result.moonIsKeyLight = moonIsKeyLight(sunMoon);
    result.weatherVersion = r.weatherVersion;
    result.weatherValidTimeUnixS = r.weather->validTimeUnixS;
    result.marchBlockPx = quality.reprojected ? r.reprojection.block.blockPx : 1u;
    result.marchBlockReason = quality.reprojected ? r.reprojection.block.reason : "";
    if (request.shadowMap)
        SKY_TRY(renderShadowMap(r, request, quality, camera, sunMoon, result));
    return SkyStatus::success();
}

}  // namespace sky
