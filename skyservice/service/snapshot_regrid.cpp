// SPDX-License-Identifier: MIT
#include "skyservice/service/snapshot_regrid.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

constexpr float kDefaultTropopauseM = 11000.0f; // as the renderer's window takes where there is none

/// The four cells around a point and their bilinear weights; `inside` false off a regional grid (the
/// corners are then the nearest edge's).
struct Corners
{
    size_t cell[4] = {0, 0, 0, 0};
    double weight[4] = {0, 0, 0, 0};
    size_t nearest = 0;
    bool inside = true;
};

Corners corners(const LatLonGrid& g, double latDeg, double lonDeg)
{
    Corners c;
    const bool wraps = double(g.nLon) * g.dLonDeg >= 360.0 - 1e-6;
    double fi = (latDeg - g.lat0Deg) / g.dLatDeg;
    double dLon = std::fmod(lonDeg - g.lon0Deg, 360.0);
    if (dLon < 0)
        dLon += 360.0;
    double fj = dLon / g.dLonDeg;
    const double lastRow = double(g.nLat - 1), lastCol = double(g.nLon - 1);
    if (!wraps && fj > lastCol + 1e-9)
    {
        // Past the east edge: the nearer of the two edges (west is 360 degrees on).
        c.inside = false;
        fj = (fj - lastCol) * g.dLonDeg < (360.0 - dLon) ? lastCol : 0.0;
    }
    if (fi < -1e-9 || fi > lastRow + 1e-9)
        c.inside = wraps; // a global grid is clamped at the poles; a regional one ends
    fi = std::clamp(fi, 0.0, lastRow);
    const uint32_t i0 = uint32_t(std::floor(fi)), j0 = uint32_t(std::floor(fj));
    const uint32_t i1 = std::min(i0 + 1, g.nLat - 1);
    const uint32_t j1 = wraps ? (j0 + 1) % g.nLon : std::min(j0 + 1, g.nLon - 1);
    const double ti = fi - double(i0), tj = fj - double(j0);
    c.cell[0] = g.index(i0, j0 % g.nLon);
    c.cell[1] = g.index(i0, j1);
    c.cell[2] = g.index(i1, j0 % g.nLon);
    c.cell[3] = g.index(i1, j1);
    c.weight[0] = (1 - ti) * (1 - tj);
    c.weight[1] = (1 - ti) * tj;
    c.weight[2] = ti * (1 - tj);
    c.weight[3] = ti * tj;
    c.nearest = c.cell[(ti >= 0.5 ? 2 : 0) + (tj >= 0.5 ? 1 : 0)];
    return c;
}

/// Bilinear, NaN corners left out; `fallback` when all are (or the field is absent), as the renderer takes.
float value(const std::vector<float>& field, const Corners& c, size_t cells, float fallback = 0.0f)
{
    if (field.size() != cells)
        return fallback;
    double sum = 0, weights = 0;
    for (int k = 0; k < 4; ++k)
        if (!std::isnan(field[c.cell[k]]))
        {
            sum += c.weight[k] * double(field[c.cell[k]]);
            weights += c.weight[k];
        }
    if (weights > 0)
        return float(sum / weights);
    for (int k = 0; k < 4; ++k) // only zero-weight corners are known
        if (!std::isnan(field[c.cell[k]]))
            return field[c.cell[k]];
    return fallback;
}

float coverage(const std::vector<float>& cov, const std::vector<float>& base, const std::vector<float>& top,
               const std::vector<float>& dataWeight, const Corners& c, size_t cells)
{
    if (!c.inside || cov.size() != cells || base.size() != cells || top.size() != cells)
        return 0.0f;
    double sum = 0;
    for (int k = 0; k < 4; ++k)
    {
        const size_t i = c.cell[k];
        if (std::isnan(cov[i]) || std::isnan(base[i]) || std::isnan(top[i]))
            continue;
        const double w = dataWeight.size() == cells ? std::clamp(double(dataWeight[i]), 0.0, 1.0) : 1.0;
        sum += c.weight[k] * std::clamp(double(cov[i]), 0.0, 1.0) * w;
    }
    return float(std::clamp(sum, 0.0, 1.0));
}

uint8_t nearestType(const std::vector<uint8_t>& type, const Corners& c, size_t cells)
{
    return type.size() == cells ? type[c.nearest] : uint8_t(CloudType::None);
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
    for (uint32_t iLat = 0; iLat < to.nLat; ++iLat)
        for (uint32_t iLon = 0; iLon < to.nLon; ++iLon)
        {
            const size_t cell = to.index(iLat, iLon);
            const Corners c = corners(from.grid, std::clamp(to.lat0Deg + iLat * to.dLatDeg, -90.0, 90.0),
                                      to.lon0Deg + iLon * to.dLonDeg);
            for (size_t k = 0; k < from.layers.size(); ++k)
            {
                const CloudLayerFields& s = from.layers[k];
                CloudLayerFields& l = w.layers[k];
                l.coverage[cell] = coverage(s.coverage, s.baseAltitudeM, s.topAltitudeM, from.dataWeight, c, cells);
                l.baseAltitudeM[cell] = value(s.baseAltitudeM, c, cells);
                l.topAltitudeM[cell] = value(s.topAltitudeM, c, cells);
                l.type[cell] = nearestType(s.type, c, cells);
                l.precipitationMmH[cell] = value(s.precipitationMmH, c, cells);
                l.windEastMS[cell] = value(s.windEastMS, c, cells);
                l.windNorthMS[cell] = value(s.windNorthMS, c, cells);
            }
            if (hasHigh)
            {
                const HighCloudFields& s = from.high;
                w.high.coverage[cell] = coverage(s.coverage, s.altitudeM, s.altitudeM, from.dataWeight, c, cells);
                w.high.altitudeM[cell] = value(s.altitudeM, c, cells);
                w.high.type[cell] = nearestType(s.type, c, cells);
                w.high.windEastMS[cell] = value(s.windEastMS, c, cells);
                w.high.windNorthMS[cell] = value(s.windNorthMS, c, cells);
            }
            if (!w.capeJKg.empty())
                w.capeJKg[cell] = value(from.capeJKg, c, cells);
            if (!w.tropopauseAltitudeM.empty())
                w.tropopauseAltitudeM[cell] = value(from.tropopauseAltitudeM, c, cells, kDefaultTropopauseM);
        }
    return w;
}

} // namespace sky
