// SPDX-License-Identifier: MIT
#include "skyservice/service/render_loop.h"

#include "skyservice/app/render_files.h"
#include "skyservice/ipc/protocol.h"
#include "skyservice/service/log.h"
#include "skyservice/service/log_limiter.h"
#include "skyservice/service/shm_view.h"
#include "skyservice/service/vulkan_export.h"
#include "skyservice/service/weather_schedule.h"
#include "skyservice/sky/ephemeris.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <unistd.h>

namespace sky
{
namespace
{

SkyShmShadowGeoRef shadowGeoRef(const RenderResult& result)
{
    SkyShmShadowGeoRef g{};
    if (result.shadowMapSize == 0)
        return g;
    const ShadowMapReference& ref = result.shadowReference;
    g.centre_lat_deg = ref.centreLatDeg;
    g.centre_lon_deg = ref.centreLonDeg;
    g.extent_m = ref.extentM;
    for (int i = 0; i < 4; ++i)
    {
        g.corner_lat_deg[i] = ref.cornerLatDeg[i];
        g.corner_lon_deg[i] = ref.cornerLonDeg[i];
    }
    g.sun_azimuth_deg = ref.keyLightAzimuthDeg;
    g.sun_elevation_deg = ref.keyLightElevationDeg;
    g.size_texels = result.shadowMapSize;
    g.light_is_moon = ref.keyLightIsMoon ? 1u : 0u;
    return g;
}

std::string okLine(RequestType type, const nlohmann::json& id)
{
    Request r;
    r.type = type;
    r.id = id;
    return okReply(r);
}

std::string failedLine(const nlohmann::json& id, const std::string& message)
{
    ProtocolError e;
    e.code = "failed";
    e.message = message;
    e.id = id;
    return errorReply(e);
}

}  // namespace

/// A frame submitted to the GPU and not yet published.
struct InFlightFrame
{
    FrameTicket ticket;  ///< holds the frame's request (ticket.request)
    uint64_t id = 0;
    double simTimeS = 0;
    SteadyClock::time_point start;
    DrawnWeather drawn;        ///< the weather this frame drew (the schedule may move on before it is published)
    uint32_t layers = 0;       ///< shm layers to publish (bit k = SKY_LAYER_k)
    uint32_t exportLayers = 0; ///< layers the zero-copy export copies (vulkan subscribers'), same bits
    bool copyPixels = false;   ///< files are written from this frame: its pixels go to `result` too
    std::vector<FilesSubscription> files;
};

struct RenderLoop::Impl
{
    Setup setup;
    RenderResult result;        ///< the last frame collected (pixels only when it wrote files)
    bool resultHasPixels = false;
    ViewRequest lastRequest;
    DrawnWeather lastDrawn;
    bool haveFrame = false;
    WeatherSchedule weatherSchedule;
    VulkanExport exporter;
    std::string lastLoggedError;
    LogLimiter frameErrorLog;  ///< distinct failures that alternate still cost a line per window, not per frame
    std::optional<InFlightFrame> inFlight;
    double lastPublishMs = 0;  ///< the last completed frame's copy into the ring and export (ms)
    /// write_files requests that came while the last frame had no pixels on the host (or no linear frame
    /// for the EXR): they are written after the next frame, which reads them back.
    std::vector<RenderJob> pendingWriteFiles;

