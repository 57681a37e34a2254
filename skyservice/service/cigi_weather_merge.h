// SPDX-License-Identifier: MIT
// The CIGI host's weather laid over a gridded weather (a loaded GRIB/NetCDF snapshot file, or the built-in
// scene): the merge CIGI 3.3 describes with its region merge flags, on the renderer's four layer slots.
//
//  - The gridded weather is the global weather, except where the host sets global cloud layers: each host
//    layer (1-3) is matched by altitude to one of the snapshot's layer slots (the gridded layer whose
//    altitude range near the ownship overlaps it most, else a slot with no cloud near the ownship, else a
//    new slot while there are fewer than four, else the nearest by mid altitude) and replaces that gridded
//    layer everywhere. A global host layer that draws no cloud (disabled, coverage 0) leaves the gridded
//    layer as it is. Gridded layers no host layer is matched with are drawn as they are.
//  - Inside a region the region's layers replace ("use last") or, with Merge Weather set, average with
//    (half weight: coverage, altitudes and wind) whatever is beneath in their slots: the gridded layer, the
//    host's global layer or an earlier region; over the region's transition perimeter the weight falls
//    to 0 (smoothstep), so the region blends into the gridded weather. A region changes only the slots of the
//    layers it sets (a layer it clears is cleared inside it).
//  - Cirrus-type host layers go to the high (2D) cloud layer, where the densest of the gridded and the
//    host's cloud is drawn per cell, as they do without a gridded weather.
//  - The merged snapshot's grid: the gridded one while the host has no regions; with regions a grid around
//    the ownship (cigiWeatherGrid with overGridded: 4-5 km cells out to 800 km, the renderer's weather
//    window) onto which the gridded snapshot is resampled (snapshot_regrid.h).
//  - Altitudes: the gridded ones are kept as they are (a model's heights are taken as ellipsoid heights);
//    the host's are above mean sea level and get the EGM96 undulation of each cell. Where the host changes
//    nothing, a cell keeps the gridded values exactly.
//
// The overlay is applied to every sample of the gridded timeline on the renderer's worker thread
// (weather_schedule.h), so the merge is redone when the timeline moves to a new sample or a new file is
// loaded; the CIGI link makes a new overlay when the host's weather (or a fade step of it) changes.
#pragma once

#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/service/cigi_weather.h"
#include "skyservice/service/cigi_weather_fade.h"
#include "skyservice/service/service_state.h"

#include <array>
#include <memory>

namespace sky
{

/// For each host cloud layer (1-3), the slot (index into `gridded.layers`, or one past them for a new
/// layer) it is drawn in over `gridded`; -1 when it takes none (not set, or a cirrus type: high layer).
std::array<int, 3> cigiMatchLayerSlots(const WeatherSnapshot& gridded, const CigiWeatherFade& fade,
                                       double ownLatDeg, double ownLonDeg);

/// The host's weather as drawn at IG time nowS (`fade`) over `gridded` (see the top of this file). `grid`:
/// from cigiWeatherGrid(fade, own, overGridded = true); when regional the result lies on it, else on
/// gridded's grid.
WeatherSnapshot cigiMergeWeather(const WeatherSnapshot& gridded, const CigiWeatherFade& fade, double nowS,
                                 const CigiWeatherGrid& grid, const cigi::GeoidGrid& geoid, double ownLatDeg,
                                 double ownLonDeg);

/// The host's weather at one IG time as a WeatherOverlay: a copy of the fade, evaluated at nowS.
class CigiOverlay : public WeatherOverlay
{
  public:
    CigiOverlay(const CigiWeatherFade& fade, double nowS, const CigiWeatherGrid& grid,
                std::shared_ptr<const cigi::GeoidGrid> geoid, double ownLatDeg, double ownLonDeg)
        : fade_(fade), nowS_(nowS), grid_(grid), geoid_(std::move(geoid)), ownLatDeg_(ownLatDeg),
          ownLonDeg_(ownLonDeg)
    {
    }
    WeatherSnapshot over(const WeatherSnapshot& gridded) const override
    {
        return cigiMergeWeather(gridded, fade_, nowS_, grid_, *geoid_, ownLatDeg_, ownLonDeg_);
    }
    std::string name() const override { return "cigi"; }

  private:
    CigiWeatherFade fade_;
    double nowS_;
    CigiWeatherGrid grid_;
    std::shared_ptr<const cigi::GeoidGrid> geoid_;
    double ownLatDeg_, ownLonDeg_;
};

} // namespace sky
