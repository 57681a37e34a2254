// SPDX-License-Identifier: MIT
// Answers to a host's Environmental Conditions Request (28): the Weather Conditions Response (109) and the
// Aerosol Concentration Responses (110) for the point asked, from what the sky draws there.
//
// Visibility: inside a drawn cloud layer, the distance at which its extinction leaves 5 % contrast
// (Koschmieder: 3 / extinction), with extinction = QualitySettings::extinctionPerM x the cloud's density
// there. A CIGI layer is uniform, so its coverage stands for the density (the renderer's density also
// shapes the layer's top and base and erodes it with noise: this is the layer's mean, not the pixel's).
// Outside clouds: the air the renderer draws there (Rayleigh + Mie extinction of skyservice/sky/atmosphere.h
// at 550 nm at that altitude, the Mie set by the host's Atmosphere Control visibility when it sent one:
// that visibility at sea level, clearer above as the haze thins), plus the global ground fog's extinction
// inside its band.
// Temperature and pressure: the ICAO standard atmosphere at the altitude, from the host's sea-level values
// when Atmosphere Control set them. Humidity: 100 % inside a cloud, else the host's. Wind: the cloud
// layer's inside it, else the host's global wind. Liquid water (110, per cloud layer): the layer's aerosol
// concentration when the host set one, else the liquid water of droplets of 10 um effective radius that
// gives the layer's extinction (LWC = 2/3 rho_w r_e beta), 0 outside the layer.
#pragma once

#include "skyservice/cigi/cigi_packets.h"
#include "skyservice/cigi/cigi_state.h"

#include <vector>

namespace sky
{

/// Visibility (m) of the clear air the renderer draws, at `altitudeM` above sea level.
double clearAirVisibilityM(double altitudeM);
/// ... of the air drawn under the host's Atmosphere Control visibility and global ground fog (layer 0).
double cigiAirVisibilityM(const cigi::CigiState& state, double altitudeM);

/// ICAO standard atmosphere from sea-level temperature (C) and pressure (hPa): temperature (C) and
/// pressure (hPa) at `altitudeM` (0..32 km; clamped).
void standardAtmosphere(double altitudeM, double seaLevelC, double seaLevelHpa, double& temperatureC,
                        double& pressureHpa);

cigi::WeatherConditionsResponse cigiWeatherConditions(const cigi::CigiState& state,
                                                      const cigi::EnvironmentalConditionsRequest& request,
                                                      double extinctionPerM);

/// One response per cloud layer the host has set (layers 1-3), in layer order.
std::vector<cigi::AerosolConcentrationResponse>
cigiAerosolConcentrations(const cigi::CigiState& state, const cigi::EnvironmentalConditionsRequest& request,
                          double extinctionPerM);

} // namespace sky