    void run();
    void startFrame(uint64_t id, ViewRequest& request, const SimClock& clock, double simTimeS,
                    const WeatherState& weather, const QualitySettings& quality,
                    std::vector<FilesSubscription> files, uint32_t layers, uint32_t exportLayers);
    void completeFrame(InFlightFrame& frame);
    void completeInFlight()
    {
        if (!inFlight)
            return;
        InFlightFrame frame = std::move(*inFlight);
        inFlight.reset();
        completeFrame(frame);
    }
    void frameDone(uint64_t id, const SkyStatus& status, double ms);
    /// After a failed vulkan subscribe: the client's layers that have no exported images are not drawn for it.
    void dropUnexportedLayers(ClientId client)
    {
        std::lock_guard<std::mutex> lock(setup.state->mutex);
        auto it = setup.state->vulkanLayers.find(client);
        if (it != setup.state->vulkanLayers.end())
            it->second &= exporter.layersMade();
    }
    void doJob(const RenderJob& job);
    bool writeFiles(const std::string& prefix, const std::string& format, std::string& error);
    void reply(ClientId client, std::string line, std::vector<int> fds = {})
    {
        {
            std::lock_guard<std::mutex> lock(setup.state->mutex);
            setup.state->replies.push_back(PendingReply{client, std::move(line), std::move(fds)});
        }
        setup.repliesReady();
    }
};

RenderLoop::RenderLoop() : impl_(std::make_unique<Impl>()) {}
RenderLoop::~RenderLoop() { stop(); }

void RenderLoop::start(const Setup& setup)
{
    impl_->setup = setup;
    thread_ = std::thread([this] { impl_->run(); });
}

void RenderLoop::stop()
{
    if (!impl_->setup.state)
        return;
    {
        std::lock_guard<std::mutex> lock(impl_->setup.state->mutex);
        impl_->setup.state->stop = true;
    }
    impl_->setup.state->wake.notify_all();
    if (thread_.joinable())
        thread_.join();
    impl_->exporter.destroy(*impl_->setup.renderer);
}

// Frames in flight: a frame is submitted, and while the GPU renders it the loop goes on to the next one
// (its CPU setup and recording) when one is due at once; the earlier frame is published after the later
// one is submitted. When nothing else is due the frame in flight is published right away, so a client
// that asks for one frame at a time waits for no other.
void RenderLoop::Impl::run()
{
    ServiceState& s = *setup.state;
    SteadyClock::time_point nextDue = SteadyClock::now();
    for (;;)
    {
        std::unique_lock<std::mutex> lock(s.mutex);
        bool idle = false;
        for (;;)
        {
            if (s.stop)
                break;
            if (!s.jobs.empty() || s.renderWantedUpTo > s.framesStarted)
                break;
            if (s.renderRateHz > 0 && SteadyClock::now() >= nextDue)
                break;
            if (inFlight)
            {
                idle = true;  // nothing due now: publish the frame in flight first
                break;
            }
            if (s.renderRateHz > 0)
                s.wake.wait_until(lock, nextDue);
            else
                s.wake.wait(lock);
        }
        if (idle || s.stop || !s.jobs.empty())
        {
            const bool stopNow = s.stop && !idle;
            std::optional<RenderJob> job;
            if (!idle && !s.stop)
            {
                job = s.jobs.front();
                s.jobs.pop_front();
            }
            lock.unlock();
            completeInFlight();  // jobs read the latest frame
            if (stopNow)
                return;
            if (job)
                doJob(*job);
            continue;
        }
        uint64_t id = ++s.framesStarted;
        ViewRequest request = s.view;  // the frame's view, taken under the lock; startFrame completes it
        SteadyClock::time_point now = SteadyClock::now();
        SimClock clock = s.clock;
        double simTimeS = clock.nowUnixS(now);
        WeatherState weather = s.weather;
        QualitySettings quality = s.quality;
        std::vector<FilesSubscription> files = s.files;
        uint32_t layers = 0;
        for (const auto& [client, bits] : s.shmLayers)
            layers |= bits;
        uint32_t exportLayers = 0;
        for (const auto& [client, bits] : s.vulkanLayers)
            exportLayers |= bits;
        // The display picture goes through the ring unless every reader imports the exported images:
        // then the ring carries each frame's facts and the GPU's copy into the export is all there is.
        if (!exporter.active() || !s.shmLayers.empty())
            layers |= 1u << SKY_LAYER_DISPLAY;
        if (s.renderRateHz > 0)
        {
            auto period = std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(1.0 / s.renderRateHz));
            // Keep the cadence, but never try to catch up on frames missed while rendering was slow.
            nextDue = std::max(nextDue + period, now);
        }
        lock.unlock();
        // The zero-copy export copies the display image after the frame: the frame in flight must be
        // exported before the next one overwrites that image.
        if (exporter.active())
            completeInFlight();
        startFrame(id, request, clock, simTimeS, weather, quality, std::move(files), layers, exportLayers);
    }
}

