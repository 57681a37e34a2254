// SPDX-License-Identifier: MIT
// Range checks of decoded CIGI 3.3 packets against the ICD's stated ranges. Each returns "" when the packet
// may be applied, else one sentence naming the first field that is wrong and its value. NaN and infinities
// are refused in every float field; angles are checked loosely (see each function) because hosts in
// service send yaw in -180..180 as often as in the ICD's 0..360.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <string>

namespace sky::cigi
{

std::string validate(const IgControl& p);
/// Detached entities: latitude within ±90, longitude within ±180 (±360 accepted and wrapped), altitude finite.
/// Attitude: pitch within ±90, roll and yaw within ±360.
std::string validate(const EntityControl& p);
/// Only when Date/Time Valid: hour 0-23, minute 0-59, a calendar date (month 1-12, day within the month).
std::string validate(const CelestialSphereControl& p);
std::string validate(const AtmosphereControl& p);
std::string validate(const EnvironmentalRegionControl& p);
/// Humidity, coverage and scud frequency 0-100, thickness/transition/visibility/wind speed/aerosol >= 0,
/// scope 0-2, severity 0-5.
std::string validate(const WeatherControl& p);
std::string validate(const ViewControl& p);
/// Enabled fields only: near > 0, far > near, each half-angle within ±90 (exclusive), left < right, bottom < top.
std::string validate(const ViewDefinition& p);
std::string validate(const EnvironmentalConditionsRequest& p);

} // namespace sky::cigi
