// SPDX-License-Identifier: MIT
// The weather windows a moving eye needs, prepared off the frame path (issue 5).
//
// A window is centred on a lattice node (earth/window_lattice.h), so a moving eye needs a new one only
// when it crosses into another lattice cell. The renderer asks for the window of the eye's node every
// frame (takeWindow) and names the node the eye is heading for (prefetchWindow): that one is resampled,
// its anvils derived and summarised on a worker thread while frames go on. When the eye arrives, the
// window is ready (it takes 17-85 ms to make, the eye needs ~9 s to cross a cell at 250 m/s); if it is
// not, takeWindow waits for it, so the window used never depends on timing.
#pragma once

#include "skyservice/earth/weather_window.h"
#include "skyservice/earth/window_lattice.h"
#include "skyservice/render/window_analysis.h"
#include "weather_ingest/weather_snapshot.h"

#include <future>
#include <memory>

namespace sky
{

/// How far ahead along its horizontal motion the eye looks for the next lattice node (m): the next
/// window starts being made when the eye is this close to its cell's edge, 5 s ahead at 300 m/s, for a
/// job of 17-85 ms.
inline constexpr double kWindowLookAheadM = 1500.0;

/// What a window was made from: the same key gives the same texels.
struct WindowKey
{
    uint64_t weatherVersion = 0;  ///< Renderer::weatherVersion when it was made
    WindowCentre centre;
    double halfExtentM = 0, warpRadiusM = 0;
    bool operator==(const WindowKey& o) const
    {
        return weatherVersion == o.weatherVersion && centre == o.centre && halfExtentM == o.halfExtentM &&
               warpRadiusM == o.warpRadiusM;
    }
};

/// A resampled window with its derived anvil slice and summary.
struct PreparedWindow
{
    WindowKey key;
    WeatherWindow window;
    WindowSummary summary;
    /// window.texels as half floats, the layout of the GPU image (RGBA16F: half the bytes and twice the
    /// filtering rate of RGBA32F; altitudes keep 8 m steps up to 16 km, coverage 1/2048).
    std::vector<uint16_t> gpuTexelsHalf;
};

/// Resamples, derives the anvils and summarises (the CPU work of a window).
std::shared_ptr<const PreparedWindow> prepareWindow(const WeatherSnapshot& weather, const WindowKey& key);

/// The one window being prepared in the background, and counts for tests and benchmarks.
struct WindowPrefetch
{
    std::future<std::shared_ptr<const PreparedWindow>> job;  ///< valid while a job was started and not taken
    WindowKey key;                                            ///< what `job` makes
    uint64_t used = 0;         ///< ... whose result a frame used
    uint64_t madeOnFrame = 0;  ///< windows prepared on the frame path (first frame, new weather, a jump)
};

/// The window for `key`: the background one if it is for this key (waiting for it if need be),
/// otherwise prepared now, on the calling thread.
std::shared_ptr<const PreparedWindow> takeWindow(WindowPrefetch& prefetch,
                                                 const std::shared_ptr<const WeatherSnapshot>& weather,
                                                 const WindowKey& key);

/// Starts preparing `key` on a worker thread unless it is already being prepared or a job still runs
/// (one at a time: a started job is never abandoned mid-way). The job keeps its own reference to the
/// weather, so a setWeather meanwhile is safe (its result is then simply not used).
void prefetchWindow(WindowPrefetch& prefetch, const std::shared_ptr<const WeatherSnapshot>& weather,
                    const WindowKey& key);

}  // namespace sky
