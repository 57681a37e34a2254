// SPDX-License-Identifier: MIT
// The weather windows a moving eye needs, prepared off the frame path so that no frame waits for one.
//
// A window is centred on a lattice node (weather/window_lattice.h), so a moving eye needs a new one only
// when it crosses into another lattice cell. The renderer asks for the window of the eye's node every
// frame (takeWindow) and names the node the eye is heading for (prefetchWindow): that one is resampled,
// its anvils derived and summarised on the weather worker (weather_worker.h) while frames go on. When the eye arrives, the
// window is ready (it takes tens of milliseconds to make, the eye needs ~9 s to cross a cell at 250 m/s); if it is
// not, takeWindow waits for it, so the window used never depends on timing.
#pragma once

#include "skyservice/earth/geodesy.h"
#include "skyservice/weather/weather_window.h"
#include "skyservice/weather/window_lattice.h"
#include "skyservice/weather/weather_worker.h"
#include "skyservice/weather/window_analysis.h"
#include "weather_ingest/weather_snapshot.h"

#include <future>
#include <memory>
#include <optional>

namespace sky
{

/// How far ahead along its horizontal motion the eye looks for the next lattice node: the next window
/// starts being made when the eye is this close to its cell's edge. At least kWindowLookAheadMinM (5 s
/// at 300 m/s, for a job of tens of milliseconds), and kWindowLookAheadS of motion at the eye's speed: at
/// 3000 m/s a fixed 1500 m is only 0.5 s, too little for a job that shares the CPU with frames rendered
/// back to back, and a frame would wait for its window.
/// At most kWindowLookAheadMaxM: 1 s at Mach 60, 9 lattice cells, well inside
/// the window's ~1 km texels (warp radius 150 km); a faster "speed" is a jump, not a flight.
inline constexpr double kWindowLookAheadMinM = 1500.0;
inline constexpr double kWindowLookAheadS = 1.5;
inline constexpr double kWindowLookAheadMaxM = 20000.0;
/// The eye's speed estimate keeps a peak this long (s, e-folding): a service renders frames between two
/// set_view requests in which the eye does not move, and those must not make it look slow.
inline constexpr double kEyeSpeedMemoryS = 2.0;

/// What a window was made from: the same key gives the same texels.
struct WindowKey
{
    /// The snapshot it was made from: its weather's version (RendererWeather::version) and its valid time,
    /// which tells apart the samples of one weather at different times.
    uint64_t weatherVersion = 0;
    int64_t weatherValidTimeUnixS = 0;
    WindowCentre centre;
    double halfExtentM = 0, warpRadiusM = 0;
    bool operator==(const WindowKey& o) const
    {
        return weatherVersion == o.weatherVersion && weatherValidTimeUnixS == o.weatherValidTimeUnixS &&
               centre == o.centre && halfExtentM == o.halfExtentM && warpRadiusM == o.warpRadiusM;
    }
};

/// A resampled window with its derived anvil slice and summary.
struct PreparedWindow
{
    WindowKey key;
    WeatherWindow window;
    WindowSummary summary;
    /// The slices of window.texels the shaders read, as half floats in the layout of the GPU image
    /// (shaders/shared/weather_window.h "The GPU copy"; RGBA16F: half the bytes and twice the filtering
    /// rate of RGBA32F; altitudes keep 8 m steps up to 16 km, coverage 1/2048).
    std::vector<uint16_t> gpuTexelsHalf;
    /// The column-bounds pyramid of `window` (column_bounds.h), the layout of its GPU image (R8G8_UINT).
    std::vector<uint8_t> columnBounds;
};

/// The look-ahead distance (m) for an eye moving at `speedMps` (m/s): kWindowLookAheadS of motion,
/// clamped to [kWindowLookAheadMinM, kWindowLookAheadMaxM].
double windowLookAheadM(double speedMps);

/// The eye's speed (m/s) after a frame that moved it `moveM` (m) in `dtS` (s) of real time: the new
/// speed, or the previous one decayed over dtS with kEyeSpeedMemoryS when that is larger.
double updateEyeSpeedMps(double previousMps, double moveM, double dtS);

/// The node the eye reaches next flying straight along `directionEnu` (east, north; any length > 0)
/// from camera.eye: the first node other than the eye's own along that line (walked in steps of
/// kNextNodeStepM in the eye's tangent plane), when it is reached within `lookAheadM` (m).
std::optional<WindowCentre> nextWindowNode(const CameraFrame& camera, glm::dvec2 directionEnu, double lookAheadM);
/// 25 m: a path that clips a cell's corner for less than this may be missed (that window is then made
/// on the frame path); 2.2 km cells take at most ~130 steps to leave.
inline constexpr double kNextNodeStepM = 25.0;

/// Resamples, derives the anvils, summarises and bounds the columns (the CPU work of a window).
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

/// The background window when its job has finished (never waits; null otherwise), without counting it
/// as used: the renderer copies it to the GPU ahead of the eye (window_upload.h) and counts it when a
/// frame draws it.
std::shared_ptr<const PreparedWindow> takeFinishedWindow(WindowPrefetch& prefetch);

/// Starts preparing `key` on `worker` unless it is already being prepared or a job still runs
/// (one at a time: a started job is never abandoned mid-way). The job keeps its own reference to the
/// weather, so a setWeather meanwhile is safe (its result is then simply not used).
void prefetchWindow(WindowPrefetch& prefetch, WeatherWorker& worker,
                    const std::shared_ptr<const WeatherSnapshot>& weather, const WindowKey& key);

}  // namespace sky
