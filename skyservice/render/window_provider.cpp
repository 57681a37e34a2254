// SPDX-License-Identifier: MIT
#include "skyservice/render/window_provider.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>

namespace sky
{

std::shared_ptr<const PreparedWindow> prepareWindow(const WeatherSnapshot& weather, const WindowKey& key)
{
    auto out = std::make_shared<PreparedWindow>();
    out->key = key;
    resampleWeatherWindow(weather, key.centre.latDeg, key.centre.lonDeg, key.halfExtentM, out->window,
                          WEATHER_WINDOW_SIZE, key.warpRadiusM);
    computeAnvils(out->window);
    out->summary = summarizeWindow(out->window);
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
