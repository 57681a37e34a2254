// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_client_run.h"

#include "skyservice/bench/service_frame_wait.h"
#include "skyservice/bench/service_host_metrics.h"
#include "skyservice/bench/service_session.h"

#include <GeographicLib/Geodesic.hpp>
#include <algorithm>
#include <chrono>
#include <thread>

namespace sky
{
namespace
{

using Clock = std::chrono::steady_clock;

// Where the read of a frame's bytes ends up, so that the compiler keeps the loads.
volatile uint64_t gTouchSink = 0;

constexpr size_t kPageBytes = 4096;

void touchPages(const uint8_t* bytes, size_t size)
{
    uint64_t sum = 0;
    for (size_t at = 0; bytes != nullptr && at < size; at += kPageBytes)
        sum += bytes[at];
    gTouchSink = gTouchSink + sum;
}

double msBetween(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// The client side of one run: its connection, its transport, and the frame in hand.
class Session
{
  public:
    explicit Session(const ServiceRunSettings& s) : s_(s) {}

    bool open(ServiceRunResult& out, std::string& error)
    {
        if (!c_.open(s_.socketPath, "sky-service-bench", error))
            return false;
        if (s_.transport == "vulkan")
        {
            SkyExportedFrames exported{};
            if (sky_client_subscribe_vulkan_layers(c_.get(), s_.layers, &exported) != SKY_OK)
            {
                error = c_.why("subscribe vulkan");
                return false;
            }
            if (!wait_.open(exported, error))
                return false;
            out.timelineSemaphore = wait_.hasSemaphore();
            return true;
        }
        if (sky_client_subscribe_shm_layers(c_.get(), s_.layers) != SKY_OK)
        {
            error = c_.why("subscribe shm");
            return false;
        }
        return true;
    }

    SkyClient* client() const { return c_.get(); }
    std::string why(const std::string& what) const { return c_.why(what); }

    /**
     * Waits for a frame newer than `afterId` of the run's size, acquires it and reads it (or waits for
     * the GPU to finish it). `frame` is held on success: release it with release().
     */
    bool take(uint64_t afterId, SkyFrame& frame, std::string& error)
    {
        const int timeoutMs = int(s_.frameTimeoutS * 1000.0);
        for (;;)
        {
            SkyResult r = sky_client_wait_frame(c_.get(), afterId, timeoutMs);
            if (r == SKY_ERR_TIMEOUT)
            {
                error = "no frame after id " + std::to_string(afterId) + " within " +
                        std::to_string(int(s_.frameTimeoutS)) + " s";
                return false;
            }
            if (r != SKY_OK)
            {
                error = c_.why("wait_frame");
                return false;
            }
            if (sky_client_acquire_frame(c_.get(), &frame) != SKY_OK)
            {
                error = c_.why("acquire_frame");
                return false;
            }
            // A frame of an older view size (a run that just changed it) is not the run's.
            if (frame.frame_id > afterId && frame.width == s_.width && frame.height == s_.height)
                break;
            if (frame.frame_id > afterId)
                afterId = frame.frame_id;
            sky_client_release_frame(c_.get(), &frame);
        }
        if (s_.transport == "vulkan")
            return wait_.wait(frame.frame_id, uint64_t(s_.frameTimeoutS * 1e9), error);
        if (frame.pixels == nullptr || frame.format != SKY_FORMAT_RGBA8_SRGB)
        {
            error = "the shared-memory frame " + std::to_string(frame.frame_id) + " has no RGBA8 pixels (format " +
                    std::to_string(frame.format) + ")";
            return false;
        }
        touchPages(frame.pixels, size_t(frame.row_bytes) * frame.height);
        for (uint32_t k = 1; k < SKY_LAYER_COUNT; ++k)
        {
            if ((s_.layers & (1u << k)) == 0)
                continue;
            if (frame.layers[k].pixels == nullptr)
            {
                error = "the shared-memory frame " + std::to_string(frame.frame_id) + " lacks layer " +
                        std::to_string(k) + " it subscribed to";
                return false;
            }
            touchPages(frame.layers[k].pixels, size_t(frame.layers[k].row_bytes) * frame.height);
        }
        if (frame.shadow_transmittance != nullptr)
            touchPages(reinterpret_cast<const uint8_t*>(frame.shadow_transmittance),
                       size_t(frame.shadow_size) * frame.shadow_size * sizeof(float));
        return true;
    }

    /// Returns false only on a failure; a torn frame counts in out.torn when `timed`.
    bool release(const SkyFrame& frame, bool timed, ServiceRunResult& out, std::string& error)
    {
        SkyResult r = sky_client_release_frame(c_.get(), &frame);
        if (r == SKY_ERR_TORN)
        {
            out.torn += timed ? 1 : 0;
            return true;
        }
        if (r != SKY_OK)
        {
            error = c_.why("release_frame");
            return false;
        }
        return true;
    }

  private:
    const ServiceRunSettings& s_;
    ServiceConnection c_;
    FrameCompletionWait wait_;
};

/// The daemon's counters at the start of the timed part.
struct DaemonMark
{
    double cpuS = -1;
    uint64_t framesRendered = 0;
};

bool markDaemon(const ServiceRunSettings& s, SkyClient* client, DaemonMark& mark, nlohmann::json& status,
                std::string& error)
{
    if (!readServiceStatus(client, status, error))
        return false;
    mark.framesRendered = status.value("frames_rendered", uint64_t(0));
    mark.cpuS = processCpuTimeS(s.daemonPid);
    return true;
}

bool finishDaemon(const ServiceRunSettings& s, SkyClient* client, const DaemonMark& start, ServiceRunResult& out,
                  std::string& error)
{
    // The daemon publishes a frame before it counts it in its status, so the frame last taken may not be counted
    // yet when the client asks: read again (briefly) until every frame the client took is there.
    constexpr auto kCountSettlesWithin = std::chrono::seconds(2);
    const Clock::time_point giveUp = Clock::now() + kCountSettlesWithin;
    DaemonMark end;
    nlohmann::json status;
    do
    {
        if (!markDaemon(s, client, end, status, error))
            return false;
        if (end.framesRendered - start.framesRendered >= out.frames)
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    } while (Clock::now() < giveUp);
    out.daemonFrames = end.framesRendered - start.framesRendered;
    out.daemonFrameMs = status.contains("frame_ms") ? status["frame_ms"] : nlohmann::json(nullptr);
    if (start.cpuS >= 0 && end.cpuS >= 0)
    {
        out.daemonCpuS = end.cpuS - start.cpuS;
        if (out.daemonFrames > 0)
            out.daemonCpuMsPerFrame = 1000.0 * out.daemonCpuS / double(out.daemonFrames);
    }
    return true;
}

SkyShmView sceneView(const ServiceRunSettings& s)
{
    SkyShmView v{};
    v.lat_deg = s.scene.pose.latDeg;
    v.lon_deg = s.scene.pose.lonDeg;
    v.alt_m = s.scene.pose.altitudeM;
    v.heading_deg = s.scene.pose.headingDeg;
    v.pitch_deg = s.scene.pose.pitchDeg;
    v.roll_deg = s.scene.pose.rollDeg;
    v.fov_deg = s.scene.fovYDeg;
    v.width = s.width;
    v.height = s.height;
    return v;
}

bool runOnRequest(const ServiceRunSettings& s, Session& session, ServiceRunResult& out, std::string& error)
{
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    SkyShmView view = sceneView(s);
    DaemonMark mark;
    nlohmann::json status;
    Clock::time_point timedStart, lastInHand;
    bool haveLast = false;
    for (uint32_t i = 0; i < s.warmup + s.frames; ++i)
    {
        const bool timed = i >= s.warmup;
        if (i == s.warmup)
        {
            if (!markDaemon(s, session.client(), mark, status, error))
                return false;
            timedStart = Clock::now();
        }
        if (!s.path.empty())
        {
            const EyePose& eye = s.path[timed ? std::min<size_t>(i - s.warmup, s.path.size() - 1) : 0];
            view.lat_deg = eye.latDeg;
            view.lon_deg = eye.lonDeg;
            view.alt_m = eye.altitudeM;
            view.heading_deg = eye.headingDeg;
            view.pitch_deg = eye.pitchDeg;
            view.roll_deg = eye.rollDeg;
        }
        else if (i > 0) // one 60 Hz frame of flight along the heading, as sky-bench --speed
            geodesic.Direct(view.lat_deg, view.lon_deg, view.heading_deg, s.speedMps / 60.0, view.lat_deg,
                            view.lon_deg);
        const Clock::time_point asked = Clock::now();
        if (sky_client_set_view(session.client(), &view) != SKY_OK)
        {
            error = session.why("set_view");
            return false;
        }
        uint64_t frameId = 0;
        if (sky_client_request_frame(session.client(), &frameId) != SKY_OK)
        {
            error = session.why("render");
            return false;
        }
        SkyFrame frame{};
        if (!session.take(frameId > 0 ? frameId - 1 : 0, frame, error))
            return false;
        const Clock::time_point inHand = Clock::now();
        if (!session.release(frame, timed, out, error))
            return false;
        if (timed)
        {
            out.latencyMs.push_back(msBetween(asked, inHand));
            out.inHandS.push_back(msBetween(timedStart, inHand) / 1000.0);
            out.frameIds.push_back(frame.frame_id);
            if (haveLast)
                out.intervalMs.push_back(msBetween(lastInHand, inHand));
            ++out.frames;
        }
        lastInHand = inHand;
        haveLast = true;
    }
    out.elapsedS = std::chrono::duration<double>(lastInHand - timedStart).count();
    return finishDaemon(s, session.client(), mark, out, error);
}

bool runAtServiceRate(const ServiceRunSettings& s, Session& session, ServiceRunResult& out, std::string& error)
{
    SkyShmView view = sceneView(s);
    if (sky_client_set_view(session.client(), &view) != SKY_OK)
    {
        error = session.why("set_view");
        return false;
    }
    DaemonMark mark;
    nlohmann::json status;
    Clock::time_point timedStart, lastInHand;
    uint64_t lastId = 0;
    for (uint32_t i = 0; i < s.warmup + s.frames; ++i)
    {
        const bool timed = i >= s.warmup;
        if (i == s.warmup)
        {
            if (!markDaemon(s, session.client(), mark, status, error))
                return false;
            timedStart = Clock::now();
        }
        SkyFrame frame{};
        if (!session.take(lastId, frame, error))
            return false;
        const Clock::time_point inHand = Clock::now();
        if (!session.release(frame, timed, out, error))
            return false;
        if (timed)
        {
            if (lastId > 0)
                out.skipped += frame.frame_id - lastId - 1;
            out.intervalMs.push_back(msBetween(i == s.warmup ? timedStart : lastInHand, inHand));
            ++out.frames;
        }
        lastId = frame.frame_id;
        lastInHand = inHand;
    }
    out.elapsedS = std::chrono::duration<double>(lastInHand - timedStart).count();
    return finishDaemon(s, session.client(), mark, out, error);
}

} // namespace

bool runServiceClient(const ServiceRunSettings& s, ServiceRunResult& out, std::string& error)
{
    out = ServiceRunResult{};
    out.width = s.width;
    out.height = s.height;
    out.transport = s.transport;
    Session session(s);
    if (!session.open(out, error))
        return false;
    bool ok = s.onRequest ? runOnRequest(s, session, out, error) : runAtServiceRate(s, session, out, error);
    if (ok && out.elapsedS > 0)
        out.deliveredFps = double(out.frames) / out.elapsedS;
    return ok;
}

} // namespace sky
