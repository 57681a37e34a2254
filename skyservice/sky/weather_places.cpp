// SPDX-License-Identifier: MIT
#include "skyservice/sky/weather_places.h"

#include "skyservice/sky/ephemeris.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

namespace sky
{
namespace
{

constexpr size_t kLow = 0, kMiddle = 1, kConvective = 2;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

float valueAt(const std::vector<float>& field, size_t cell)
{
    return cell < field.size() ? field[cell] : kNaN;
}

float layerCoverage(const WeatherSnapshot& w, size_t layer, size_t cell)
{
    return layer < w.layers.size() ? valueAt(w.layers[layer].coverage, cell) : 0.0f;
}

class Neighbourhood
{
  public:
    explicit Neighbourhood(const LatLonGrid& g) : grid_(g), global_(g.wrapsInLongitude()) {}

    // Calls f(cell) for every cell within `ring` rows and columns of (i, j); false if any f is false.
    // Cells past a regional grid's edge count as failing: the place must be surrounded by known data.
    bool all(uint32_t i, uint32_t j, int ring, const std::function<bool(size_t)>& f) const
    {
        for (int di = -ring; di <= ring; ++di)
            for (int dj = -ring; dj <= ring; ++dj)
            {
                int64_t ii = int64_t(i) + di, jj = int64_t(j) + dj;
                if (ii < 0 || ii >= int64_t(grid_.nLat))
                    continue; // beyond a pole row of a global grid, or the edge of a regional one
                if (jj < 0 || jj >= int64_t(grid_.nLon))
                {
                    if (!global_)
                        return false;
                    jj = (jj + int64_t(grid_.nLon)) % int64_t(grid_.nLon);
                }
                if (!f(grid_.index(uint32_t(ii), uint32_t(jj))))
                    return false;
            }
        return true;
    }

