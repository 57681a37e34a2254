// SPDX-License-Identifier: MIT
#include "skyservice/service/render_loop.h"

#include "skyservice/app/render_files.h"
#include "skyservice/ipc/protocol.h"
#include "skyservice/service/log.h"
#include "skyservice/service/vulkan_export.h"
#include "skyservice/service/weather_schedule.h"
#include "skyservice/sky/ephemeris.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace sky
{
namespace
{

double lonToRange(double lonDeg)
{
    double l = std::fmod(lonDeg + 180.0, 360.0);
    return (l < 0 ? l + 360.0 : l) - 180.0;
}

double jsonNumber(const nlohmann::json& j, const char* a, const char* b)
{
    if (j.contains(a) && j[a].contains(b) && j[a][b].is_number())
        return j[a][b].get<double>();
    return 0;
}

SkyShmShadowGeoRef shadowGeoRef(const RenderResult& result)
{
    SkyShmShadowGeoRef g{};
    if (result.shadowMapSize == 0)
        return g;
    const nlohmann::json& j = result.shadowMap;
    g.centre_lat_deg = jsonNumber(j, "centre", "latDeg");
    g.centre_lon_deg = jsonNumber(j, "centre", "lonDeg");
    g.extent_m = j.value("extentM", 0.0);
    const char* corners[4] = {"northWest", "northEast", "southEast", "southWest"};
    for (int i = 0; i < 4; ++i)
    {
        const nlohmann::json& c = j.contains("corners") ? j["corners"] : nlohmann::json::object();
        g.corner_lat_deg[i] = jsonNumber(c, corners[i], "latDeg");
        g.corner_lon_deg[i] = jsonNumber(c, corners[i], "lonDeg");
    }
    g.sun_azimuth_deg = jsonNumber(j, "keyLightDirection", "azimuthDeg");
    g.sun_elevation_deg = jsonNumber(j, "keyLightDirection", "elevationDeg");
    g.size_texels = result.shadowMapSize;
    g.light_is_moon = j.value("keyLight", std::string()) == "moon" ? 1u : 0u;
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

struct RenderLoop::Impl
{
    Setup setup;
    RenderResult result;
    ViewRequest lastRequest;
    bool haveFrame = false;
    WeatherSchedule weatherSchedule;
    VulkanExport exporter;
    std::string lastLoggedError;
    /// write_files requests that came while the frames had no linear frame (no EXR subscription): they
    /// are written after the next frame, which makes it.
    std::vector<RenderJob> pendingWriteFiles;

    void run();
    void renderFrame(uint64_t id, ViewRequest request, const SimClock& clock, double simTimeS,
                     const WeatherState& weather, const QualitySettings& quality,
                     const std::vector<FilesSubscription>& files);
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

void RenderLoop::Impl::run()
{
    ServiceState& s = *setup.state;
    SteadyClock::time_point nextDue = SteadyClock::now();
    for (;;)
    {
        std::unique_lock<std::mutex> lock(s.mutex);
        for (;;)
        {
            if (s.stop)
                return;
            if (!s.jobs.empty() || s.renderWantedUpTo > s.framesStarted)
                break;
            if (s.renderRateHz > 0)
            {
                if (SteadyClock::now() >= nextDue)
                    break;
                s.wake.wait_until(lock, nextDue);
            }
            else
                s.wake.wait(lock);
        }
        if (!s.jobs.empty())
        {
            RenderJob job = s.jobs.front();
            s.jobs.pop_front();
            lock.unlock();
            doJob(job);
            continue;
        }
        uint64_t id = ++s.framesStarted;
        ViewRequest request = s.view;
        SteadyClock::time_point now = SteadyClock::now();
        SimClock clock = s.clock;
        double simTimeS = clock.nowUnixS(now);
        WeatherState weather = s.weather;
        QualitySettings quality = s.quality;
        std::vector<FilesSubscription> files = s.files;
        if (s.renderRateHz > 0)
        {
            auto period = std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(1.0 / s.renderRateHz));
            // Keep the cadence, but never try to catch up on frames missed while rendering was slow.
            nextDue = std::max(nextDue + period, now);
        }
        lock.unlock();
        renderFrame(id, request, clock, simTimeS, weather, quality, files);
    }
}

void RenderLoop::Impl::renderFrame(uint64_t id, ViewRequest request, const SimClock& clock, double simTimeS,
                                   const WeatherState& weather, const QualitySettings& quality,
                                   const std::vector<FilesSubscription>& files)
{
    Renderer& r = *setup.renderer;
    auto start = SteadyClock::now();
    request.unixTimeS = int64_t(std::floor(simTimeS));
    weatherSchedule.beforeFrame(r, weather, clock, simTimeS);  // a new weather is prepared off this thread
    // The linear frame (16.6 MB at 1080p) only for EXR files: a files subscription that writes them, or a
    // write_files request waiting for this frame.
    QualitySettings frameQuality = quality;
    frameQuality.linearOutput = !pendingWriteFiles.empty() ||
                                std::any_of(files.begin(), files.end(),
                                            [](const FilesSubscription& f) { return f.format != "png"; });
    SkyStatus status = renderView(r, request, frameQuality, result);
    weatherSchedule.afterFrame(r);
    double ms = std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count();
    std::string error;
    if (status.ok())
    {
        haveFrame = true;
        lastRequest = request;
        ShmFrame f;
        f.frameId = id;
        f.simTimeUnixS = simTimeS;
        f.exposure = result.exposure;
        f.view = SkyShmView{request.pose.latDeg, lonToRange(request.pose.lonDeg), request.pose.altitudeM,
                            request.pose.headingDeg, request.pose.pitchDeg, request.pose.rollDeg, request.fovYDeg,
                            request.width, request.height};
        f.format = SKY_FORMAT_RGBA8_SRGB;
        f.width = result.width;
        f.height = result.height;
        f.rowBytes = result.width * 4;
        f.pixels = result.displayRgba8.data();
        if (result.shadowMapSize > 0)
        {
            f.shadowTransmittance = result.shadowTransmittance.data();
            f.shadow = shadowGeoRef(result);
        }
        uint32_t slot = setup.ring->beginSlot();
        if (exporter.active() && !exporter.exportFrame(r, slot, id, result, error))
            SKY_LOG_WARN("frame %llu: zero-copy export: %s", (unsigned long long)id, error.c_str());
        if (!setup.ring->endSlot(f, error))
            SKY_LOG_WARN("frame %llu: not published: %s", (unsigned long long)id, error.c_str());
        error.clear();
    }
    else
    {
        error = status.message;
        if (error != lastLoggedError)  // one line per distinct failure, not one per frame
            SKY_LOG_ERROR("frame %llu: %s", (unsigned long long)id, error.c_str());
    }
    lastLoggedError = error;
    for (const FilesSubscription& sub : files)
    {
        if (!haveFrame || !status.ok() || id % sub.every != 0)
            continue;
        char name[32];
        std::snprintf(name, sizeof name, "/frame-%08llu", (unsigned long long)id);
        std::string why;
        if (!writeFiles(sub.dir + name, sub.format, why))
            SKY_LOG_WARN("files subscription: %s", why.c_str());
    }
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
    VkDeviceSize memory = 0;
    {
        std::lock_guard<std::mutex> lock(r.memory.mutex);
        memory = r.memory.totalBytes;
    }
    std::lock_guard<std::mutex> lock(setup.state->mutex);
    ServiceState& s = *setup.state;
    if (status.ok())
    {
        s.lastFrameId = id;
        ++s.framesRendered;
        s.recordFrameMs(ms);
        const DrawnWeather& drawn = weatherSchedule.drawn();
        s.frameWeather = FrameWeather{drawn.serviceVersion, drawn.source, result.weatherValidTimeUnixS, true};
    }
    s.weatherPending = weatherSchedule.pending();
    s.windowsMadeOnFramePath = r.windowPrefetch.madeOnFrame;
    s.windowsFromWorker = r.windowPrefetch.used + r.weatherStage.swapped;
    s.lastRenderError = error;
    s.deviceMemoryBytes = memory;
    SKY_LOG_DEBUG("frame %llu: %.1f ms", (unsigned long long)id, ms);
}

bool RenderLoop::Impl::writeFiles(const std::string& prefix, const std::string& format, std::string& error)
{
    RenderFacts facts;
    facts.weatherSource = weatherSchedule.drawn().source;  // afterFrame: the weather `result` drew
    facts.weatherVersion = weatherSchedule.drawn().serviceVersion;
    facts.timeIso = formatIso8601Utc(lastRequest.unixTimeS);
    facts.deviceName = setup.renderer->ctx.deviceName;
    facts.driver = setup.renderer->ctx.driverInfo;
    if (!writeRenderFiles(prefix, lastRequest, result, facts, error))
        return false;
    // writeRenderFiles writes both images; a subscription for one format drops the other.
    std::error_code ignored;
    if (format == "png")
        std::filesystem::remove(prefix + ".exr", ignored);
    else if (format == "exr")
        std::filesystem::remove(prefix + ".png", ignored);
    return true;
}

void RenderLoop::Impl::doJob(const RenderJob& job)
{
    std::string error;
    if (job.kind == RenderJob::WriteFiles)
    {
        if (!haveFrame)
            reply(job.client, failedLine(job.requestId, "no frame has been rendered yet"));
        else if (result.linearRgbaHalf.empty())
        {
            // The last frame has no linear frame for the EXR: render the next one with it, now.
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
        reply(job.client, failedLine(job.requestId, "the device cannot export frames: " + error));
        return;
    }
    nlohmann::json body;
    std::vector<int> fds;
    if (!exporter.describe(r, body, fds, error))
    {
        reply(job.client, failedLine(job.requestId, error));
        return;
    }
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