void RenderLoop::Impl::startFrame(uint64_t id, ViewRequest& request, const SimClock& clock, double simTimeS,
                                  const WeatherState& weather, const QualitySettings& quality,
                                  std::vector<FilesSubscription> files, uint32_t layers, uint32_t exportLayers)
{
    Renderer& r = *setup.renderer;
    InFlightFrame frame;
    frame.start = SteadyClock::now();
    frame.id = id;
    request.unixTimeS = int64_t(std::floor(simTimeS));
    request.unixTimeFractionS = simTimeS - std::floor(simTimeS);
    weatherSchedule.beforeFrame(r, weather, clock, simTimeS);  // a new weather is prepared off this thread
    // What this frame reads back: the layers shm subscribers asked for; everything files need when this
    // frame writes files (the linear frame, 16.6 MB at 1080p, only for EXR files).
    const bool writesFiles = !pendingWriteFiles.empty() ||
                             std::any_of(files.begin(), files.end(),
                                         [id](const FilesSubscription& f) { return id % f.every == 0; });
    const bool exr = !pendingWriteFiles.empty() ||
                     std::any_of(files.begin(), files.end(), [](const FilesSubscription& f) { return f.format != "png"; });
    request.linearOutput = writesFiles && exr;
    request.readback = (layers & (1u << SKY_LAYER_DISPLAY)) ? kReadDisplay : 0u;
    if (layers & (1u << SKY_LAYER_SKY))
        request.readback |= kReadSky;
    if (layers & (1u << SKY_LAYER_CLOUDS))
        request.readback |= kReadCloudLayer;
    if (layers & (1u << SKY_LAYER_DEPTH))
        request.readback |= kReadDepthLayer;
    // Vulkan subscribers' layers are drawn on the GPU and copied into the export; only those a shm
    // subscriber asks for as well are read back (kRead* above).
    if (exportLayers & (1u << SKY_LAYER_SKY))
        request.readback |= kDrawSky;
    if (exportLayers & (1u << SKY_LAYER_CLOUDS))
        request.readback |= kDrawCloudLayer;
    if (exportLayers & (1u << SKY_LAYER_DEPTH))
        request.readback |= kDrawDepthLayer;
    if (writesFiles)
        request.readback |= kReadEverything;
    frame.simTimeS = simTimeS;
    frame.layers = layers;
    frame.exportLayers = exportLayers;
    frame.copyPixels = writesFiles;
    frame.files = std::move(files);
    SkyStatus status = submitView(r, request, quality, frame.ticket);
    weatherSchedule.afterFrame(r);
    frame.drawn = weatherSchedule.drawn();
    if (!status.ok())
    {
        completeInFlight();
        // The write_files requests this frame was rendered for learn that it failed, and why: otherwise
        // they would wait for a frame that, rendered on request only, may never come.
        if (frame.copyPixels)
        {
            std::vector<RenderJob> waiting;
            waiting.swap(pendingWriteFiles);
            for (const RenderJob& job : waiting)
                reply(job.client, failedLine(job.requestId, "frame " + std::to_string(id) + ": " + status.message));
        }
        frameDone(id, status, std::chrono::duration<double, std::milli>(SteadyClock::now() - frame.start).count());
        return;
    }
    std::optional<InFlightFrame> previous = std::move(inFlight);
    inFlight = std::move(frame);
    if (previous)
        completeFrame(*previous);
}

