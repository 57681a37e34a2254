// SPDX-License-Identifier: MIT
// WeatherSnapshot: the weather at one valid time on a regular latitude/longitude grid, in SI units.
//
// This is the one type that crosses from weather_ingest/ (which fills it from GRIB2/NetCDF) to
// skyservice/ (which renders it). It depends on nothing but the standard library, so skyservice
// never sees ecCodes or netCDF (OVERVIEW.md).
//
// Conventions:
//  - Grid: cell (iLat, iLon) is at latitude lat0Deg + iLat*dLatDeg, longitude lon0Deg + iLon*dLonDeg
//    (degrees; dLatDeg may be negative for north-to-south data, dLonDeg > 0). Fields are row-major,
//    index = iLat * nLon + iLon. Longitudes may be in any convention; a grid whose nLon*dLonDeg is
//    360 wraps around the antimeridian.
//  - Altitudes: metres above the WGS84 ellipsoid (model heights above mean sea level are taken as
//    ellipsoid heights; see README "Datums").
//  - Coverage: fraction [0,1]. Precipitation rate: mm/h (equivalently kg m^-2 h^-1). CAPE: J/kg.
//    Wind: m/s, positive towards east (U) and north (V).
//  - Missing values: NaN in a field means "unknown" and is treated as no cloud by the renderer.
//  - Sampling between nodes (wrap, edges, missing values): LatLonGrid::sample, lat_lon_grid.h.
//  - No data: a regional model covers only part of its grid. dataWeight (optional) says, per cell, how much
//    of the weather there is this snapshot's: 1 inside the model's domain, 0 outside it (every field NaN
//    there), and a smooth ramp from 0 to 1 over the outer 5 % of the domain. A renderer blends
//    coverage * dataWeight + (what another source says there, else clear sky) * (1 - dataWeight), so a
//    domain edge is soft, not a wall. Empty: 1 everywhere (a global model).
#pragma once

#include "shaders/shared/cloud_type.h"
#include "weather_ingest/lat_lon_grid.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sky
{

/// Volumetric layers per snapshot; equals MAX_CLOUD_LAYERS in shaders/shared/bindings.h.
inline constexpr int kMaxCloudLayers = 4;

/// One volumetric cloud layer: every vector has grid.cellCount() values.
struct CloudLayerFields
{
    std::string name;                     ///< e.g. "low", "middle", "convective" (for humans)
    std::vector<float> coverage;          ///< fraction [0,1]
    std::vector<float> baseAltitudeM;     ///< cloud base (m above ellipsoid)
    std::vector<float> topAltitudeM;      ///< cloud top (m above ellipsoid)
    std::vector<uint8_t> type;            ///< CloudType per cell
    std::vector<float> precipitationMmH;  ///< precipitation rate falling from this layer (mm/h)
    std::vector<float> windEastMS;        ///< wind at mid-layer (m/s, towards east)
    std::vector<float> windNorthMS;       ///< wind at mid-layer (m/s, towards north)
};

/// The high-altitude 2D texture layer (cirrus, cirrostratus, cirrocumulus).
struct HighCloudFields
{
    std::vector<float> coverage;       ///< fraction [0,1]
    std::vector<float> altitudeM;      ///< m above ellipsoid
    std::vector<uint8_t> type;         ///< CloudType (Cirrocumulus, Cirrostratus or Cirrus)
    std::vector<float> windEastMS;     ///< upper-level wind (m/s)
    std::vector<float> windNorthMS;    ///< upper-level wind (m/s)
};

/// An optional 3D field on pressure levels (e.g. GFS cloud mixing ratio), kept for consumers that want the
/// vertical profile (added by weather_ingest; the renderer may ignore it).
struct PressureLevelField
{
    std::string name;                ///< e.g. "cloudMixingRatio"
    std::string units;               ///< SI units of values, e.g. "kg/kg"
    std::vector<float> pressurePa;   ///< level pressures (Pa), one per level, decreasing (surface first)
    std::vector<float> values;       ///< level-major: values[k * grid.cellCount() + cell]; NaN = unknown
};

/// The weather at one valid time. A snapshot with layers.empty() is clear sky.
struct WeatherSnapshot
{
    LatLonGrid grid;
    int64_t validTimeUnixS = 0;                ///< valid time (seconds since 1970-01-01T00:00:00Z)
    std::vector<CloudLayerFields> layers;      ///< at most kMaxCloudLayers, lowest first
    HighCloudFields high;                      ///< empty vectors mean no high cloud
    std::vector<float> capeJKg;                ///< convective available potential energy (J/kg), may be empty
    std::vector<float> tropopauseAltitudeM;    ///< m above ellipsoid, may be empty
    std::map<std::string, std::string> provenance;  ///< field name -> where it came from (file, message, variable)
    std::vector<PressureLevelField> levelFields;    ///< optional 3D fields (added by weather_ingest), may be empty
    std::vector<float> dataWeight;                  ///< [0,1] per cell, see "No data" above; empty = 1 everywhere
};

}  // namespace sky
