// SPDX-License-Identifier: MIT
// Which weather the service's frames draw, and when a new one is handed to the renderer.
//
// The weather is a timeline (a loaded file, or the built-in scene) sampled at whole simulated seconds,
// a new sample every kWeatherResampleS of simulated time while the clock runs. A new weather reaches
// the renderer through its staging (weather/weather_stage.h): snapshot and window are made on a worker
// thread and swapped in at the first frame after they are ready, so no frame makes a window for it:
//  - a loaded file (load_weather, the watched folder, SIGHUP) is sampled at the frame's second and
//    staged at once;
//  - while the clock runs, the next sample (kWeatherResampleS after the drawn one, toward where the
//    clock goes) is staged ahead of time, held, and released at the first frame whose simulated time
//    has reached it: that frame draws it when it was ready in time (otherwise a later one does). When
//    the clock outran the samples (a high rate, or a slow job), the next one is taken at the frame's
//    own second.
// A weather's overlay (a CIGI host's weather over a loaded file) is laid over every sample, so it is merged
// again with each new sample and each newly loaded file. A small step (WeatherState::smallStepFrom: a CIGI
// fade step) is staged to keep the renderer's reprojection history; every other new weather drops it.
// Synchronous (setWeather, the window made on the frame path): the first frame, and the first frame
// after a set_time with a time (a jump in time, like a teleport: that frame equals a one-shot render of
// its view, time and weather). With rate 0 nothing is re-sampled, so a service frame equals
// `skyservice render` of the same inputs byte for byte (after a load: once the frame shows it).
#pragma once

#include "skyservice/render/renderer.h"
#include "skyservice/service/service_state.h"

#include <optional>
#include <string>

namespace sky
{

/// A weather is re-sampled when the simulated time moved this far from the drawn sample (s): cloud
/// fields change on the scale of the model's hourly steps, so a minute is invisible, and a frozen
/// clock samples exactly once.
inline constexpr double kWeatherResampleS = 60;

/// The weather's name in status and logs: the source, with " + " and the overlay's name when one is laid
/// over it (e.g. "/data/gfs.skywx + cigi").
std::string weatherName(const WeatherState& weather);

/// What a frame drew: the service's weather (WeatherState::version, which the renderer is given as the
/// weather's version, renderer.h) and its source, sampled at a time.
struct DrawnWeather
{
    uint64_t version = 0;
    std::string source;
    int64_t sampledAtUnixS = 0;
};

class WeatherSchedule
{
public:
    /// Before renderView: hands the renderer the weather this frame (or a later one) should draw.
    /// @param[in] simTimeS the frame's simulated time (s since 1970); request.unixTimeS is its floor.
    void beforeFrame(Renderer& r, const WeatherState& weather, const SimClock& clock, double simTimeS);
    /// After renderView: notes a staged weather that swapped in or was refused (logged). The renderer says
    /// which (its stage is no longer pending; a refusal left its reason), so no renderer version is kept.
    void afterFrame(const Renderer& r);
    /// The weather the renderer draws now (the last frame's, after afterFrame).
    const DrawnWeather& drawn() const { return drawn_; }
    /// A new weather is being prepared (load or re-sample).
    bool pending() const { return staged_.has_value(); }

private:
    struct Staged
    {
        DrawnWeather weather;
        int direction = 0;  ///< +1 / -1: a held re-sample for a clock running forward / backward; 0: a load
        bool held = false;
    };
    void stage(Renderer& r, const WeatherState& weather, int64_t sampleAtUnixS, int direction,
               StageHistory history = StageHistory::Drop);

    DrawnWeather drawn_;
    std::optional<Staged> staged_;
    uint64_t lastHandedVersion_ = 0;  ///< the newest WeatherState::version handed to the renderer
    uint64_t clockJumpsSeen_ = 0;
    bool started_ = false;
};

}  // namespace sky