void RenderLoop::Impl::completeFrame(InFlightFrame& frame)
{
    Renderer& r = *setup.renderer;
    SkyStatus status = finishView(r, frame.ticket, result, frame.copyPixels);
    std::string error;
    if (status.ok())
    {
        haveFrame = true;
        resultHasPixels = frame.copyPixels;
        lastRequest = frame.ticket.request;
        lastDrawn = frame.drawn;
        const ViewRequest& request = frame.ticket.request;
        const MappedFrame pixels = mappedFrame(r, frame.ticket);
        ShmFrame f;
        f.frameId = frame.id;
        f.simTimeUnixS = frame.simTimeS;
        f.exposure = result.exposure;
        f.view = shmViewOf(request);
        f.format = SKY_FORMAT_RGBA8_SRGB;
        f.width = result.width;
        f.height = result.height;
        f.rowBytes = result.width * 4;
        f.pixels = pixels.displayRgba8;
        if (frame.layers & (1u << SKY_LAYER_SKY))
            f.layers[SKY_LAYER_SKY] = pixels.skyRgbaHalf;
        if (frame.layers & (1u << SKY_LAYER_CLOUDS))
            f.layers[SKY_LAYER_CLOUDS] = pixels.cloudLayerRgbaHalf;
        if (frame.layers & (1u << SKY_LAYER_DEPTH))
            f.layers[SKY_LAYER_DEPTH] = pixels.depthLayerM;
        if (result.shadowMapSize > 0)
        {
            f.shadowTransmittance = pixels.shadowTransmittance;
            f.shadow = shadowGeoRef(result);
            f.shadowId = result.shadowMapId;
        }
        const SteadyClock::time_point publishStart = SteadyClock::now();
        uint32_t slot = setup.ring->beginSlot();
        if (exporter.active() && !exporter.exportFrame(r, slot, frame.id, result, frame.exportLayers, error))
            SKY_LOG_WARN("frame %llu: zero-copy export: %s", (unsigned long long)frame.id, error.c_str());
        if (!setup.ring->endSlot(f, error))
            SKY_LOG_WARN("frame %llu: not published: %s", (unsigned long long)frame.id, error.c_str());
        lastPublishMs = std::chrono::duration<double, std::milli>(SteadyClock::now() - publishStart).count();
        error.clear();
    }
    for (const FilesSubscription& sub : frame.files)
    {
        if (!status.ok() || frame.id % sub.every != 0)
            continue;
        char name[32];
        std::snprintf(name, sizeof name, "/frame-%08llu", (unsigned long long)frame.id);
        std::string why;
        if (!writeFiles(sub.dir + name, sub.format, why))
            SKY_LOG_WARN("files subscription: %s", why.c_str());
    }
    if (frame.copyPixels)
    {
        std::vector<RenderJob> waiting;
        waiting.swap(pendingWriteFiles);
        for (const RenderJob& job : waiting)
        {
            std::string why = status.message;
            if (status.ok() && writeFiles(job.path, "both", why))
                reply(job.client, okLine(RequestType::WriteFiles, job.requestId));
            else
                reply(job.client, failedLine(job.requestId, why));
        }
    }
    frameDone(frame.id, status, std::chrono::duration<double, std::milli>(SteadyClock::now() - frame.start).count());
}

void RenderLoop::Impl::frameDone(uint64_t id, const SkyStatus& status, double ms)
{
    Renderer& r = *setup.renderer;
    std::string error;
    if (!status.ok())
    {
        error = status.message;
        if (error != lastLoggedError && frameErrorLog.admit(SteadyClock::now()))  // not one line per frame
            SKY_LOG_ERROR("frame %llu: %s", (unsigned long long)id, error.c_str());
    }
    lastLoggedError = error;
    double spanS = 0;
    if (const uint64_t n = frameErrorLog.heldBack(SteadyClock::now(), &spanS))
        SKY_LOG_ERROR("%llu more distinct frame failures in the last %.0f s (status frames_failed and "
                      "last_failed_frame)",
                      (unsigned long long)n, spanS);
    VkDeviceSize memory = 0, hostReadback = 0;
    {
        std::lock_guard<std::mutex> lock(r.memory.mutex);
        memory = r.memory.totalBytes;
        hostReadback = r.memory.hostReadbackBytes;
    }
    std::unique_lock<std::mutex> lock(setup.state->mutex);
    ServiceState& s = *setup.state;
    if (status.ok())
    {
        s.lastFrameId = id;
        ++s.framesRendered;
        s.recordFrameMs(ms);
        s.recordFrameTimes(FrameTimes{id, ms, lastPublishMs, result.cpuSetupMs, result.gpuMs});
        s.frameWeather = FrameWeather{result.weatherVersion, lastDrawn.source, result.weatherValidTimeUnixS, true};
    }
    else
    {
        ++s.framesFailed;
        s.lastFailedFrameId = id;
        s.lastFailedFrameError = error;
    }
    s.weatherPending = weatherSchedule.pending();
    s.windowsMadeOnFramePath = r.weather.prefetch.madeOnFrame;
    s.windowsFromWorker = r.weather.prefetch.used + r.weather.stage.swapped;
    s.lastRenderError = error;
    s.deviceMemoryBytes = memory;
    s.hostReadbackBytes = hostReadback;
    SKY_LOG_DEBUG("frame %llu: %.1f ms", (unsigned long long)id, ms);
    lock.unlock();
    if (setup.frameEnded)
        setup.frameEnded(id, status.ok());
}

