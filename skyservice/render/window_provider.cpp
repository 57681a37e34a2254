// SPDX-License-Identifier: MIT
#include "skyservice/render/window_provider.h"

#include "skyservice/render/column_bounds.h"

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
    const std::vector<glm::vec4>& t = out->window.texels;
    out->gpuTexelsHalf.resize(t.size() * 4);
    for (size_t i = 0; i < t.size(); ++i)
        for (int c = 0; c < 4; ++c)  // within half range (65504): no window value comes near it
            out->gpuTexelsHalf[4 * i + size_t(c)] = glm::packHalf1x16(std::clamp(t[i][c], -65504.0f, 65504.0f));
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

void prefetchWindow(WindowPrefetch& prefetch, const std::shared_ptr<const WeatherSnapshot>& weather,
                    const WindowKey& key)
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
    prefetch.job = std::async(std::launch::async, [keep, key] { return prepareWindow(*keep, key); });
}

}  // namespace sky
