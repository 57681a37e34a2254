// SPDX-License-Identifier: MIT
// GRIB fixtures written at test time with ecCodes (no binary fixture in the repository).
#pragma once

#include "weather_ingest/grib_writer.h"

#include <string>
#include <vector>

namespace sky::test
{

/// A 2.5° global grid, north to south, 0..357.5 E (the GFS sample's layout) unless told otherwise.
inline LatLonGrid smallGlobalGrid() { return {.lat0Deg = 90, .lon0Deg = 0, .dLatDeg = -10, .dLonDeg = 20, .nLat = 19, .nLon = 18}; }

inline GribOutField field(const LatLonGrid& g, std::vector<std::pair<std::string, std::string>> keys, double value)
{
    GribOutField f;
    f.keys = {{"centre", "kwbc"}, {"dataDate", "20110110"}, {"dataTime", "1200"}, {"typeOfLevel", "surface"}};
    f.keys.insert(f.keys.end(), keys.begin(), keys.end());
    f.grid = g;
    f.values.assign(g.cellCount(), value);
    return f;
}

inline GribOutField layerField(const LatLonGrid& g, const char* shortName, const char* typeOfLevel, double value)
{
    return field(g, {{"typeOfLevel", typeOfLevel}, {"shortName", shortName}}, value);
}

inline GribOutField levelField(const LatLonGrid& g, const char* shortName, int hPa, double value)
{
    return field(g, {{"typeOfLevel", "isobaricInhPa"}, {"level", std::to_string(hPa)}, {"shortName", shortName}}, value);
}

/// A complete GFS-like set: 60 % low cloud 900..800 hPa, 40 % middle 600..450, 30 % convective
/// 950..250 hPa with 2 mm/h convective rain (cumulonimbus), 50 % high 300..200; heights 100 m at
/// 1000 hPa, 5500 m at 500 hPa, 11800 m at 200 hPa; wind u = 10, v = -5 m/s at 1000 hPa, u = 30 at 200 hPa.
inline std::vector<GribOutField> gfsLikeFields(const LatLonGrid& g)
{
    return {
        layerField(g, "tcc", "lowCloudLayer", 60),
        layerField(g, "tcc", "middleCloudLayer", 40),
        layerField(g, "tcc", "convectiveCloudLayer", 30),
        layerField(g, "tcc", "highCloudLayer", 50),
        layerField(g, "pres", "lowCloudBottom", 90000),
        layerField(g, "pres", "lowCloudTop", 80000),
        layerField(g, "pres", "middleCloudBottom", 60000),
        layerField(g, "pres", "middleCloudTop", 45000),
        layerField(g, "pres", "convectiveCloudBottom", 95000),
        layerField(g, "pres", "convectiveCloudTop", 25000),
        layerField(g, "pres", "highCloudBottom", 30000),
        layerField(g, "pres", "highCloudTop", 20000),
        layerField(g, "cape", "surface", 1500),
        layerField(g, "prate", "surface", 3.0 / 3600.0),
        layerField(g, "cprat", "surface", 2.0 / 3600.0),
        levelField(g, "gh", 1000, 100),
        levelField(g, "gh", 500, 5500),
        levelField(g, "gh", 200, 11800),
        levelField(g, "u", 1000, 10),
        levelField(g, "u", 500, 20),
        levelField(g, "u", 200, 30),
        levelField(g, "v", 1000, -5),
        levelField(g, "v", 500, -5),
        levelField(g, "v", 200, -5),
    };
}

}  // namespace sky::test
