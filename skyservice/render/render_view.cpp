// SPDX-License-Identifier: MIT
// One view from request to pixels: the CPU setup (camera, sun and moon, weather window, lighting, frame
// uniforms), the recording and submission into a frame context (frame_context.h), and the collection once
// the GPU is done. renderView does both halves; the service calls them apart to keep frames in flight.
#include "skyservice/render/renderer.h"

#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/render/frame_recording.h"
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/shadow_map.h"
#include "skyservice/render/view_frustum.h"
#include "skyservice/render/view_validation.h"
#include "skyservice/render/window_upload.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

namespace sky
{
namespace
{

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

/// The CPU half of a view: everything the frame's uniforms and passes are made from. `in` points into
/// this struct and at the caller's request and quality: it is neither copied nor moved. `params` is
/// made from `in` for each frame submitted (makeFrameParams).
struct PreparedView
{
    CameraFrame camera;
    SunMoon sunMoon;
    FrameInputs in;
    LightingEstimate light;
    FrameParams params{};
    PreparedView() = default;
    PreparedView(const PreparedView&) = delete;
    PreparedView& operator=(const PreparedView&) = delete;
};

SkyStatus prepareView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, PreparedView& v)
{
    std::string error;
    if (!validateNoisePeriods(quality, error) || !validateShadowMapRequest(request, quality, error))
        return SkyStatus::failure(error, VK_ERROR_INITIALIZATION_FAILED);
    v.camera = computeCameraFrame(request.pose);
    v.sunMoon = computeSunMoon(request.unixTimeS, v.camera.eye.latDeg, v.camera.eye.lonDeg, v.camera.eye.altitudeM);
    SKY_TRY(updateWeatherWindow(r, v.camera, quality));  // swaps a staged weather in when it is ready
    const WeatherWindow& window = r.weather.window->window;
    const EyeOnWindow eyeOnWindow =
        placeEyeOnWindow(window.centreLatDeg, window.centreLonDeg, v.camera.eye.latDeg, v.camera.eye.lonDeg);
    const FrameOutputs outputs = FrameOutputs::of(request);
    if (quality.reprojected)
        r.reconstruct.reprojection.block =
            chooseMarchBlock(window, v.camera.eye.altitudeM, eyeOnWindow.offsetM, r.tuning.insideCloudBlockPx);
    SKY_TRY(prepareFrameImages(r, request, quality, outputs));

    FrameInputs& in = v.in;
    in.camera = &v.camera;
    in.sunMoon = &v.sunMoon;
    in.window = &window;
    in.summary = &r.weather.window->summary;
    in.eyeOnWindow = eyeOnWindow;
    in.request = &request;
    in.quality = &quality;
    in.tuning = &r.tuning;
    in.animationTimeS = double(request.unixTimeS - r.weather.snapshot->validTimeUnixS) +
                        std::clamp(request.unixTimeFractionS, 0.0, 1.0);
    {
        // The drift frame is anchored at the weather grid's centre: the same on every machine and for
        // every eye position (multi-channel seams, no sliding when flying).
        const LatLonGrid& g = r.weather.snapshot->grid;
        EyePose anchor;
        anchor.latDeg = std::clamp(g.lat0Deg + 0.5 * g.dLatDeg * double(g.nLat > 0 ? g.nLat - 1 : 0), -90.0, 90.0);
        anchor.lonDeg = g.lon0Deg + 0.5 * g.dLonDeg * double(g.nLon > 0 ? g.nLon - 1 : 0);
        in.driftEnuToEcef = computeCameraFrame(anchor).enuToEcef;
    }
    v.light = estimateLighting(r.atmosphere, v.camera, v.sunMoon, r.weather.window->summary);
    // Pre-exposure: every light source is scaled by the exposure before it reaches the GPU, so that the
    // half-float images hold values near 1 by day and by moonlight alike (a full-moon sky is ~1e-7
    // W m^-2 sr^-1 nm^-1, below half precision). Linear outputs are divided by `exposure` for absolute units.
    in.sunIrradiance = v.light.sunIrradiance * v.light.exposure;
    in.ambientSkyRadiance = v.light.ambientSkyRadiance * v.light.exposure;
    in.groundIrradiance = v.light.groundIrradiance * v.light.exposure;
    in.groundAlbedo = v.light.groundAlbedo;
    in.exposure = 1.0;
    in.outputs = outputs;
    if (quality.reprojected)
    {
        std::string why;
        const bool useHistory = historyUsable(r.reconstruct.reprojection, request, v.camera, why);
        r.reconstruct.reprojection.lastDropReason = useHistory ? "" : why;
        r.reconstruct.reprojection.newLines =
            useHistory ? findNewLines(r.reconstruct.reprojection, request, v.camera) : NewLines{};
        in.reprojection = reprojectionParams(r.reconstruct.reprojection, request, v.camera, useHistory);
    }
    return SkyStatus::success();
}

void forgetGpuCaches(Renderer& r)
{
    forgetAtmosphereLuts(r.atmosphere);  // the LUTs recorded for a failed frame may never have been computed
    r.lightVolume.key.valid = false;     // nor the light volume
}

// Records and submits frame `k` of `frames` (accumulation) into the next frame context.
SkyStatus submitPrepared(Renderer& r, PreparedView& v, const ViewRequest& request, const QualitySettings& quality,
                         uint32_t k, uint32_t frames, FrameTicket& ticket)
{
    v.in.accumulationIndex = k;
    v.in.accumulationFrames = frames;
    v.params = makeFrameParams(v.in);

    r.currentFrame = (r.currentFrame + 1) % kFramesInFlight;
    FrameContext& frame = recording(r);
    const bool shadow = request.shadowMap && k + 1 == frames;  // once, after the last accumulated frame
    // The ticket keeps the frame's one copy of the request (the caller's may be gone before finishView),
    // as this frame records it: with the shadow map only on the last accumulated frame.
    ticket = FrameTicket{};
    ticket.request = request;
    ticket.request.shadowMap = shadow;
    SkyStatus status = beginFrameCommands(r.ctx, r.memory, frame, frameReadbackBytes(r, ticket.request));
    if (!status.ok())
        return status;
    std::memcpy(frame.frameUniforms.mapped, &v.params, sizeof v.params);

    ticket.context = r.currentFrame;
    ticket.reprojected = quality.reprojected;
    ticket.lightVolume = v.params.lightVolume.nearCascade.texelM > 0.0f;
    if (shadow)
        ticket.shadow.transmittance = reserveShadowMapReadback(r.shadowPass, frame, request);  // first: a fixed offset
    recordFrame(r, frame, request, v.camera, v.sunMoon, v.in, v.params, ticket.plan, ticket.facts);
    if (shadow)
        recordFrameShadowMap(r, frame, request, quality, v.camera, v.sunMoon, ticket.shadow, ticket.facts);
    recordReadbacks(frame);
    status = submitFrameCommands(r.ctx, frame);
    if (!status.ok())
        return status;
    r.newImages.clear();  // initialized by this frame
    ticket.pending = true;
    return SkyStatus::success();
}

// What a frame's result says besides its pixels and GPU times.
void fillFacts(const Renderer& r, const PreparedView& v, const ViewRequest& request, const QualitySettings& quality,
               RenderResult& facts)
{
    facts.width = request.width;
    facts.height = request.height;
    facts.sunAzimuthDeg = v.sunMoon.sun.azimuthDeg;
    facts.sunElevationDeg = v.sunMoon.sun.elevationDeg;
    facts.moonAzimuthDeg = v.sunMoon.moon.azimuthDeg;
    facts.moonElevationDeg = v.sunMoon.moon.elevationDeg;
    facts.moonIlluminatedFraction = v.sunMoon.moonIlluminatedFraction;
    facts.exposure = v.light.exposure;
    facts.moonIsKeyLight = moonIsKeyLight(v.sunMoon);
    facts.weatherVersion = r.weather.version;
    facts.weatherValidTimeUnixS = r.weather.snapshot->validTimeUnixS;
    facts.marchBlockPx = quality.reprojected ? r.reconstruct.reprojection.block.blockPx : 1u;
    facts.marchBlockReason = quality.reprojected ? r.reconstruct.reprojection.block.reason : "";
}

// The reprojection history after a reprojected frame was submitted: the next frame reprojects this one.
void advanceHistory(Renderer& r, const ViewRequest& request, const CameraFrame& camera)
{
    ReprojectionHistory& h = r.reconstruct.reprojection;
    h.valid = true;
    h.current ^= 1u;
    h.frameIndex++;
    h.lastView = request;
    h.lastCamera = camera;
}

}  // namespace