bool RenderLoop::Impl::writeFiles(const std::string& prefix, const std::string& format, std::string& error)
{
    RenderFacts facts;
    facts.weatherSource = lastDrawn.source;  // the weather `result` drew
    facts.weatherVersion = lastDrawn.version;
    facts.timeIso = formatIso8601Utc(lastRequest.unixTimeS);
    facts.deviceName = setup.renderer->ctx.deviceName;
    facts.driver = setup.renderer->ctx.driverInfo;
    if (!setup.filesRoot)
    {
        error = "no files_root: the service writes no files";
        return false;
    }
    // `prefix` is relative to files_root, resolved beneath it without following links (files_root.h).
    static const std::vector<std::string> kSuffixes = {".png", ".exr", ".json", "-shadow.exr", "-shadow.png"};
    return setup.filesRoot->writeBeneath(prefix, kSuffixes, [&](const std::string& target, std::string& why) {
        if (!writeRenderFiles(target, lastRequest, result, facts, why))
            return false;
        // writeRenderFiles writes both images; a subscription for one format drops the other.
        std::error_code ignored;
        if (format == "png")
            std::filesystem::remove(target + ".exr", ignored);
        else if (format == "exr")
            std::filesystem::remove(target + ".png", ignored);
        return true;
    }, error);
}

void RenderLoop::Impl::doJob(const RenderJob& job)
{
    std::string error;
    if (job.kind == RenderJob::WriteFiles)
    {
        if (!haveFrame || !resultHasPixels || result.linearRgbaHalf.empty())
        {
            // No frame yet (a `render` just asked for the first), or the last frame's pixels are not on the
            // host (or it has no linear frame for the EXR): render the next one with them, now.
            pendingWriteFiles.push_back(job);
            std::lock_guard<std::mutex> lock(setup.state->mutex);
            setup.state->renderWantedUpTo = std::max(setup.state->renderWantedUpTo, setup.state->framesStarted + 1);
        }
        else if (!writeFiles(job.path, "both", error))
            reply(job.client, failedLine(job.requestId, error));
        else
            reply(job.client, okLine(RequestType::WriteFiles, job.requestId));
        return;
    }
    // SubscribeVulkan: the export is created once, for every later subscriber.
    Renderer& r = *setup.renderer;
    if (!exporter.active() &&
        !exporter.create(r, setup.exportSlots, setup.exportMaxWidth, setup.exportMaxHeight, setup.exportShadowSize, error))
    {
        SKY_LOG_WARN("vulkan subscribe: %s", error.c_str());
        dropUnexportedLayers(job.client);
        reply(job.client, failedLine(job.requestId, "the device cannot export frames: " + error));
        return;
    }
    nlohmann::json body;
    std::vector<int> fds;
    if (!exporter.describe(r, job.layers, body, fds, error))
    {
        SKY_LOG_WARN("vulkan subscribe: %s", error.c_str());
        dropUnexportedLayers(job.client);
        reply(job.client, failedLine(job.requestId, error));
        return;
    }
    nlohmann::json layers = nlohmann::json::array();
    for (const char* name : {"display", "sky", "clouds", "depth"})
        if (((job.layers | (1u << SKY_LAYER_DISPLAY)) & layerBit(name)) != 0)
            layers.push_back(name);
    body["layers"] = std::move(layers);
    body["type"] = "subscribed";
    body["transport"] = "vulkan";
    body["shm_name"] = setup.ring->name();
    body["slots"] = setup.ring->slotCount();
    body["total_bytes"] = setup.ring->totalBytes();
    if (!job.requestId.is_null())
        body["id"] = job.requestId;
    reply(job.client, body.dump(), std::move(fds));
}

}  // namespace sky
