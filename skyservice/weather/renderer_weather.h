// SPDX-License-Identifier: MIT
// The renderer's weather, in one place: the snapshot drawn and its version, the staged weather prepared
// on its one worker thread (weather_stage.h), the window of the eye's lattice cell with its GPU images and the
// next cell's window made on the same worker (window_provider.h), and the eye's motion that says which
// cell comes next. setWeather / stageWeather (renderer.h) change it; updateWeatherWindow
// (window_upload.h) advances it once per frame, on the frame's thread: the worker only computes.
#pragma once

#include "skyservice/weather/weather_stage.h"
#include "skyservice/weather/weather_worker.h"
#include "skyservice/weather/window_copy.h"
#include "skyservice/weather/window_provider.h"
#include "skyservice/vk/resources.h"

#include <chrono>
#include <memory>

namespace sky
{

struct RendererWeather
{
    /// Makes staged weathers and prefetched windows. First member, so destroyed last: the jobs it still
    /// runs hold their own references to what they read, and the futures below never wait on it.
    WeatherWorker worker;
    std::shared_ptr<const WeatherSnapshot> snapshot;  ///< the weather drawn (shared with the worker's jobs)
    /// Of `snapshot`: the caller's (setWeather / stageWeather; renderer.h says whose). Windows carry the
    /// version and valid time of the snapshot they were made from (WindowKey), so a window of another
    /// weather, or of another sample of this one, is never used.
    uint64_t version = 0;
    uint64_t newestVersion = 0;  ///< the newest version given (staged weathers get theirs early)
    WeatherStage stage;           ///< a new weather being prepared on `worker` (weather_stage.h)
    /// The window frames draw, in windowImage and columnBoundsImage (centred on a lattice node near the
    /// eye, weather/window_lattice.h): frames whose eye stays in that node's cell, with the same weather
    /// and window settings, reuse it.
    std::shared_ptr<const PreparedWindow> window;
    WindowCopy copy;           ///< puts a new window into the images below without waiting (window_copy.h)
    WindowPrefetch prefetch;   ///< the next cell's window, made on `worker`
    glm::dvec3 lastEyeEcefM{0.0};  ///< eye of the previous frame: its motion says which cell is next
    std::chrono::steady_clock::time_point lastFrameClock{};  ///< when the previous frame began (real time)
    double eyeSpeedMps = 0;    ///< estimate of the eye's horizontal speed: it sets the look-ahead
    Image windowImage;         ///< `window`'s slices the shaders read (shaders/shared/weather_window.h)
    Image columnBoundsImage;   ///< its column-bounds pyramid (shaders/shared/column_bounds.h)
    uint64_t windowCopiesWaited = 0;  ///< frames that waited for the previous window copy to finish
};

/// Makes the window's GPU images (filled by the first frame's updateWeatherWindow) and their copy.
SkyStatus createWeatherImages(const Context& ctx, MemoryTracker& memory, RendererWeather& weather);
/// Destroys the images (after a copy in flight); the worker's jobs finish on their own (the worker joins
/// when RendererWeather goes).
void destroyWeatherImages(const Context& ctx, MemoryTracker& memory, RendererWeather& weather);

}  // namespace sky
