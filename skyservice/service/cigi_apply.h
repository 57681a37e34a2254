// SPDX-License-Identifier: MIT
// Applies the CIGI host's state to the service's next frame, as a set_view, set_time or load_weather
// would: the eye and frustum of this daemon's view, the simulated clock, and the host's cloud layers as a
// one-snapshot weather timeline (source "cigi") swapped in through WeatherState, so the render loop stages
// it off the frame path (weather_schedule.h) and draws it from the first frame after it is ready.
//
// With a gridded weather loaded (a file: WeatherState::timeline that is not this applier's own) the host's
// weather is not a timeline of its own but a WeatherOverlay laid over each of the file's samples
// (cigi_weather_merge.h): the file stays the global weather except where the host sets global layers, and
// the regions blend into it. Without one (the built-in scene) the host's weather replaces it, as a
// one-snapshot timeline. Which of the two is redecided with every datagram (a file loaded or dropped).
//
// A change of the host's weather fades in (cigi_weather_fade.h): while a fade is under way the snapshot (or
// overlay) of what is drawn is remade every kCigiFadeStepS of IG time and swapped in like any other, the
// next step only once the frames draw the last one (a step's window is made on the worker thread; staging
// faster than that would only replace steps never drawn). A step is published as a small step
// (WeatherState::smallStepFrom), so the renderer keeps its reprojection history across it: the reconstruct
// pass's colour clamp follows clouds that change this little. Any other new weather drops the history.
//
// One host datagram is one consistent update: everything it changes lands under one lock of
// ServiceState's mutex, so a frame never draws half of it. The snapshot is built before that lock (and
// only when what is drawn changed: hosts resend Weather Control every frame).
#pragma once

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/service/cigi_weather.h"
#include "skyservice/service/cigi_weather_fade.h"
#include "skyservice/service/log_limiter.h"
#include "skyservice/service/service_state.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace sky
{

/// While a fade is under way, its snapshot is remade this often (s of IG time): 20 steps over kCigiFadeS,
/// each moving a layer's coverage by at most ~8 % of the change.
inline constexpr double kCigiFadeStepS = 0.25;

class CigiApplier
{
  public:
    /// `geoid` is copied (an empty grid: altitudes taken as ellipsoid heights): overlays share it with the
    /// renderer's worker thread.
    CigiApplier(uint16_t viewId, const cigi::GeoidGrid& geoid)
        : viewId_(viewId), geoid_(std::make_shared<const cigi::GeoidGrid>(geoid))
    {
    }

    /// After `datagram` was applied to `state`: updates `service` (taking its mutex). With render rate 0
    /// every accepted datagram asks for one frame: the host paces the IG.
    /// `nowS`: IG time (s, steady; the fades run on it); without it, the steady clock since construction.
    void apply(const cigi::CigiState& state, const cigi::DecodeResult& datagram, ServiceState& service);
    void apply(const cigi::CigiState& state, const cigi::DecodeResult& datagram, ServiceState& service, double nowS);

    /// Between datagrams: the next step of a fade under way, when one is due (a host that sent one change
    /// and went quiet still sees it fade in).
    void tick(const cigi::CigiState& state, ServiceState& service);
    void tick(const cigi::CigiState& state, ServiceState& service, double nowS);
    /// A fade is under way: call tick at least every kCigiFadeStepS.
    bool fading() const { return lastBuildFading_; }
    /// IG time now (s since construction).
    double nowS() const;

    /// What was applied last, for the status reply.
    nlohmann::json statusJson() const;

    /// Logs how often each problem came back within the last window (a host that alternates good and bad
    /// datagrams): call now and then, also while the host is quiet.
    void logHeldBack(SteadyClock::time_point now);

  private:
    void applyView(const cigi::CigiState& state, ServiceState& service);
    void applyTime(const cigi::CigiState& state, ServiceState& service);
    /// Atmosphere Control's visibility and the global ground fog (layer 0) as the frame's haze and fog.
    void applyAir(const cigi::CigiState& state, ServiceState& service);
    /// What a build made: the host's weather as its own timeline, or as an overlay over a gridded weather.
    struct Built
    {
        std::shared_ptr<const WeatherTimeline> timeline;
        std::shared_ptr<const WeatherOverlay> overlay;
        bool smallStep = false; ///< a step of a fade under way: a small change from the last one published
        explicit operator bool() const { return timeline || overlay; }
    };
    /// Builds the snapshot when what is drawn changed or a fade step is due; empty when nothing is to be
    /// swapped in. `stepDrawn`: the frames draw the last snapshot published. `overGridded`: a gridded weather
    /// is loaded (an overlay is built).
    Built weatherIfChanged(const cigi::CigiState& state, double ownLatDeg, double ownLonDeg, double simTimeS,
                           double nowS, bool stepDrawn, bool overGridded);
    /// weatherIfChanged with the ownship (pose, or the service's eye when null) and the service's clock.
    Built weatherFor(const cigi::CigiState& state, ServiceState& service, const EyePose* pose, double nowS);
    /// Caller holds service.mutex.
    void install(ServiceState& service, Built weather);
    /// What can fail when applying: each is logged when it starts failing, not again until it has worked,
    /// and at most once per window of its limiter (a host can make it start failing with every datagram).
    enum Problem
    {
        kPose,
        kView,
        kWeather,
        kProblemCount
    };
    void report(Problem problem, bool failed, const std::string& message);

    uint16_t viewId_;
    std::shared_ptr<const cigi::GeoidGrid> geoid_;
    SteadyClock::time_point epoch_ = SteadyClock::now();
    CigiWeatherFade fade_;
    CigiWeatherGrid weatherGrid_;
    bool weatherBuilt_ = false;
    bool builtOverGridded_ = false;                       ///< the last build was an overlay
    std::shared_ptr<const WeatherTimeline> ownTimeline_; ///< the last timeline of our own published
    bool lastBuildFading_ = false;  ///< the last snapshot built was a fade step: more are to come
    double lastBuildS_ = 0;         ///< IG time of the last snapshot built (or of the change a fade began with)
    uint64_t publishedVersion_ = 0; ///< WeatherState::version of the last snapshot swapped in
    uint64_t weatherBuilds_ = 0, fadeSteps_ = 0;
    std::array<std::string, kProblemCount> problems_; ///< the current failure of each ("" = none)
    std::array<LogLimiter, kProblemCount> problemLogs_;
    bool frustumApplied_ = false;
};

} // namespace sky
