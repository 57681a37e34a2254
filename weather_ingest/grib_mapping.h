// SPDX-License-Identifier: MIT
// From the GRIB records of one valid time (GFS or ECMWF names, gribRoleTable()) to a WeatherSnapshot.
#pragma once

#include "weather_ingest/grib_fields.h"
#include "weather_ingest/layer_builder.h"

#include <string>
#include <vector>

namespace sky
{

/// Builds the snapshot of one valid time.
///
/// @param[in] records every record with that valid time (from one or several files).
/// @param[in] options strictness and optional 3D fields.
/// @param[out] warnings lenient repairs and fallbacks (e.g. "no geopotential height: ICAO standard
///   atmosphere used"), appended.
/// @return the snapshot: layers low/middle/convective (always three), high, CAPE, tropopause, provenance.
///   Throws IngestError: MissingFields when no cloud cover of any layer is present; UnsupportedGrid when
///   the records are on different grids; BadValues (see MappingOptions).
WeatherSnapshot mapGribRecords(const std::vector<const GribRecord*>& records, const MappingOptions& options,
                               std::vector<std::string>& warnings);

}  // namespace sky