  private:
    const LatLonGrid& grid_;
    bool global_;
};

bool clearCell(const WeatherSnapshot& w, size_t cell)
{
    for (size_t k = 0; k < w.layers.size(); ++k)
        if (!(valueAt(w.layers[k].coverage, cell) == 0.0f)) // NaN is unknown, not clear
            return false;
    return w.high.coverage.empty() || w.high.coverage[cell] == 0.0f;
}

const char* typeName(uint8_t type)
{
    static const char* names[] = {"none",         "altocumulus",   "altostratus",  "cirrocumulus",
                                  "cirrostratus", "cirrus",        "cumulonimbus", "cumulus",
                                  "nimbostratus", "stratocumulus", "stratus"};
    return type < 11 ? names[type] : "?";
}

}  // namespace

std::string formatLatLon(double latDeg, double lonDeg)
{
    char text[64];
    double lon = wrapLongitudeDeg(lonDeg);
    std::snprintf(text, sizeof text, "%.1f%c %.1f%c", std::abs(latDeg), latDeg >= 0.0 ? 'N' : 'S', std::abs(lon),
                  lon >= 0.0 ? 'E' : 'W');
    return text;
}

WeatherPlace findWeatherPlace(const WeatherSnapshot& w, PlaceKind kind, const PlaceFilter& filter)
{
    WeatherPlace best;
    const LatLonGrid& g = w.grid;
    if (g.cellCount() == 0 || (kind != PlaceKind::Clear && w.layers.size() <= kConvective))
        return best;
    Neighbourhood around(g);
    for (uint32_t i = 0; i < g.nLat; ++i)
    {
        const double latDeg = g.lat0Deg + double(i) * g.dLatDeg;
        if (std::abs(latDeg) > filter.maxAbsLatDeg)
            continue;
        for (uint32_t j = 0; j < g.nLon; ++j)
        {
            const double lonDeg = wrapLongitudeDeg(g.lon0Deg + double(j) * g.dLonDeg);
            const size_t cell = g.index(i, j);
            double score = -1.0;
            if (kind == PlaceKind::LowDeck)
            {
                const CloudLayerFields& low = w.layers[kLow];
                if (layerCoverage(w, kLow, cell) > 0.8f && std::isfinite(valueAt(low.baseAltitudeM, cell)))
                {
                    float minimum = 1.0f;
                    around.all(i, j, 1,
                               [&](size_t c)
                               {
                                   float v = layerCoverage(w, kLow, c);
                                   minimum = std::isnan(v) ? 0.0f : std::min(minimum, v);
                                   return true;
                               });
                    // Among decks, prefer those with the least cloud above them: the picture and the
                    // test should show the low layer, not a veil over it.
                    float above = 0.0f;
                    for (float v : {layerCoverage(w, kMiddle, cell), valueAt(w.high.coverage, cell)})
                        above = std::isnan(v) ? above : std::max(above, v);
                    score = double(minimum) + 0.1 * (1.0 - double(above));
                }
            }
            else if (kind == PlaceKind::Convective)
            {
                const float cover = layerCoverage(w, kConvective, cell);
                if (cover > 0.0f)
                {
                    const bool cb = cell < w.layers[kConvective].type.size() &&
                                    w.layers[kConvective].type[cell] == uint8_t(CloudType::Cumulonimbus);
                    const float cape = valueAt(w.capeJKg, cell);
                    score = double(cover) + (cb ? 1.0 : 0.0) +
                            (std::isfinite(cape) ? std::min(double(cape) / 2000.0, 1.0) : 0.0);
                }
            }
            else if (clearCell(w, cell))
            {
                int ring = 0;
                while (ring < 4 && around.all(i, j, ring + 1, [&](size_t c) { return clearCell(w, c); }))
                    ++ring;
                score = ring;
            }
            if (score <= best.score && best.found)
                continue;
            if (score < 0.0)
                continue;
            double sunDeg = computeSunMoon(w.validTimeUnixS, latDeg, lonDeg, 0.0).sun.elevationDeg;
            if (sunDeg < filter.minSunElevationDeg)
                continue;
            best.found = true;
            best.score = score;
            best.latDeg = latDeg;
            best.lonDeg = lonDeg;
            best.iLat = i;
            best.iLon = j;
            best.sunElevationDeg = sunDeg;
        }
    }
    if (!best.found)
        return best;
    const size_t cell = g.index(best.iLat, best.iLon);
    for (size_t k = 0; k < 3; ++k)
    {
        best.coverage[k] = layerCoverage(w, k, cell);
        best.baseM[k] = k < w.layers.size() ? valueAt(w.layers[k].baseAltitudeM, cell) : kNaN;
        best.topM[k] = k < w.layers.size() ? valueAt(w.layers[k].topAltitudeM, cell) : kNaN;
        best.type[k] = k < w.layers.size() && cell < w.layers[k].type.size() ? w.layers[k].type[cell] : 0;
    }
    best.coverage[3] = w.high.coverage.empty() ? 0.0f : valueAt(w.high.coverage, cell);
    best.highAltitudeM = valueAt(w.high.altitudeM, cell);
    best.type[3] = cell < w.high.type.size() ? w.high.type[cell] : 0;
    best.capeJKg = valueAt(w.capeJKg, cell);
    return best;
}

std::string describeWeatherPlace(const WeatherPlace& p)
{
    if (!p.found)
        return "(no place found)";
    static const char* layerNames[] = {"low", "middle", "convective"};
    std::string text = formatLatLon(p.latDeg, p.lonDeg) + ":";
    char part[160];
    for (int k = 0; k < 3; ++k)
    {
        if (p.coverage[k] > 0.0f)
            std::snprintf(part, sizeof part, " %s %.0f%% (%s, %.0f-%.0f m),", layerNames[k],
                          double(p.coverage[k]) * 100.0, typeName(p.type[k]), double(p.baseM[k]), double(p.topM[k]));
        else
            std::snprintf(part, sizeof part, " %s %.0f%%,", layerNames[k], double(p.coverage[k]) * 100.0);
        text += part;
    }
    if (p.coverage[3] > 0.0f)
        std::snprintf(part, sizeof part, " high %.0f%% (%s, %.0f m)", double(p.coverage[3]) * 100.0,
                      typeName(p.type[3]), double(p.highAltitudeM));
    else
        std::snprintf(part, sizeof part, " high %.0f%%", double(p.coverage[3]) * 100.0);
    text += part;
    if (std::isfinite(p.capeJKg))
    {
        std::snprintf(part, sizeof part, ", CAPE %.0f J/kg", double(p.capeJKg));
        text += part;
    }
    std::snprintf(part, sizeof part, ", sun %.0f deg", p.sunElevationDeg);
    return text + part;
}

}  // namespace sky
