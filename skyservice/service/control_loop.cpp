// SPDX-License-Identifier: MIT
#include "skyservice/service/control_loop.h"

#include "skyservice/render/view_validation.h"
#include "skyservice/service/log.h"
#include "skyservice/service/weather_schedule.h"
#include "skyservice/sky/ephemeris.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace sky
{
namespace
{

/// The view as set_view takes it: fov, or the four half-angles of an asymmetric frustum.
nlohmann::json viewJson(const ViewRequest& v)
{
    nlohmann::json j = {{"lat", v.pose.latDeg},         {"lon", v.pose.lonDeg},     {"alt", v.pose.altitudeM},
                        {"heading", v.pose.headingDeg}, {"pitch", v.pose.pitchDeg}, {"roll", v.pose.rollDeg},
                        {"width", v.width},             {"height", v.height}};
    if (v.frustum.asymmetric)
    {
        j["left"] = v.frustum.leftDeg;
        j["right"] = v.frustum.rightDeg;
        j["up"] = v.frustum.upDeg;
        j["down"] = v.frustum.downDeg;
    }
    else
        j["fov"] = v.fovYDeg;
    return j;
}

/// Value at quantile q of `values` (nearest rank), 0 for none.
double quantile(std::vector<double> values, double q)
{
    if (values.empty())
        return 0;
    auto k = size_t(std::min(double(values.size() - 1), std::ceil(q * double(values.size())) - 1));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
}

/// Milliseconds to the microsecond: finer is noise, and the status line has 64 KiB.
double roundedMs(double ms) { return std::round(ms * 1000.0) / 1000.0; }

/// The status reply's `recent_frames`: per published frame (oldest first) its id, wall-clock time, the
/// copy into shared memory, the CPU's preparation of the frame and the GPU time of each pass.
nlohmann::json recentFramesJson(const std::deque<FrameTimes>& frames)
{
    nlohmann::json list = nlohmann::json::array();
    for (const FrameTimes& f : frames)
    {
        nlohmann::json gpu = nlohmann::json::object();
        for (const auto& [pass, ms] : f.gpuMs)
            gpu[pass] = roundedMs(ms);
        list.push_back({{"id", f.frameId}, {"ms", roundedMs(f.frameMs)}, {"publish_ms", roundedMs(f.publishMs)},
                        {"setup_ms", roundedMs(f.setupMs)}, {"gpu_ms", std::move(gpu)}});
    }
    return list;
}

}  // namespace

ControlSocketServer::Handlers ControlLoop::handlers()
{
    ControlSocketServer::Handlers h;
    h.connected = [this](ClientId client) {
        clients_[client] = Client{};
        if (connectionLog_.admit(SteadyClock::now()))
            SKY_LOG_INFO("client %llu connected (uid %u)", (unsigned long long)client, c_.server->peerUid(client));
    };
    h.line = [this](ClientId client, std::string_view line) { onLine(client, line); };
    h.disconnected = [this](ClientId client) {
        auto it = clients_.find(client);
        if (connectionLog_.admit(SteadyClock::now()))
            SKY_LOG_INFO("client %llu (%s) disconnected", (unsigned long long)client,
                         it != clients_.end() && !it->second.name.empty() ? it->second.name.c_str() : "unnamed");
        clients_.erase(client);
        std::lock_guard<std::mutex> lock(c_.state->mutex);
        std::erase_if(c_.state->files, [client](const FilesSubscription& f) { return f.client == client; });
        c_.state->shmLayers.erase(client);
        c_.state->vulkanLayers.erase(client);
    };
    return h;
}

void ControlLoop::sendPendingReplies()
{
    std::deque<PendingReply> replies;
    {
        std::lock_guard<std::mutex> lock(c_.state->mutex);
        replies.swap(c_.state->replies);
    }
    for (PendingReply& r : replies)
    {
        if (clients_.count(r.client))
            c_.server->send(r.client, r.line, r.fds);
        for (int fd : r.fds)  // the server dups what it sends; these copies are ours
            ::close(fd);
    }
}

void ControlLoop::sendError(ClientId client, const nlohmann::json& id, const std::string& code,
                            const std::string& message, const std::string& field)
{
    ProtocolError e;
    e.code = code;
    e.message = message;
    e.field = field;
    e.id = id;
    SKY_LOG_DEBUG("client %llu: %s: %s", (unsigned long long)client, code.c_str(), message.c_str());
    c_.server->send(client, errorReply(e));
}

void ControlLoop::onLine(ClientId client, std::string_view line)
{
    Request request;
    ProtocolError error;
    if (!parseRequest(line, c_.limits, request, error))
    {
        SKY_LOG_DEBUG("client %llu: %s: %s", (unsigned long long)client, error.code.c_str(), error.message.c_str());
        c_.server->send(client, errorReply(error));
        return;
    }
    Client& state = clients_[client];
    if (!state.hello && request.type != RequestType::Hello)
    {
        sendError(client, request.id, "not_hello", "the first request must be hello");
        return;
    }
    dispatch(client, request);
}

void ControlLoop::dispatch(ClientId client, const Request& request)
{
    ServiceState& s = *c_.state;
    switch (request.type)
    {
    case RequestType::Hello:
        if (request.protocol != kProtocolVersion)
        {
            sendError(client, request.id, "bad_version", "this service speaks protocol 1", "protocol");
            return;
        }
        clients_[client].hello = true;
        clients_[client].name = request.clientName;
        c_.server->admit(client);  // past the hello and idle timeouts
        c_.server->send(client, replyWithId(request, {{"type", "hello"},
                                                     {"protocol", kProtocolVersion},
                                                     {"service", "skyservice 0.1"},
                                                     {"recent_frames", recentFramesJson(s.recentFrames)},
            {"device", c_.deviceName},
                                                     {"max_width", c_.limits.maxWidth},
                                                     {"max_height", c_.limits.maxHeight}}));
        return;
    case RequestType::SetView: setView(client, request); return;
    case RequestType::SetTime: setTime(client, request); return;
    case RequestType::LoadWeather:
        if (request.path.empty() || request.path[0] != '/')
        {
            sendError(client, request.id, "out_of_range", "path must be absolute", "path");
            return;
        }
        if (filesRequestLog_.admit(SteadyClock::now()))
            SKY_LOG_INFO("load_weather %s (client %llu)", request.path.c_str(), (unsigned long long)client);
        c_.loader->enqueue(request.path);
        c_.server->send(client, okReply(request, {{"queued", true}}));
        return;
    case RequestType::Subscribe: subscribe(client, request); return;
    case RequestType::Render:
    {
        uint64_t id = 0;
        {
            std::lock_guard<std::mutex> lock(s.mutex);
            id = s.framesStarted + 1;  // the next frame to begin takes this request's view into account
            s.renderWantedUpTo = std::max(s.renderWantedUpTo, id);
        }
        s.wake.notify_all();
        c_.server->send(client, okReply(request, {{"frame_id", id}}));
        return;
    }
    case RequestType::Status:
    {
        nlohmann::json status = statusJson();
        // Why a file was refused (missing, not a file, bad magic...) tells whether a path exists and
        // what it is: only the daemon's own user learns that; others are told "cannot load".
        if (c_.server->peerUid(client) != uint32_t(::geteuid()) && status["weather"]["last_error"].is_string())
        {
            std::lock_guard<std::mutex> lock(s.mutex);
            status["weather"]["last_error"] = s.weather.lastErrorPath + ": cannot load";
        }
        c_.server->send(client, replyWithId(request, status));
        return;
    }
    case RequestType::WriteFiles:
    {
        if (request.path.empty())
        {
            sendError(client, request.id, "missing_field", "write_files needs a prefix", "prefix");
            return;
        }
        std::string why;
        if (!FilesRoot::checkName(request.path, "prefix", why))
        {
            sendError(client, request.id, "out_of_range", why, "prefix");
            return;
        }
        if (filesRequestLog_.admit(SteadyClock::now()))
            SKY_LOG_INFO("write_files %s (client %llu, uid %u)", request.path.c_str(), (unsigned long long)client,
                         c_.server->peerUid(client));
        queueJob(client, request, RenderJob{RenderJob::WriteFiles, client, request.id, request.path});
        return;  // the render thread replies once the files are written
    }
    }
}

void ControlLoop::logHeldBack()
{
    const SteadyClock::time_point now = SteadyClock::now();
    double spanS = 0;
    if (const uint64_t n = connectionLog_.heldBack(now, &spanS))
        SKY_LOG_INFO("%llu more client connects and disconnects in the last %.0f s (not logged one by one)",
                     (unsigned long long)n, spanS);
    if (const uint64_t n = filesRequestLog_.heldBack(now, &spanS))
        SKY_LOG_INFO("%llu more load_weather / write_files / subscribe files requests in the last %.0f s (not "
                     "logged one by one)",
                     (unsigned long long)n, spanS);
}

void ControlLoop::setView(ClientId client, const Request& request)
{
    ServiceState& s = *c_.state;
    std::lock_guard<std::mutex> lock(s.mutex);
    ViewRequest v = s.view;
    const ViewUpdate& u = request.view;
    if (u.lat) v.pose.latDeg = *u.lat;
    if (u.lon) v.pose.lonDeg = *u.lon;
    if (u.alt) v.pose.altitudeM = *u.alt;
    if (u.heading) v.pose.headingDeg = *u.heading;
    if (u.pitch) v.pose.pitchDeg = *u.pitch;
    if (u.roll) v.pose.rollDeg = *u.roll;
    if (u.fov)
    {
        v.fovYDeg = *u.fov;
        v.frustum.asymmetric = false;
    }
    if (u.left)  // parseRequest: the four half-angles come together
        v.frustum = Frustum{true, *u.left, *u.right, *u.up, *u.down};
    if (u.width) v.width = *u.width;
    if (u.height) v.height = *u.height;
    if (v.width > c_.limits.maxWidth || v.height > c_.limits.maxHeight || v.width < 8 || v.height < 8)
    {
        sendError(client, request.id, "out_of_range", "image size outside the service's limits",
                  v.width > c_.limits.maxWidth || v.width < 8 ? "view.width" : "view.height");
        return;
    }
    // parseRequest checked each field it got; this is the check of the whole view, the one the renderer
    // relies on: frames draw s.view without checking it again (view_validation.h).
    std::string why;
    if (!validateView(v, why))
    {
        sendError(client, request.id, "out_of_range", why, "view");
        return;
    }
    s.view = v;
    c_.server->send(client, okReply(request));
}

void ControlLoop::setTime(ClientId client, const Request& request)
{
    ServiceState& s = *c_.state;
    int64_t unixTimeS = 0;
    if (request.timeIso)
    {
        std::string why;
        if (!parseIso8601Utc(*request.timeIso, unixTimeS, why))
        {
            sendError(client, request.id, "out_of_range", "time: " + why, "time");
            return;
        }
    }
    if (!request.timeIso && !request.rate)
    {
        sendError(client, request.id, "missing_field", "set_time needs time and/or rate", "time");
        return;
    }
    {
        std::lock_guard<std::mutex> lock(s.mutex);
        SteadyClock::time_point now = SteadyClock::now();
        double base = request.timeIso ? double(unixTimeS) : s.clock.nowUnixS(now);
        s.clock.baseUnixS = base;
        s.clock.baseReal = now;
        if (request.timeIso)
            ++s.clock.jumps;
        if (request.rate)
            s.clock.rate = *request.rate;
    }
    c_.server->send(client, okReply(request));
}

void ControlLoop::subscribe(ClientId client, const Request& request)
{
    ServiceState& s = *c_.state;
    switch (request.transport)
    {
    case Transport::Shm:
    {
        {
            std::lock_guard<std::mutex> lock(s.mutex);
            s.shmLayers[client] |= request.layers;  // a second subscribe adds layers
        }
        s.wake.notify_all();
        nlohmann::json layers = nlohmann::json::array();
        for (const char* name : {"display", "sky", "clouds", "depth"})
            if (request.layers & layerBit(name))
                layers.push_back(name);
        c_.server->send(client, replyWithId(request, {{"type", "subscribed"},
                                                     {"transport", "shm"},
                                                     {"shm_name", c_.ring->name()},
                                                     {"slots", c_.ring->slotCount()},
                                                     {"total_bytes", c_.ring->totalBytes()},
                                                     {"layers", layers}}));
        return;
    }
    case Transport::Vulkan:
        queueJob(client, request, RenderJob{RenderJob::SubscribeVulkan, client, request.id, "", request.layers});
        return;
    case Transport::Files:
    {
        if (filesRequestLog_.admit(SteadyClock::now()))
            SKY_LOG_INFO("subscribe files %s (client %llu, uid %u)", request.path.c_str(),
                         (unsigned long long)client, c_.server->peerUid(client));
        FilesFolder folder;
        std::string why;
        if (!FilesRoot::checkName(request.path, "dir", why))
        {
            sendError(client, request.id, "out_of_range", why, "dir");
            return;
        }
        if (!c_.filesRoot || !c_.filesRoot->openFolder(request.path, folder, why))
        {
            sendError(client, request.id, "failed", c_.filesRoot ? why : "the service writes no files", "dir");
            return;
        }
        {
            // Every subscription costs each frame it writes: the same dir again replaces the earlier one,
            // and a client holds a few at most.
            std::lock_guard<std::mutex> lock(s.mutex);
            FilesSubscription sub{client, request.path, std::max(request.every, 1u), request.fileFormat};
            auto same = std::find_if(s.files.begin(), s.files.end(), [&](const FilesSubscription& f) {
                return f.client == client && f.dir == sub.dir;
            });
            if (same != s.files.end())
                *same = sub;
            else if (size_t(std::count_if(s.files.begin(), s.files.end(), [&](const FilesSubscription& f) {
                         return f.client == client;
                     })) >= c_.maxFilesSubscriptionsPerClient)
            {
                sendError(client, request.id, "failed",
                          "busy: a client holds at most " + std::to_string(c_.maxFilesSubscriptionsPerClient) +
                              " files subscriptions (the same dir again replaces its subscription)",
                          "dir");
                return;
            }
            else
                s.files.push_back(sub);
        }
        c_.server->send(client, okReply(request, {{"dir", folder.shown}}));  // where the files appear
        return;
    }
    }
}

void ControlLoop::queueJob(ClientId client, const Request& request, RenderJob job)
{
    ServiceState& s = *c_.state;
    size_t queued = 0;
    {
        // The render thread takes jobs before frames: one client's pipelined requests must not stall
        // rendering for everyone.
        std::lock_guard<std::mutex> lock(s.mutex);
        queued = size_t(
            std::count_if(s.jobs.begin(), s.jobs.end(), [client](const RenderJob& j) { return j.client == client; }));
        if (queued < c_.maxQueuedJobsPerClient)
        {
            // A vulkan subscriber's layers count from now on (frames draw them before its job makes their
            // exported images); this thread's disconnect handler drops them, whatever the job's fate.
            if (job.kind == RenderJob::SubscribeVulkan)
                s.vulkanLayers[client] |= job.layers & ~(1u << SKY_LAYER_DISPLAY);
            s.jobs.push_back(std::move(job));
        }
    }
    if (queued >= c_.maxQueuedJobsPerClient)
    {
        sendError(client, request.id, "failed",
                  "busy: " + std::to_string(queued) +
                      " of this client's write_files / subscribe vulkan requests are still queued; wait for their "
                      "replies");
        return;
    }
    s.wake.notify_all();
}

nlohmann::json ControlLoop::statusJson()
{
    ServiceState& s = *c_.state;
    // Before ServiceState's mutex: the CIGI link takes its own lock first, then that one.
    nlohmann::json cigi = c_.cigi ? c_.cigi->statusJson() : nlohmann::json();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (c_.cigi)
        cigi["frustum"] = {{"asymmetric", s.view.frustum.asymmetric}, {"left", s.view.frustum.leftDeg},
                           {"right", s.view.frustum.rightDeg},        {"up", s.view.frustum.upDeg},
                           {"down", s.view.frustum.downDeg}};
    nlohmann::json weather = {{"source", weatherName(s.weather)}, {"valid_time", nullptr}, {"last_error", nullptr}};
    if (s.weather.timeline && !s.weather.timeline->empty())
    {
        weather["valid_time"] = formatIso8601Utc(s.weather.timeline->firstTimeUnixS());
        weather["valid_time_last"] = formatIso8601Utc(s.weather.timeline->lastTimeUnixS());
    }
    if (!s.weather.lastError.empty())
        weather["last_error"] = s.weather.lastError;
    weather["version"] = s.weather.version;
    weather["frame"] = nullptr;
    if (s.frameWeather.known)
        weather["frame"] = {{"version", s.frameWeather.version},
                            {"source", s.frameWeather.source},
                            {"valid_time", formatIso8601Utc(s.frameWeather.validTimeUnixS)}};
    weather["pending"] = s.weatherPending;
    double uptime = std::chrono::duration<double>(SteadyClock::now() - c_.startedAt).count();
    double simNow = s.clock.nowUnixS();
    return {{"type", "status"},
            {"frame_id", s.lastFrameId},
            {"frames_rendered", s.framesRendered},
            {"frame_ms",
             {{"last", s.frameMs.empty() ? 0.0 : s.frameMs[(s.frameMsNext + s.frameMs.size() - 1) % s.frameMs.size()]},
              {"median", quantile(s.frameMs, 0.5)},
              {"p95", quantile(s.frameMs, 0.95)}}},
            {"recent_frames", recentFramesJson(s.recentFrames)},
            {"device", c_.deviceName},
            {"driver", c_.driver},
            {"device_memory_bytes", s.deviceMemoryBytes},
            {"host_readback_bytes", s.hostReadbackBytes},
            {"view", viewJson(s.view)},
            {"time", formatIso8601Utc(int64_t(std::floor(simNow)))},
            {"time_unix_s", simNow},
            {"rate", s.clock.rate},
            {"render_rate_hz", s.renderRateHz},
            {"weather", weather},
            {"windows", {{"made_on_frame_path", s.windowsMadeOnFramePath}, {"from_worker", s.windowsFromWorker}}},
            {"last_render_error", s.lastRenderError.empty() ? nlohmann::json() : nlohmann::json(s.lastRenderError)},
            {"frames_failed", s.framesFailed},
            {"last_failed_frame",
             s.lastFailedFrameId == 0
                 ? nlohmann::json()
                 : nlohmann::json{{"frame_id", s.lastFailedFrameId}, {"error", s.lastFailedFrameError}}},
            {"cigi", cigi},
            {"clients", c_.server->clientCount()},
            {"uptime_s", uptime}};
}

}  // namespace sky
