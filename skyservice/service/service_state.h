// SPDX-License-Identifier: MIT
// What the control loop (socket thread) and the render loop (render thread) share, under one mutex:
// the inputs of the next frame (view, time, weather, quality, requests) and the outputs of the last
// (frame ids, frame times, memory). The render thread copies the inputs at the start of a frame, so a
// set_view or a weather swap never lands in the middle of one.
#pragma once

#include "skyservice/ipc/control_socket.h"
#include "skyservice/render/render_types.h"
#include "weather_ingest/weather_timeline.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace sky
{

using SteadyClock = std::chrono::steady_clock;

/// Where one published frame's time went: what a client needs to tell a slow frame's cause (the GPU's
/// passes, the copy into shared memory) from its own side's.
struct FrameTimes
{
    uint64_t frameId = 0;
    double frameMs = 0;    ///< submit to published, wall clock
    double publishMs = 0;  ///< the copy into the shared-memory ring and the zero-copy export, wall clock
    /// The CPU's preparation of the frame before its commands are recorded (RenderResult::cpuSetupMs: the
    /// weather window's update and copy, the light volume's placement, the frame's parameters), wall clock
    double setupMs = 0;
    std::map<std::string, double> gpuMs;  ///< GPU time per pass (RenderResult::gpuMs)
};

/// Simulated UTC: base time plus rate * real seconds since the base was set.
struct SimClock
{
    double baseUnixS = 0;
    SteadyClock::time_point baseReal = SteadyClock::now();
    double rate = 0;
    uint64_t jumps = 0;  ///< +1 per set_time with a time: the next frame draws the weather of its time at once

    double nowUnixS(SteadyClock::time_point now = SteadyClock::now()) const
    {
        return baseUnixS + rate * std::chrono::duration<double>(now - baseReal).count();
    }
};

/// Laid over every sample of a gridded weather before it is drawn (the CIGI host's weather over a loaded
/// file: cigi_weather_merge.h). Immutable once made: samples are made on the renderer's worker thread.
class WeatherOverlay
{
  public:
    virtual ~WeatherOverlay() = default;
    /// The weather drawn: `gridded` (a sample of the timeline, or the built-in scene) with the overlay on it.
    virtual WeatherSnapshot over(const WeatherSnapshot& gridded) const = 0;
    /// What status calls it (e.g. "cigi").
    virtual std::string name() const = 0;
};

/// The weather frames are rendered with: null timeline = the built-in scene.
struct WeatherState
{
    std::shared_ptr<const WeatherTimeline> timeline;
    std::string source = "builtin";  ///< "builtin" or the file
    /// Laid over each sample of `timeline` (null: the timeline is drawn as it is). Kept when a new file is
    /// loaded: it is laid over that one's samples.
    std::shared_ptr<const WeatherOverlay> overlay;
    uint64_t version = 1;            ///< +1 per swap
    /// `version` is a small step from this version (a CIGI fade step): its swap keeps the renderer's
    /// reprojection history. Any other swap (a load, a new overlay) leaves it behind, so it no longer matches.
    uint64_t smallStepFrom = 0;
    std::string lastError;           ///< the last refused file and why ("" after a good load)
    std::string lastErrorPath;       ///< that file: all that clients of another uid are told
};

/// The weather a published frame drew (status `weather.frame`): which load, sampled at which time.
struct FrameWeather
{
    uint64_t version = 0;            ///< WeatherState::version
    std::string source;
    int64_t validTimeUnixS = 0;      ///< valid time of the snapshot drawn (the sample time)
    bool known = false;              ///< false until a frame was published
};

/// `subscribe` with transport files: every N frames into dir.
struct FilesSubscription
{
    ClientId client = 0;  ///< 0 = from the config file
    std::string dir;
    uint32_t every = 1;
    std::string format = "png";
};

/// Work the render thread does for a request; its reply goes back through `replies`.
struct RenderJob
{
    enum Kind
    {
        WriteFiles,       ///< write the latest frame to `path` (a prefix)
        SubscribeVulkan,  ///< create the frame export lazily, reply with its description and fds
    } kind = WriteFiles;
    ClientId client = 0;
    nlohmann::json requestId;
    std::string path;
    uint32_t layers = 0;  ///< SubscribeVulkan: the layers asked for (bit k = SKY_LAYER_k)
};

/// A reply line made on the render thread, sent by the control loop (the only thread that sends).
struct PendingReply
{
    ClientId client = 0;
    std::string line;
    std::vector<int> fds;  ///< owned: closed by the control loop after sending
};

struct ServiceState
{
    std::mutex mutex;
    std::condition_variable wake;  ///< the render thread waits on it

    // Inputs of the next frame.
    ViewRequest view;              ///< pose, fov, size, shadow-map settings
    SimClock clock;
    WeatherState weather;
    QualitySettings quality;
    double renderRateHz = 0;
    uint64_t renderWantedUpTo = 0; ///< render on demand until this frame id has started
    std::vector<FilesSubscription> files;
    /// Shared-memory subscribers and the layers each asked for (bit k = SKY_LAYER_k, skyservice/ipc/shm_layout.h):
    /// frames draw and publish the union; the display layer is published always (while some
    /// client is subscribed here, or no client imports the exported images).
    std::map<ClientId, uint32_t> shmLayers;
    /// Vulkan subscribers' compositing layers (SKY_LAYER_SKY/CLOUDS/DEPTH bits), registered when the
    /// subscribe is queued and dropped on disconnect: frames draw them on the GPU and the export copies
    /// them; only layers some shm subscriber asks for as well are read back.
    std::map<ClientId, uint32_t> vulkanLayers;
    std::deque<RenderJob> jobs;
    bool stop = false;

    // Outputs.
    uint64_t framesStarted = 0;    ///< id of the last frame begun (ids start at 1)
    uint64_t lastFrameId = 0;      ///< id of the last frame published (0 = none yet)
    uint64_t framesRendered = 0;
    std::vector<double> frameMs;   ///< the last kFrameHistory frame times (ring), ms
    size_t frameMsNext = 0;
    std::deque<FrameTimes> recentFrames;  ///< the last kRecentFrames published frames, oldest first
    uint64_t deviceMemoryBytes = 0;
    uint64_t hostReadbackBytes = 0;  ///< the frames' host-cached readback buffers (system RAM)
    std::string lastRenderError;    ///< why the last frame failed; empty when it was published
    uint64_t framesFailed = 0;      ///< frames that failed to render since start-up
    uint64_t lastFailedFrameId = 0; ///< the last of them (0 = none); kept after later frames succeed
    std::string lastFailedFrameError;
    std::deque<PendingReply> replies;
    FrameWeather frameWeather;      ///< the weather of the last published frame
    bool weatherPending = false;    ///< a new weather (load or re-sample) is being prepared off the frame path
    uint64_t windowsMadeOnFramePath = 0;  ///< weather windows a frame had to make itself (a hitch each)
    uint64_t windowsFromWorker = 0;       ///< ... and those it took ready-made from the worker thread

    static constexpr size_t kFrameHistory = 128;
    /// Enough for a client that reads status every 5 ms to see every frame's pass times at 3000 frames per
    /// second; few enough (about 2.5 KB) that a status still fits the 8 KiB buffers clients read it into.
    static constexpr size_t kRecentFrames = 16;

    void recordFrameTimes(FrameTimes times)
    {
        recentFrames.push_back(std::move(times));
        while (recentFrames.size() > kRecentFrames)
            recentFrames.pop_front();
    }

    void recordFrameMs(double ms)
    {
        if (frameMs.size() < kFrameHistory)
            frameMs.push_back(ms);
        else
            frameMs[frameMsNext] = ms;
        frameMsNext = (frameMsNext + 1) % kFrameHistory;
    }
};

}  // namespace sky
