// SPDX-License-Identifier: MIT
#include "skyservice/weather/window_provider.h"

#include "skyservice/weather/column_bounds.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sky
{

double windowLookAheadM(double speedMps)
{
    if (!std::isfinite(speedMps))
        return kWindowLookAheadMaxM;
    return std::clamp(speedMps * kWindowLookAheadS, kWindowLookAheadMinM, kWindowLookAheadMaxM);
}

double updateEyeSpeedMps(double previousMps, double moveM, double dtS)
{
    if (!(dtS > 0) || !std::isfinite(moveM))
        return previousMps;
    return std::max(moveM / dtS, previousMps * std::exp(-dtS / kEyeSpeedMemoryS));
}

std::optional<WindowCentre> nextWindowNode(const CameraFrame& camera, glm::dvec2 directionEnu, double lookAheadM)
{
    const double length = glm::length(directionEnu);
    if (!(length > 0))
        return std::nullopt;
    const glm::dvec2 unit = directionEnu / length;
    const WindowCentre here = windowCentreForEye(camera.eye.latDeg, camera.eye.lonDeg);
    for (double alongM = kNextNodeStepM; alongM <= lookAheadM + 0.5 * kNextNodeStepM; alongM += kNextNodeStepM)
    {
        double latDeg = 0, lonDeg = 0, hM = 0;
        enuToGeodetic(camera, glm::dvec3(unit * std::min(alongM, lookAheadM), 0.0), latDeg, lonDeg, hM);
        WindowCentre c = windowCentreForEye(latDeg, lonDeg);
        if (!(c == here))
            return c;
    }
    return std::nullopt;
}

std::shared_ptr<const PreparedWindow> prepareWindow(const WeatherSnapshot& weather, const WindowKey& key)
{
    auto out = std::make_shared<PreparedWindow>();
    out->key = key;
    resampleWeatherWindow(weather, key.centre.latDeg, key.centre.lonDeg, key.halfExtentM, out->window,
                          WEATHER_WINDOW_SIZE, key.warpRadiusM);
    computeAnvils(out->window);
    out->summary = summarizeWindow(out->window);
    out->columnBounds = buildColumnBounds(out->window);
    // The GPU copy: the slices the shaders read (shaders/shared/weather_window.h "The GPU copy").
    const WeatherWindow& w = out->window;
    const size_t texelsPerSlice = size_t(w.sizeTexels) * w.sizeTexels;
    out->gpuTexelsHalf.resize(size_t(WEATHER_GPU_SLICES) * texelsPerSlice * 4);
    auto put = [&](uint32_t gpuSlice, size_t texel, int channel, float value) {
        // within half range (65504): no window value comes near it
        out->gpuTexelsHalf[(gpuSlice * texelsPerSlice + texel) * 4 + size_t(channel)] =
            glm::packHalf1x16(std::clamp(value, -65504.0f, 65504.0f));
    };
    auto copySlice = [&](uint32_t gpuSlice, uint32_t windowSlice) {
        for (size_t i = 0; i < texelsPerSlice; ++i)
            for (int c = 0; c < 4; ++c)
                put(gpuSlice, i, c, w.texels[windowSlice * texelsPerSlice + i][c]);
    };
    for (uint32_t k = 0; k < MAX_CLOUD_LAYERS; ++k)
    {
        copySlice(k, 2 * k);
        for (size_t i = 0; i < texelsPerSlice; ++i)
            put(WEATHER_GPU_PRECIP_SLICE, i, int(k), w.texels[(2 * k + 1) * texelsPerSlice + i].z);
    }
    copySlice(WEATHER_GPU_HIGH_SLICE, WEATHER_WINDOW_HIGH_SLICE);
    copySlice(WEATHER_GPU_HIGH_WIND_SLICE, WEATHER_WINDOW_HIGH_SLICE + 1);
    copySlice(WEATHER_GPU_ANVIL_SLICE, WEATHER_WINDOW_ANVIL_SLICE);
    return out;
}

std::shared_ptr<const PreparedWindow> takeWindow(WindowPrefetch& prefetch,
                                                 const std::shared_ptr<const WeatherSnapshot>& weather,
                                                 const WindowKey& key)
{
    if (prefetch.job.valid() && prefetch.key == key)
    {
        ++prefetch.used;
        return prefetch.job.get();  // waits if it is not finished: the result must not depend on timing
    }
    ++prefetch.madeOnFrame;
    return prepareWindow(*weather, key);
}

std::shared_ptr<const PreparedWindow> takeFinishedWindow(WindowPrefetch& prefetch)
{
    if (!prefetch.job.valid() || prefetch.job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        return nullptr;
    return prefetch.job.get();
}

void prefetchWindow(WindowPrefetch& prefetch, WeatherWorker& worker,
                    const std::shared_ptr<const WeatherSnapshot>& weather, const WindowKey& key)
{
    if (prefetch.job.valid())
    {
        if (prefetch.key == key)
            return;  // already on its way
        if (prefetch.job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            return;  // another one still runs: never block the frame on a guess
        prefetch.job.get();  // a finished guess that was not needed
    }
    prefetch.key = key;
    std::shared_ptr<const WeatherSnapshot> keep = weather;
    prefetch.job = worker.submit<std::shared_ptr<const PreparedWindow>>(
        WeatherJobPriority::Prefetch, [keep, key] { return prepareWindow(*keep, key); });
}

}  // namespace sky
