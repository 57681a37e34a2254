// SPDX-License-Identifier: MIT
#include "skyservice/service/weather_schedule.h"

#include "skyservice/service/log.h"
#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"

#include <cmath>

namespace sky
{
namespace
{

/// The weather at a whole second, as `skyservice render --weather` samples it (weather_source.cpp), with
/// the overlay (a CIGI host's weather) laid over it: so the merge is redone with every sample. Runs on the
/// renderer's worker thread: the timeline and the overlay are shared read-only (the service never changes a
/// loaded one, it replaces the pointer), the built-in scene is a pure function of the time.
WeatherMaker sampler(std::shared_ptr<const WeatherTimeline> timeline, std::shared_ptr<const WeatherOverlay> overlay,
                     int64_t atUnixS)
{
    return [timeline = std::move(timeline), overlay = std::move(overlay), atUnixS] {
        WeatherSnapshot w =
            timeline && !timeline->empty() ? timeline->sample(double(atUnixS)) : makeBuiltinWeather(atUnixS);
        return std::make_shared<const WeatherSnapshot>(overlay ? overlay->over(w) : std::move(w));
    };
}

WeatherMaker sampler(const WeatherState& weather, int64_t atUnixS)
{
    return sampler(weather.timeline, weather.overlay, atUnixS);
}

}  // namespace

std::string weatherName(const WeatherState& weather)
{
    return weather.overlay ? weather.source + " + " + weather.overlay->name() : weather.source;
}

void WeatherSchedule::stage(Renderer& r, const WeatherState& weather, int64_t sampleAtUnixS, int direction,
                            StageHistory history)
{
    Staged s;
    s.weather = DrawnWeather{weather.version, weatherName(weather), sampleAtUnixS};
    s.direction = direction;
    s.held = direction != 0;
    stageWeather(r, sampler(weather, sampleAtUnixS), s.held ? StageSwap::WhenReleased : StageSwap::WhenReady,
                 history, weather.version);
    staged_ = s;
    lastHandedVersion_ = weather.version;
}

void WeatherSchedule::beforeFrame(Renderer& r, const WeatherState& weather, const SimClock& clock, double simTimeS)
{
    const int64_t second = int64_t(std::floor(simTimeS));
    if (!started_ || clock.jumps != clockJumpsSeen_)
    {
        // Nothing to keep drawing yet, or a jump in time: this frame draws the weather of its time.
        setWeather(r, *sampler(weather, second)(), weather.version);
        drawn_ = DrawnWeather{weather.version, weatherName(weather), second};
        staged_.reset();
        lastHandedVersion_ = weather.version;
        clockJumpsSeen_ = clock.jumps;
        started_ = true;
        return;
    }
    if (weather.version != lastHandedVersion_)
    {
        // A newly loaded weather (replaces a staged re-sample), or a small step of a fade that keeps the
        // reprojection history: then a re-sample staged and not drawn yet is dropped first (the renderer
        // keeps the history only when every stage a small one replaces was small too), the step samples
        // this second anyway.
        const bool small = weather.smallStepFrom == lastHandedVersion_;
        if (small && staged_ && staged_->direction != 0)
        {
            cancelStagedWeather(r);
            staged_.reset();
        }
        stage(r, weather, second, 0, small ? StageHistory::Keep : StageHistory::Drop);
        return;
    }
    const int direction = clock.rate > 0 ? 1 : clock.rate < 0 ? -1 : 0;
    if (staged_ && staged_->direction != 0 && staged_->direction != direction)
    {
        cancelStagedWeather(r);  // a re-sample for a clock that has stopped or turned since
        staged_.reset();
    }
    if (direction != 0 && !staged_)
    {
        const int64_t next = drawn_.sampledAtUnixS + direction * int64_t(kWeatherResampleS);
        if (double(next - second) * direction < 0)
            stage(r, weather, second, 0);  // the clock outran the samples: this second's, swapped when ready
        else
            stage(r, weather, next, direction);  // ahead of time, released when the clock gets there
    }
    if (staged_ && staged_->held && (simTimeS - double(staged_->weather.sampledAtUnixS)) * direction >= 0)
    {
        releaseStagedWeather(r);
        staged_->held = false;
    }
}

void WeatherSchedule::afterFrame(const Renderer& r)
{
    if (!staged_ || weatherStagePending(r))
        return;
    // The stage ended: swapped in (the stage clears its last error then), or refused with a reason.
    if (r.weather.stage.lastError.empty())
    {
        drawn_ = staged_->weather;
        staged_.reset();
        SKY_LOG_DEBUG("weather %s sampled at %s drawn from this frame on", drawn_.source.c_str(),
                      formatIso8601Utc(drawn_.sampledAtUnixS).c_str());
    }
    else
    {
        SKY_LOG_ERROR("weather %s at %s: %s (keeping %s)", staged_->weather.source.c_str(),
                      formatIso8601Utc(staged_->weather.sampledAtUnixS).c_str(), r.weather.stage.lastError.c_str(),
                      drawn_.source.c_str());
        staged_.reset();
    }
}

}  // namespace sky
