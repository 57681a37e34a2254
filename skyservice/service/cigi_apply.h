// SPDX-License-Identifier: MIT
// Applies the CIGI host's state to the service's next frame, as a set_view, set_time or load_weather
// would: the eye and frustum of this daemon's view, the simulated clock, and the host's cloud layers as a
// one-snapshot weather timeline (source "cigi") swapped in through WeatherState, so the render loop stages
// it off the frame path (weather_schedule.h) and draws it from the first frame after it is ready.
//
// One host datagram is one consistent update: everything it changes lands under one lock of
// ServiceState's mutex, so a frame never draws half of it. The snapshot is built before that lock (and
// only when what is drawn changed: hosts resend Weather Control every frame).
#pragma once

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/service/cigi_weather.h"
#include "skyservice/service/service_state.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace sky
{

class CigiApplier
{
  public:
    /// `geoid` must outlive the applier (an empty grid: altitudes taken as ellipsoid heights).
    CigiApplier(uint16_t viewId, const cigi::GeoidGrid& geoid) : viewId_(viewId), geoid_(geoid) {}

    /// After `datagram` was applied to `state`: updates `service` (taking its mutex). With render rate 0
    /// every accepted datagram asks for one frame: the host paces the IG.
    void apply(const cigi::CigiState& state, const cigi::DecodeResult& datagram, ServiceState& service);

    /// What was applied last, for the status reply.
    nlohmann::json statusJson() const;

  private:
    void applyView(const cigi::CigiState& state, ServiceState& service);
    void applyTime(const cigi::CigiState& state, ServiceState& service);
    /// Builds the snapshot when what is drawn changed; null when nothing is to be swapped in.
    std::shared_ptr<const WeatherTimeline> weatherIfChanged(const cigi::CigiState& state, double ownLatDeg,
                                                            double ownLonDeg, double simTimeS);
    /// What can fail when applying: each is logged when it starts failing, not again until it has worked.
    enum Problem
    {
        kPose,
        kView,
        kWeather,
        kProblemCount
    };
    void report(Problem problem, bool failed, const std::string& message);

    uint16_t viewId_;
    const cigi::GeoidGrid& geoid_;
    std::vector<double> weatherSignature_;
    CigiWeatherGrid weatherGrid_;
    bool weatherBuilt_ = false;
    uint64_t weatherBuilds_ = 0;
    std::array<std::string, kProblemCount> problems_; ///< the current failure of each ("" = none)
    bool frustumApplied_ = false;
};

} // namespace sky
