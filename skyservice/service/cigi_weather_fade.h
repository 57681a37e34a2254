// SPDX-License-Identifier: MIT
// The host's weather as drawn while its changes fade in: a new or changed cloud layer (global or
// regional) ramps from what was drawn to what the host set, a region that appears ramps its weight in, and
// one that is destroyed (or made inactive) ramps it out before it is forgotten. Every ramp is a smoothstep
// over kCigiFadeS of IG time (the daemon's steady clock, not the simulated clock a host often freezes).
//
// The CIGI 3.3 ICD names no fade duration (a layer's Transition Band is vertical, a region's Transition
// Perimeter horizontal); what it asks for is that weather changes do not pop. Five seconds is our choice:
// slower than a frame-to-frame pop is noticed, faster than a host that ramps weather itself would see lag.
//
// Each layer keeps two things: what was drawn when its last change came (`from`, a uniform layer at a weight:
// a change that comes while another is fading folds the drawn mix into `from`, so nothing jumps) and the
// host's layer (`to`). At a point the layer drawn is the weather under it (for a region: the global layers
// and the regions before it) with `from` blended in at its weight, cross-faded to the same with `to`
// blended in at full weight. A region's shape and merge flag take effect at once (hosts move storm cells a
// little every frame; their weather is what fades). The first weather the host ever sets is drawn at once:
// it replaces the configured weather, and an IG starts on the host's weather, not fading into it.
#pragma once

#include "skyservice/cigi/cigi_state.h"
#include "skyservice/service/cigi_weather.h"

#include <array>
#include <limits>
#include <map>

namespace sky
{

/// How long a change of the host's weather takes to fade in (s of IG time).
inline constexpr double kCigiFadeS = 5.0;

/// Fraction [0, 1] of a fade that began at startS, at nowS (smoothstep in time; 1 for startS = -inf).
float cigiFadeFraction(double startS, double nowS);

/// A weight fading from `from` to `to`.
struct CigiRamp
{
    float from = 0, to = 0;
    double startS = -std::numeric_limits<double>::infinity();
    float at(double nowS) const;
};

/// One cloud layer fading from what was drawn to what the host set (see the top of this file).
struct CigiFadingLayer
{
    CigiCloudAt from;     ///< the drawn mix when the fade began (set = false: nothing)
    float fromWeight = 0; ///< its weight [0, 1]
    CigiCloudAt to;       ///< the host's layer (set = false: not mentioned)
    double startS = -std::numeric_limits<double>::infinity();
};

struct CigiFadingRegion
{
    cigi::EnvironmentalRegion shape; ///< the host's latest geometry and merge flags (its layers are not used)
    std::array<CigiFadingLayer, 3> layers;
    CigiRamp presence; ///< 1 while active with layers, 0 when destroyed, inactive or gone
};

class CigiWeatherFade
{
  public:
    /// The host's weather is now `state`, at IG time nowS. Returns true when what is drawn changed (a layer,
    /// a region's shape, flags or presence); a state resent unchanged returns false.
    bool setTarget(const cigi::CigiState& state, double nowS);
    /// The host has set cloud weather (from then on it is drawn).
    bool started() const { return started_; }
    /// A fade is under way at nowS: what is drawn still changes.
    bool fading(double nowS) const;
    /// The cloud layers drawn at a point at nowS.
    CigiCloudsAt cloudsAt(double latDeg, double lonDeg, double nowS) const;
    /// The cloud layers drawn at a point at nowS over a gridded weather (cigi_weather_merge.h): `under` holds,
    /// for each host layer, the gridded layer of the slot it was matched to (set = false where there is no
    /// cloud), in metres above the ellipsoid. A global host layer replaces it (one that draws no cloud is no
    /// layer: the gridded one stays); a region replaces what is beneath it ("use last") or, with Merge Weather,
    /// averages with it (weight 1/2), over its transition perimeter as ever. The host's altitudes (above mean
    /// sea level) are raised by `undulationM`, so every altitude out is above the ellipsoid.
    CigiCloudsAt cloudsOver(const CigiCloudsAt& under, double latDeg, double lonDeg, double nowS,
                            float undulationM) const;
    /// Where host layer `layerId` (1-3) lies, for matching it with a gridded layer: the global layer when it
    /// draws cloud, else the first region's that sets it (what the host set, or what it fades from). False
    /// when no global or regional layer of that id is set.
    bool layerExtent(uint8_t layerId, CigiCloudAt& out) const;
    /// Regions still drawn or fading, by id.
    const std::map<uint16_t, CigiFadingRegion>& regions() const { return regions_; }

  private:
    std::array<CigiFadingLayer, 3> global_;
    std::map<uint16_t, CigiFadingRegion> regions_;
    bool started_ = false;
};

} // namespace sky
