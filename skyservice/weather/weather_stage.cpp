// SPDX-License-Identifier: MIT
#include "skyservice/weather/weather_stage.h"

#include "weather_ingest/snapshot_file.h"

#include <chrono>
#include <exception>

namespace sky
{
namespace
{

/// The worker's part: the snapshot (unless it was made before: then only the window for another node),
/// its validation, and the window for `key`.
StagedResult runStageJob(const WeatherMaker& make, std::shared_ptr<const WeatherSnapshot> weather, const WindowKey& key)
{
    StagedResult out;
    out.version = key.weatherVersion;
    if (!weather)
    {
        try
        {
            weather = make ? make() : nullptr;
        }
        catch (const std::exception& e)
        {
            out.error = std::string("the staged weather could not be made: ") + e.what();
            return out;
        }
        if (!weather)
        {
            out.error = "the staged weather could not be made (no snapshot)";
            return out;
        }
        std::string why;
        if (!validateSnapshot(*weather, why))
        {
            out.error = "staged weather refused: " + why;
            return out;
        }
    }
    out.weather = std::move(weather);
    WindowKey made = key;
    made.weatherValidTimeUnixS = out.weather->validTimeUnixS;  // known once the snapshot is made
    out.window = prepareWindow(*out.weather, made);
    return out;
}

bool finished(const std::future<StagedResult>& job)
{
    return job.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

void forgetStaged(WeatherStage& s)
{
    s.version = 0;
    s.held = false;
    s.keepHistory = false;
    s.make = nullptr;
    s.weather.reset();
    s.ready.reset();
}

}  // namespace

void stage(WeatherStage& s, uint64_t version, WeatherMaker make, StageSwap swap, StageHistory history)
{
    const bool keep = history == StageHistory::Keep && (!stagePending(s) || s.keepHistory);
    forgetStaged(s);
    s.keepHistory = keep;
    s.version = version;
    s.ticket = ++s.ticketsIssued;
    s.held = swap == StageSwap::WhenReleased;
    s.make = std::move(make);
}

void releaseStage(WeatherStage& s) { s.held = false; }

void cancelStage(WeatherStage& s) { forgetStaged(s); }

std::optional<StagedResult> advanceStage(WeatherStage& s, WeatherWorker& worker, const WindowKey& eyeKey, bool wait)
{
    for (;;)
    {
        // Collect a finished job (with `wait`, also an unfinished one: it must be done before ours starts).
        if (s.job.valid() && (wait || finished(s.job)))
        {
            const uint64_t jobTicket = s.jobTicket;
            StagedResult result = s.job.get();
            if (jobTicket == s.ticket && stagePending(s))  // else superseded or cancelled: dropped
            {
                if (!result.error.empty())
                {
                    s.lastError = result.error;
                    ++s.refused;
                    forgetStaged(s);
                }
                else
                {
                    s.weather = result.weather;
                    s.ready = result.window;
                    ++s.windowsMade;
                }
            }
        }
        if (s.version == 0)
            return std::nullopt;
        WindowKey want = eyeKey;
        want.weatherVersion = s.version;
        want.weatherValidTimeUnixS = s.weather ? s.weather->validTimeUnixS : 0;  // no window before the snapshot
        if (s.ready && !(s.ready->key == want))
            s.ready.reset();  // the eye went to another cell meanwhile: the window alone is made again
        if (s.ready && (!s.held || wait))
        {
            StagedResult out{s.version, s.weather, s.ready, "", s.keepHistory};
            forgetStaged(s);
            s.lastError.clear();
            ++s.swapped;
            return out;
        }
        if (!s.ready && !s.job.valid())
        {
            s.jobTicket = s.ticket;
            WeatherMaker make = std::move(s.make);  // the snapshot is made once; s.weather keeps it after
            s.make = nullptr;
            std::shared_ptr<const WeatherSnapshot> weather = s.weather;
            s.job = worker.submit<StagedResult>(
                WeatherJobPriority::Staged,
                [make = std::move(make), weather = std::move(weather), want] { return runStageJob(make, weather, want); });
        }
        if (!wait)
            return std::nullopt;
    }
}

}  // namespace sky