SkyStatus submitView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, FrameTicket& ticket)
{
    auto cpuStart = std::chrono::steady_clock::now();
    PreparedView v;
    SKY_TRY(prepareView(r, request, quality, v));
    const double setupMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();
    SkyStatus status = submitPrepared(r, v, request, quality, 0, 1, ticket);
    if (!status.ok())
    {
        forgetGpuCaches(r);
        return status;
    }
    ticket.facts.cpuSetupMs = setupMs;
    fillFacts(r, v, request, quality, ticket.facts);
    if (quality.reprojected)
        advanceHistory(r, request, v.camera);
    return SkyStatus::success();
}

SkyStatus finishView(Renderer& r, FrameTicket& ticket, RenderResult& result, bool copyPixels)
{
    if (!ticket.pending)
        return SkyStatus::failure("finishView: no frame pending", VK_ERROR_INITIALIZATION_FAILED);
    ticket.pending = false;
    FrameContext& frame = r.frames[ticket.context];
    SkyStatus status = waitFrameCommands(r.ctx, frame);
    if (!status.ok())
    {
        forgetGpuCaches(r);
        return status;
    }
    // The facts move in; the pixel vectors keep their capacity (copied into, not reallocated).
    std::swap(result.marchRowOrder, ticket.facts.marchRowOrder);
    result.width = ticket.facts.width;
    result.height = ticket.facts.height;
    result.cpuSetupMs = ticket.facts.cpuSetupMs;
    result.sunAzimuthDeg = ticket.facts.sunAzimuthDeg;
    result.sunElevationDeg = ticket.facts.sunElevationDeg;
    result.moonAzimuthDeg = ticket.facts.moonAzimuthDeg;
    result.moonElevationDeg = ticket.facts.moonElevationDeg;
    result.moonIlluminatedFraction = ticket.facts.moonIlluminatedFraction;
    result.exposure = ticket.facts.exposure;
    result.moonIsKeyLight = ticket.facts.moonIsKeyLight;
    result.weatherVersion = ticket.facts.weatherVersion;
    result.weatherValidTimeUnixS = ticket.facts.weatherValidTimeUnixS;
    result.marchBlockPx = ticket.facts.marchBlockPx;
    result.marchBlockReason = ticket.facts.marchBlockReason;
    result.shadowMapSize = ticket.shadow.recorded ? ticket.facts.shadowMapSize : 0;
    result.shadowMap = ticket.shadow.recorded ? std::move(ticket.facts.shadowMap) : nlohmann::json();
    result.shadowReference = ticket.facts.shadowReference;
    result.shadowMapId = ticket.shadow.recorded ? ticket.facts.shadowMapId : 0;
    result.shadowMapRedrawn = ticket.shadow.recorded && ticket.shadow.redrawn;
    result.gpuMs.clear();
    collectFrame(r, frame, ticket.request, ticket.reprojected, ticket.lightVolume,
                 copyPixels ? ticket.plan : FrameReadbackPlan{}, result);
    if (ticket.shadow.recorded)
    {
        ShadowMapReadback regions = ticket.shadow;
        if (!copyPixels)
            regions.transmittance = regions.detail = ReadbackRegion{};  // the caller reads mappedFrame
        collectShadowMap(r.ctx, frame, regions, result);
    }
    else
    {
        result.shadowTransmittance.clear();
        result.shadowOpticalDepth.clear();
    }
    return SkyStatus::success();
}

