// SPDX-License-Identifier: MIT
// From WRF output (NetCDF, any map projection) to WeatherSnapshots, one per time in `Times`.
#pragma once

#include "weather_ingest/ingest_progress.h"
#include "weather_ingest/layer_builder.h"
#include "weather_ingest/netcdf_file.h"

#include <string>
#include <vector>

namespace sky
{

/// Variables the WRF mapping cannot do without.
inline constexpr const char* kWrfRequired[] = {"Times", "XLAT", "XLONG", "PH", "PHB", "QCLOUD"};

/// Variables it uses when present.
inline constexpr const char* kWrfOptional[] = {"QICE", "QRAIN", "U", "V", "P", "PB", "T",
                                                "RAINC", "RAINNC", "RAINSH", "COSALPHA", "SINALPHA"};

/// Converts every time of a WRF file.
///
/// Per column: heights from (PH + PHB) / g on the staggered levels; a level is cloudy where
/// QCLOUD + QICE >= 1e-5 kg/kg; a contiguous cloudy run from below 3 km at least 5 km deep is the
/// convective layer, other cloudy levels go to low (< 2 km), middle (2-6 km) or high (>= 6 km) by the
/// height of the level; a layer's base/top are the lowest/highest cloudy level edges, its coverage
/// 1 - exp(-W / 0.02 kg m-2) from its condensed water path W = sum(rho (QCLOUD + QICE + QRAIN) dz), its
/// wind the mean de-staggered, earth-rotated U/V of its cloudy levels. Precipitation rates from the time
/// differences of RAINC + RAINSH (convective) and RAINNC (large-scale). Then every field is resampled
/// from XLAT/XLONG onto a regular lat/lon grid (CurvilinearResampler).
///
/// @return one snapshot per time, in file order. Throws IngestError: MissingFields naming the missing
///   variables (all of kWrfRequired are needed), Corrupt for inconsistent dimensions, TooLarge,
///   BadValues (see MappingOptions).
std::vector<WeatherSnapshot> mapWrfFile(const NcFile& file, const MappingOptions& options,
                                        std::vector<std::string>& warnings, const ProgressFn& progress);

/// Parses a WRF time "2005-08-28_12:00:00" (also with 'T' or ' ' as separator).
/// @return false when the text is not such a time.
bool parseWrfTime(const std::string& text, int64_t& unixS);

}  // namespace sky
