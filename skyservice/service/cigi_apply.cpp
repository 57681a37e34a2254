// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_apply.h"

#include "skyservice/render/view_limits.h"
#include "skyservice/service/cigi_view.h"
#include "skyservice/service/cigi_weather_merge.h"
#include "skyservice/service/log.h"
#include "skyservice/service/weather_schedule.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace sky
{
namespace
{

template <typename Packet> bool contains(const cigi::DecodeResult& datagram)
{
    return std::any_of(datagram.packets.begin(), datagram.packets.end(),
                       [](const cigi::HostPacket& p) { return std::holds_alternative<Packet>(p); });
}

/// Distance (m) between two points, small-distance approximation (the regional grid's drift).
double roughDistanceM(double lat0, double lon0, double lat1, double lon1)
{
    constexpr double kMetresPerDegree = 111195.0;
    double dLon = std::fmod(lon1 - lon0 + 540.0, 360.0) - 180.0;
    return kMetresPerDegree * std::hypot(lat1 - lat0, dLon * std::cos(lat0 * M_PI / 180.0));
}

} // namespace

void CigiApplier::report(Problem problem, bool failed, const std::string& message)
{
    std::string& current = problems_[problem];
    if (failed && current.empty() && problemLogs_[problem].admit(SteadyClock::now()))
        SKY_LOG_WARN("cigi: %s (logged once until it works again)", message.c_str());
    current = failed ? message : std::string();
}

void CigiApplier::logHeldBack(SteadyClock::time_point now)
{
    static const char* const kNames[kProblemCount] = {"ownship pose", "view", "weather"};
    for (size_t k = 0; k < kProblemCount; ++k)
    {
        double spanS = 0;
        if (const uint64_t n = problemLogs_[k].heldBack(now, &spanS))
            SKY_LOG_WARN("cigi: %s failed again %llu more times in the last %.0f s (not logged one by one; status "
                         "cigi.applied shows the current error)",
                         kNames[k], (unsigned long long)n, spanS);
    }
}

double CigiApplier::nowS() const
{
    return std::chrono::duration<double>(SteadyClock::now() - epoch_).count();
}

CigiApplier::Built CigiApplier::weatherIfChanged(const cigi::CigiState& state, double ownLatDeg, double ownLonDeg,
                                                 double simTimeS, double nowS, bool stepDrawn, bool overGridded)
{
    const bool changed = fade_.setTarget(state, nowS);
    if (!fade_.started())
        return {}; // the configured weather stays until the host sets a cloud layer
    const bool fading = fade_.fading(nowS);
    if (changed && fading && !lastBuildFading_)
    {
        // At nowS the fade has not begun (what is drawn is what was): its first step comes a step later.
        lastBuildFading_ = true;
        lastBuildS_ = nowS;
    }
    // A regional grid follows the ownship: remade when it has come a quarter of the way to the grid's edge.
    const bool drifted = weatherGrid_.regional &&
                         roughDistanceM(weatherGrid_.centreLatDeg, weatherGrid_.centreLonDeg, ownLatDeg, ownLonDeg) >
                             0.25 * weatherGrid_.halfExtentM;
    const bool stepDue = lastBuildFading_ && stepDrawn && nowS - lastBuildS_ >= kCigiFadeStepS;
    const bool modeChanged = weatherBuilt_ && overGridded != builtOverGridded_; // a file loaded or dropped
    if (weatherBuilt_ && !drifted && !(changed && !fading) && !stepDue && !modeChanged)
        return {};
    Built built;
    built.smallStep = weatherBuilt_ && lastBuildFading_ && !drifted && !(changed && !fading) && !modeChanged;
    CigiWeatherGrid grid = cigiWeatherGrid(fade_, ownLatDeg, ownLonDeg, overGridded);
    if (overGridded)
        built.overlay = std::make_shared<const CigiOverlay>(fade_, nowS, grid, geoid_, ownLatDeg, ownLonDeg);
    else
    {
        auto timeline = std::make_shared<WeatherTimeline>();
        std::string error;
        if (!timeline->setSnapshots({cigiWeatherSnapshot(fade_, nowS, grid, *geoid_, int64_t(std::floor(simTimeS)))},
                                    error))
        {
            report(kWeather, true, "the host's weather was not drawn: " + error);
            return {};
        }
        built.timeline = std::move(timeline);
    }
    report(kWeather, false, "");
    weatherGrid_ = grid;
    weatherBuilt_ = true;
    builtOverGridded_ = overGridded;
    fadeSteps_ += lastBuildFading_ ? 1 : 0;
    lastBuildFading_ = fading;
    lastBuildS_ = nowS;
    ++weatherBuilds_;
    // The first at info; later ones at debug: a host that ramps a layer changes it every frame.
    if (overGridded)
        logMessage(weatherBuilds_ == 1 ? LogLevel::Info : LogLevel::Debug,
                   "cigi: weather from the host laid over the gridded weather%s%s",
                   grid.regional ? " (regions on a grid around the ownship)" : "", fading ? " (fading in)" : "");
    else
        logMessage(weatherBuilds_ == 1 ? LogLevel::Info : LogLevel::Debug,
                   "cigi: weather from the host: %zu cloud layer(s)%s on a %ux%u grid%s",
                   built.timeline->snapshot(0).layers.size(),
                   built.timeline->snapshot(0).high.coverage.empty() ? "" : " + high cloud", grid.grid.nLat,
                   grid.grid.nLon, fading ? " (fading in)" : "");
    return built;
}

CigiApplier::Built CigiApplier::weatherFor(const cigi::CigiState& state, ServiceState& s, const EyePose* pose,
                                           double nowS)
{
    double ownLat = 0, ownLon = 0, simTimeS = 0;
    bool stepDrawn = false, overGridded = false;
    {
        std::lock_guard<std::mutex> lock(s.mutex);
        ownLat = pose ? pose->latDeg : s.view.pose.latDeg;
        ownLon = pose ? pose->lonDeg : s.view.pose.lonDeg;
        simTimeS = s.clock.nowUnixS();
        stepDrawn = s.frameWeather.known && s.frameWeather.version >= publishedVersion_;
        overGridded = s.weather.timeline && s.weather.timeline != ownTimeline_;
    }
    return weatherIfChanged(state, ownLat, ownLon, simTimeS, nowS, stepDrawn, overGridded);
}

void CigiApplier::install(ServiceState& s, Built weather)
{
    // A file loaded since the build (or ours replaced): drawn as built, but not as a small step from it.
    const bool small = weather.smallStep && s.weather.version == publishedVersion_;
    if (weather.overlay)
        s.weather.overlay = std::move(weather.overlay); // over the file, whose source and timeline stay
    else
    {
        ownTimeline_ = weather.timeline;
        s.weather.timeline = std::move(weather.timeline);
        s.weather.overlay.reset();
        s.weather.source = "cigi";
        s.weather.lastError.clear();
    }
    s.weather.smallStepFrom = small ? s.weather.version : 0;
    publishedVersion_ = ++s.weather.version;
}

void CigiApplier::tick(const cigi::CigiState& state, ServiceState& s)
{
    tick(state, s, nowS());
}

void CigiApplier::tick(const cigi::CigiState& state, ServiceState& s, double nowS)
{
    if (!lastBuildFading_ || nowS - lastBuildS_ < kCigiFadeStepS)
        return;
    Built weather = weatherFor(state, s, nullptr, nowS);
    if (!weather)
        return;
    {
        std::lock_guard<std::mutex> lock(s.mutex);
        install(s, std::move(weather));
    }
    s.wake.notify_all();
}

void CigiApplier::applyTime(const cigi::CigiState& state, ServiceState& s)
{
    // Caller holds s.mutex. CIGI 3.3 sets hours and minutes: a host that resends the same minute every frame
    // must not pull a running clock back to its start, so the clock is re-based only when the minute or the
    // ephemeris flag changes. A change of more than the weather's re-sample interval is a jump in time.
    const cigi::SimulatedTime& t = state.time;
    const double rate = t.ephemerisEnable ? 1.0 : 0.0;
    const SteadyClock::time_point now = SteadyClock::now();
    const double current = s.clock.nowUnixS(now);
    double target = current;
    if (t.valid && std::floor(current / 60.0) != std::floor(t.unixTimeS() / 60.0))
        target = t.unixTimeS();
    if (target == current && rate == s.clock.rate)
        return;
    if (std::fabs(target - current) > kWeatherResampleS)
        ++s.clock.jumps;
    s.clock.baseUnixS = target;
    s.clock.baseReal = now;
    s.clock.rate = rate;
}

void CigiApplier::applyAir(const cigi::CigiState& state, ServiceState& s)
{
    // Caller holds s.mutex. The haze near the ground (skyservice/sky/atmosphere.h setHazeVisibility; 0: the
    // clear atmosphere's) and the global ground fog (setGroundFog): a band at its height above mean sea level
    // under the eye, all around the earth (the atmosphere is a sphere).
    const cigi::AtmosphereState& air = state.atmosphere;
    s.view.visibilityM = air.set && air.visibilityM > 0 ? double(air.visibilityM) : 0.0;
    s.view.fogBaseM = s.view.fogTopM = s.view.fogVisibilityM = 0.0;
    auto fog = state.globalLayers.find(0);
    if (fog == state.globalLayers.end() || !fog->second.enabled || !(fog->second.thicknessM > 0) ||
        !(fog->second.visibilityM > 0))
        return;
    const double n = geoid_->undulationM(s.view.pose.latDeg, s.view.pose.lonDeg);
    const double undulationM = std::isfinite(n) ? n : 0.0;
    s.view.fogBaseM = double(fog->second.baseElevationMslM) + undulationM;
    s.view.fogTopM = s.view.fogBaseM + double(fog->second.thicknessM);
    s.view.fogVisibilityM = double(fog->second.visibilityM);
}

void CigiApplier::apply(const cigi::CigiState& state, const cigi::DecodeResult& datagram, ServiceState& s)
{
    apply(state, datagram, s, nowS());
}

void CigiApplier::apply(const cigi::CigiState& state, const cigi::DecodeResult& datagram, ServiceState& s, double nowS)
{
    if (!datagram.accepted)
        return;
    // The eye and the frustum, and the weather, made before taking the service's lock.
    auto view = state.views.find(viewId_);
    const bool defined = view != state.views.end() && view->second.defined;
    const cigi::ViewState* control = view != state.views.end() && view->second.controlled ? &view->second : nullptr;
    EyePose pose;
    std::string poseWhy, viewWhy;
    const bool havePose = state.ownship.valid && cigiEyePose(state.ownship, control, *geoid_, pose, poseWhy);
    report(kPose, state.ownship.valid && !havePose, "ownship pose not applied: " + poseWhy);
    Frustum frustum;
    double fovYDeg = 0;
    const bool haveFrustum = defined && cigiFrustum(view->second, frustum, fovYDeg, viewWhy);
    report(kView, defined && !haveFrustum, "view not applied: " + viewWhy);

    Built weather = weatherFor(state, s, havePose ? &pose : nullptr, nowS);

    {
        std::lock_guard<std::mutex> lock(s.mutex);
        if (havePose)
            s.view.pose = pose;
        if (haveFrustum)
        {
            s.view.frustum = frustum;
            s.view.fovYDeg = std::clamp(fovYDeg, kMinFovYDeg, kMaxFovYDeg);
            frustumApplied_ = true;
        }
        if (contains<cigi::CelestialSphereControl>(datagram))
            applyTime(state, s);
        applyAir(state, s);
        if (weather)
            install(s, std::move(weather));
        if (s.renderRateHz == 0)
            s.renderWantedUpTo = std::max(s.renderWantedUpTo, s.framesStarted + 1);
    }
    s.wake.notify_all();
}

nlohmann::json CigiApplier::statusJson() const
{
    return {{"weather_builds", weatherBuilds_},
            {"fade_steps", fadeSteps_},
            {"fading", lastBuildFading_},
            {"regional_grid", weatherGrid_.regional},
            {"over_gridded", builtOverGridded_},
            {"frustum_applied", frustumApplied_},
            {"pose_error", problems_[kPose].empty() ? nlohmann::json() : nlohmann::json(problems_[kPose])},
            {"view_error", problems_[kView].empty() ? nlohmann::json() : nlohmann::json(problems_[kView])},
            {"weather_error", problems_[kWeather].empty() ? nlohmann::json() : nlohmann::json(problems_[kWeather])}};
}

} // namespace sky