MappedFrame mappedFrame(const Renderer& r, const FrameTicket& ticket)
{
    const FrameContext& frame = r.frames[ticket.context];
    const auto* base = static_cast<const uint8_t*>(frame.readback.mapped);
    auto at = [&](const ReadbackRegion& region) { return region.bytes ? base + region.offset : nullptr; };
    MappedFrame m;
    m.displayRgba8 = at(ticket.plan.display);
    m.skyRgbaHalf = reinterpret_cast<const uint16_t*>(at(ticket.plan.sky));
    m.cloudLayerRgbaHalf = reinterpret_cast<const uint16_t*>(at(ticket.plan.cloudLayer));
    m.cloudDepthM = reinterpret_cast<const float*>(at(ticket.plan.depth));
    m.depthLayerM = reinterpret_cast<const float*>(at(ticket.plan.depthLayer));
    m.shadowTransmittance = reinterpret_cast<const float*>(at(ticket.shadow.transmittance));
    return m;
}

SkyStatus renderView(Renderer& r, const ViewRequest& request, const QualitySettings& quality, RenderResult& result)
{
    // The entry point of callers that draw directly; submitView's caller validated its views (view_validation.h).
    if (std::string error; !validateView(request, error))
        return SkyStatus::failure(error, VK_ERROR_INITIALIZATION_FAILED);
    const uint32_t frames = quality.reprojected ? 1u : std::max(1u, quality.accumulationFrames);
    FrameTicket ticket;
    if (frames == 1)
    {
        SKY_TRY(submitView(r, request, quality, ticket));
        return finishView(r, ticket, result);
    }

    // Accumulation (offline quality): the frames one after the other, averaged on the host.
    auto cpuStart = std::chrono::steady_clock::now();
    PreparedView v;
    SKY_TRY(prepareView(r, request, quality, v));
    const double setupMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();
    std::map<std::string, double> gpuMs;
    std::vector<double> cloudSum, linearSum, displaySum, depthSum, depthWeight, skySum, layerSum, depthLayerSum;
    RenderResult one;
    for (uint32_t k = 0; k < frames; ++k)
    {
        SkyStatus status = submitPrepared(r, v, request, quality, k, frames, ticket);
        if (!status.ok())
        {
            forgetGpuCaches(r);
            return status;
        }
        SKY_TRY(finishView(r, ticket, one));
        for (const auto& [pass, ms] : one.gpuMs)
            gpuMs[pass] += ms / frames;
        accumulate(one.cloudRgbaHalf, cloudSum);
        accumulate(one.linearRgbaHalf, linearSum);
        accumulate(one.skyRgbaHalf, skySum);
        accumulate(one.cloudLayerRgbaHalf, layerSum);
        displaySum.resize(one.displayRgba8.size());
        for (size_t i = 0; i < one.displayRgba8.size(); ++i)
            displaySum[i] += one.displayRgba8[i];
        depthSum.resize(one.cloudDepthM.size());
        depthWeight.resize(one.cloudDepthM.size());
        for (size_t i = 0; i < one.cloudDepthM.size(); ++i)
        {
            const double a = one.cloudRgbaHalf.empty() ? 1.0 : double(glm::unpackHalf1x16(one.cloudRgbaHalf[i * 4 + 3]));
            depthSum[i] += a * double(one.cloudDepthM[i]);
            depthWeight[i] += a;
        }
        // The depth layer's two distances are averaged like the depth, weighted by alpha.
        depthLayerSum.resize(one.depthLayerM.size());
        for (size_t i = 0; i < one.depthLayerM.size(); ++i)
        {
            const double a = one.cloudRgbaHalf.empty() ? 1.0 : double(glm::unpackHalf1x16(one.cloudRgbaHalf[i / 2 * 4 + 3]));
            depthLayerSum[i] += a * double(one.depthLayerM[i]);
        }
    }
    result = std::move(one);  // the last frame's facts, march order and shadow map
    result.cpuSetupMs = setupMs;
    result.gpuMs = std::move(gpuMs);
    fillFacts(r, v, request, quality, result);
    result.cloudRgbaHalf = average(cloudSum, frames);
    result.linearRgbaHalf = average(linearSum, frames);
    result.skyRgbaHalf = average(skySum, frames);
    result.cloudLayerRgbaHalf = average(layerSum, frames);
    result.displayRgba8.resize(displaySum.size());
    for (size_t i = 0; i < displaySum.size(); ++i)
        result.displayRgba8[i] = uint8_t(std::lround(displaySum[i] / frames));
    result.cloudDepthM.resize(depthSum.size());
    for (size_t i = 0; i < depthSum.size(); ++i)
        result.cloudDepthM[i] = depthWeight[i] > 1e-6 ? float(depthSum[i] / depthWeight[i]) : 0.0f;
    if (depthWeight.size() * 2 == depthLayerSum.size())
        for (size_t i = 0; i < depthLayerSum.size(); ++i)
            result.depthLayerM[i] = depthWeight[i / 2] > 1e-6 ? float(depthLayerSum[i] / depthWeight[i / 2]) : 0.0f;
    return SkyStatus::success();
}

}  // namespace sky
