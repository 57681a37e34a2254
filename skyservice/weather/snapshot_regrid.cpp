// SPDX-License-Identifier: MIT
#include "skyservice/weather/snapshot_regrid.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

constexpr float kDefaultTropopauseM = 11000.0f; // as the renderer's window takes where there is none

/// Bilinear, missing corners left out (LatLonGrid::sample); `fallback` where nothing is known, as the
/// renderer's window takes.
float value(const LatLonGrid& g, const std::vector<float>& field, const GridPoint& p, float fallback = 0.0f)
{
    return g.sample(field, p, fallback);
}

uint8_t nearestType(const std::vector<uint8_t>& type, const GridPoint& p, size_t cells)
{
    return type.size() == cells ? type[p.nearest] : uint8_t(CloudType::None);
}

void scale(std::vector<float>& coverage, const std::vector<float>& weight)
{
    if (coverage.size() != weight.size())
        return;
    for (size_t i = 0; i < coverage.size(); ++i)
        coverage[i] *= std::clamp(weight[i], 0.0f, 1.0f);
}

} // namespace

void foldDataWeight(WeatherSnapshot& w)
{
    if (w.dataWeight.empty())
        return;
    for (CloudLayerFields& l : w.layers)
        scale(l.coverage, w.dataWeight);
    scale(w.high.coverage, w.dataWeight);
    w.dataWeight.clear();
}

WeatherSnapshot regridSnapshot(const WeatherSnapshot& from, const LatLonGrid& to)
{
    WeatherSnapshot w;
    w.grid = to;
    w.validTimeUnixS = from.validTimeUnixS;
    w.provenance = from.provenance;
    const size_t n = to.cellCount(), cells = from.grid.cellCount();
    const bool hasHigh = from.high.coverage.size() == cells && cells > 0;
    w.layers.resize(from.layers.size());
    for (size_t k = 0; k < from.layers.size(); ++k)
    {
        CloudLayerFields& l = w.layers[k];
        l.name = from.layers[k].name;
        for (std::vector<float>* f : {&l.coverage, &l.baseAltitudeM, &l.topAltitudeM, &l.precipitationMmH,
                                      &l.windEastMS, &l.windNorthMS})
            f->assign(n, 0.0f);
        l.type.assign(n, uint8_t(CloudType::None));
    }
    if (hasHigh)
    {
        for (std::vector<float>* f : {&w.high.coverage, &w.high.altitudeM, &w.high.windEastMS, &w.high.windNorthMS})
            f->assign(n, 0.0f);
        w.high.type.assign(n, uint8_t(CloudType::None));
    }
    if (from.capeJKg.size() == cells)
        w.capeJKg.assign(n, 0.0f);
    if (from.tropopauseAltitudeM.size() == cells)
        w.tropopauseAltitudeM.assign(n, 0.0f);
    if (cells == 0)
        return w;
    const LatLonGrid& g = from.grid;
    for (uint32_t iLat = 0; iLat < to.nLat; ++iLat)
        for (uint32_t iLon = 0; iLon < to.nLon; ++iLon)
        {
            const size_t cell = to.index(iLat, iLon);
            const GridPoint c = g.locate(std::clamp(to.lat0Deg + iLat * to.dLatDeg, -90.0, 90.0),
                                         to.lon0Deg + iLon * to.dLonDeg);
            for (size_t k = 0; k < from.layers.size(); ++k)
            {
                const CloudLayerFields& s = from.layers[k];
                CloudLayerFields& l = w.layers[k];
                l.coverage[cell] = sampleCoverage(g, s.coverage, s.baseAltitudeM, s.topAltitudeM, c, from.dataWeight);
                l.baseAltitudeM[cell] = value(g, s.baseAltitudeM, c);
                l.topAltitudeM[cell] = value(g, s.topAltitudeM, c);
                l.type[cell] = nearestType(s.type, c, cells);
                l.precipitationMmH[cell] = value(g, s.precipitationMmH, c);
                l.windEastMS[cell] = value(g, s.windEastMS, c);
                l.windNorthMS[cell] = value(g, s.windNorthMS, c);
            }
            if (hasHigh)
            {
                const HighCloudFields& s = from.high;
                w.high.coverage[cell] = sampleCoverage(g, s.coverage, s.altitudeM, s.altitudeM, c, from.dataWeight);
                w.high.altitudeM[cell] = value(g, s.altitudeM, c);
                w.high.type[cell] = nearestType(s.type, c, cells);
                w.high.windEastMS[cell] = value(g, s.windEastMS, c);
                w.high.windNorthMS[cell] = value(g, s.windNorthMS, c);
            }
            if (!w.capeJKg.empty())
                w.capeJKg[cell] = value(g, from.capeJKg, c);
            if (!w.tropopauseAltitudeM.empty())
                w.tropopauseAltitudeM[cell] = value(g, from.tropopauseAltitudeM, c, kDefaultTropopauseM);
        }
    return w;
}

} // namespace sky
