// SPDX-License-Identifier: MIT
// A new weather prepared off the frame path: the staged weather.
//
// setWeather makes the next frame resample the whole window on the frame path (tens of milliseconds of CPU). A staged
// weather instead gets its snapshot made (e.g. a timeline sampled), validated and its window resampled
// for the eye's lattice node on the weather worker (weather_worker.h), while frames go on drawing the old
// weather; the first frame after the job finished swaps it in and drops the reprojection history, as
// setWeather does, unless it was staged as a small step (StageHistory::Keep: a weather fading in, a step
// every fraction of a second, differs so little from the last that the reconstruct pass's colour clamp
// follows it; dropping the history at every step would leave the image re-sharpening over 16 frames after each).
// That frame renders exactly what a one-shot render with the new weather renders: its window is the one
// of its pose's node, made from the same snapshot (window_provider.h: the texels depend on the key only).
//
// Which frame the swap lands on depends on how long the job took (frames before it show the old
// weather); RenderResult::weatherVersion and weatherValidTimeUnixS say which weather a frame drew.
//
// The rules, all of them decided on the frame's thread (the worker only computes):
//  - the newest staged weather wins: staging again replaces one not yet swapped in; a job already
//    running for the older one is never abandoned mid-way (it finishes, its result is dropped), and the
//    newer one's job starts when it is done. A caller that stages faster than a job takes never sees
//    a swap: stage the next one after weatherStagePending() turned false (the service does).
//  - the window is made for the eye's node when the job starts; if the eye is in another cell when the
//    job is done, the window alone is made again (the snapshot is kept) for the node it is in then.
//  - held (StageSwap::WhenReleased): ready, but swapped in only after releaseStage (the service stages
//    the next timeline sample ahead of time and releases it when the simulated clock gets there).
//  - a bad weather (the maker threw or returned nothing, or validateSnapshot refuses it) is dropped
//    with the reason in lastError; the frames keep the last good weather.
#pragma once

#include "skyservice/weather/weather_worker.h"
#include "skyservice/weather/window_provider.h"

#include <functional>
#include <optional>
#include <string>

namespace sky
{

/// Makes a staged weather's snapshot, on the worker thread. It must only read what no other thread
/// changes: capture values, or shared_ptr<const ...> (a WeatherTimeline shared that way is safe to
/// sample from several threads: sample() is const and the service never changes a loaded timeline).
using WeatherMaker = std::function<std::shared_ptr<const WeatherSnapshot>()>;

/// Whether the swap of a staged weather drops the reprojection history.
enum class StageHistory
{
    Drop,  ///< a new weather: the previous frame shows other clouds
    Keep,  ///< a small step from the weather drawn (a fade step): the history still matches it closely
};

enum class StageSwap
{
    WhenReady,     ///< the first frame after the window is ready
    WhenReleased,  ///< the first frame after the window is ready and releaseStage was called
};

/// What a staging job made: the validated weather and its window, or why it was refused.
struct StagedResult
{
    uint64_t version = 0;  ///< the weather version the stage was given
    std::shared_ptr<const WeatherSnapshot> weather;
    std::shared_ptr<const PreparedWindow> window;
    std::string error;  ///< why the weather was refused ("" = good)
    bool keepHistory = false;  ///< StageHistory::Keep, and every stage it replaced unswapped was Keep too
};

/// The newest staged weather, the job in flight, and counts for tests and the service's status.
struct WeatherStage
{
    uint64_t version = 0;  ///< version of the staged weather (0: none staged)
    uint64_t ticket = 0;   ///< which stage() call `version` came from (a re-stage of one version is a new one)
    bool held = false;     ///< StageSwap::WhenReleased and not released yet
    /// StageHistory::Keep and so was every stage it replaced before they swapped in: the frames still draw
    /// the weather before those, so a small step over a replaced big one is a big change.
    bool keepHistory = false;
    WeatherMaker make;     ///< until a job took it
    std::shared_ptr<const WeatherSnapshot> weather;  ///< once made and valid
    std::shared_ptr<const PreparedWindow> ready;     ///< its window, for ready->key

    std::future<StagedResult> job;  ///< valid while a job was started and not collected
    uint64_t jobTicket = 0;         ///< the ticket `job` works for (older than `ticket` if superseded)
    uint64_t ticketsIssued = 0;

    std::string lastError;   ///< the last refused weather and why ("" once a staged weather swapped in)
    uint64_t swapped = 0;    ///< staged weathers swapped in
    uint64_t refused = 0;    ///< staged weathers refused (bad snapshot)
    uint64_t windowsMade = 0;  ///< windows the staging jobs made on the worker thread
};

/// Stages a weather as `version` (replacing one staged before and not swapped in yet).
void stage(WeatherStage& s, uint64_t version, WeatherMaker make, StageSwap swap,
           StageHistory history = StageHistory::Drop);
/// Lets a held staged weather swap in (nothing when none is staged).
void releaseStage(WeatherStage& s);
/// Forgets the staged weather (a running job finishes on its own; its result is dropped).
void cancelStage(WeatherStage& s);
inline bool stagePending(const WeatherStage& s) { return s.version != 0; }

/// One frame's step: collects a finished job without waiting, starts the next job (on `worker`) for `eyeKey`'s node
/// (its weatherVersion is ignored), and returns the weather and window to show from this frame on
/// when the staged weather is ready for that node (and released). With `wait` (nothing is on screen
/// yet, so there is nothing to keep drawing) it blocks until the staged weather is ready or refused,
/// held or not.
std::optional<StagedResult> advanceStage(WeatherStage& s, WeatherWorker& worker, const WindowKey& eyeKey, bool wait);

}  // namespace sky
