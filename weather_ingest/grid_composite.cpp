// SPDX-License-Identifier: MIT
#include "weather_ingest/grid_composite.h"

#include "weather_ingest/regular_grid.h"
#include "weather_ingest/snapshot_blend.h"

#include <algorithm>
#include <array>
#include <span>
#include <cmath>

namespace sky
{
namespace
{

/// Where each target cell falls on the source grid (LatLonGrid::locate).
std::vector<GridPoint> positions(const LatLonGrid& src, const LatLonGrid& dst)
{
    std::vector<GridPoint> out(dst.cellCount());
    for (uint32_t r = 0; r < dst.nLat; ++r)
        for (uint32_t c = 0; c < dst.nLon; ++c)
            out[dst.index(r, c)] = src.locate(dst.lat0Deg + r * dst.dLatDeg, dst.lon0Deg + c * dst.dLonDeg);
    return out;
}

/// A source field on the target cells: NaN outside the source grid and where nothing is known.
std::vector<float> sample(const LatLonGrid& src, std::span<const float> v, const std::vector<GridPoint>& pos)
{
    if (v.empty())
        return {};
    std::vector<float> out(pos.size(), NAN);
    for (size_t t = 0; t < pos.size(); ++t)
        if (pos[t].inside)
            out[t] = src.sample(v, pos[t]);
    return out;
}

std::vector<uint8_t> nearest(const std::vector<uint8_t>& v, const std::vector<GridPoint>& pos)
{
    if (v.empty())
        return {};
    std::vector<uint8_t> out(pos.size(), 0);
    for (size_t t = 0; t < pos.size(); ++t)
        if (pos[t].inside)
            out[t] = v[pos[t].nearest];
    return out;
}

double spanLonDeg(const LatLonGrid& g)
{
    return g.wrapsInLongitude() ? 360.0 : g.dLonDeg * double(g.nLon - 1);
}

} // namespace

WeatherSnapshot resampleSnapshot(const WeatherSnapshot& s, const LatLonGrid& target)
{
    const std::vector<GridPoint> pos = positions(s.grid, target);
    const LatLonGrid& src = s.grid;
    WeatherSnapshot out;
    out.grid = target;
    out.validTimeUnixS = s.validTimeUnixS;
    out.provenance = s.provenance;
    for (const CloudLayerFields& l : s.layers)
    {
        CloudLayerFields o;
        o.name = l.name;
        o.coverage = sample(src, l.coverage, pos);
        o.baseAltitudeM = sample(src, l.baseAltitudeM, pos);
        o.topAltitudeM = sample(src, l.topAltitudeM, pos);
        o.type = nearest(l.type, pos);
        o.precipitationMmH = sample(src, l.precipitationMmH, pos);
        o.windEastMS = sample(src, l.windEastMS, pos);
        o.windNorthMS = sample(src, l.windNorthMS, pos);
        out.layers.push_back(std::move(o));
    }
    out.high.coverage = sample(src, s.high.coverage, pos);
    out.high.altitudeM = sample(src, s.high.altitudeM, pos);
    out.high.type = nearest(s.high.type, pos);
    out.high.windEastMS = sample(src, s.high.windEastMS, pos);
    out.high.windNorthMS = sample(src, s.high.windNorthMS, pos);
    out.capeJKg = sample(src, s.capeJKg, pos);
    out.tropopauseAltitudeM = sample(src, s.tropopauseAltitudeM, pos);
    for (const PressureLevelField& f : s.levelFields)
    {
        PressureLevelField o{f.name, f.units, f.pressurePa, {}};
        for (size_t k = 0; k < f.pressurePa.size(); ++k)
        {
            const auto levelValues = std::span<const float>(f.values).subspan(k * src.cellCount(), src.cellCount());
            const std::vector<float> level = sample(src, levelValues, pos);
            o.values.insert(o.values.end(), level.begin(), level.end());
        }
        out.levelFields.push_back(std::move(o));
    }
    const std::vector<float> ones(s.dataWeight.empty() ? s.grid.cellCount() : 0, 1.0f);
    out.dataWeight = sample(src, s.dataWeight.empty() ? ones : s.dataWeight, pos);
    for (float& w : out.dataWeight)
        w = std::isfinite(w) ? std::clamp(w, 0.0f, 1.0f) : 0.0f;
    return out;
}

WeatherSnapshot compositeSnapshots(std::vector<WeatherSnapshot> parts, size_t maxCells,
                                   std::vector<std::string>& warnings)
{
    if (parts.size() == 1)
        return std::move(parts.front());
    std::stable_sort(parts.begin(), parts.end(),
                     [](const WeatherSnapshot& a, const WeatherSnapshot& b)
                     { return std::abs(a.grid.dLatDeg) * a.grid.dLonDeg > std::abs(b.grid.dLatDeg) * b.grid.dLonDeg; });
    // The union of the areas; longitudes unwrapped around the coarsest part's first column.
    const double lonRef = parts.front().grid.lon0Deg;
    double latMin = 90, latMax = -90, lonMin = 1e9, lonMax = -1e9;
    bool global = false;
    for (const WeatherSnapshot& p : parts)
    {
        const LatLonGrid& g = p.grid;
        const double latEnd = g.lat0Deg + g.dLatDeg * double(g.nLat - 1);
        latMin = std::min({latMin, g.lat0Deg, latEnd});
        latMax = std::max({latMax, g.lat0Deg, latEnd});
        global = global || g.wrapsInLongitude();
        const double west = lonRef + wrapLongitudeDeg(g.lon0Deg - lonRef);
        lonMin = std::min(lonMin, west);
        lonMax = std::max(lonMax, west + spanLonDeg(g));
    }
    global = global || lonMax - lonMin >= 360.0;
    const LatLonGrid& finest = parts.back().grid;
    double dLat = std::abs(finest.dLatDeg), dLon = finest.dLonDeg;
    const double lonSpan = global ? 360.0 : lonMax - lonMin;
    const double cells = (std::floor((latMax - latMin) / dLat) + 1) * (std::floor(lonSpan / dLon) + 1);
    if (cells > double(maxCells))
    {
        const double factor = std::sqrt(cells / double(maxCells)) * 1.01;
        dLat *= factor;
        dLon *= factor;
        warnings.push_back("composite grid coarsened to " + std::to_string(dLat) + " deg to stay within " +
                           std::to_string(maxCells) + " cells; convert the finest input alone to keep its resolution");
    }
    LatLonGrid g;
    g.lat0Deg = latMin;
    g.dLatDeg = dLat;
    g.nLat = uint32_t(std::floor((latMax - latMin) / dLat + 1e-9) + 1);
    g.lon0Deg = wrapLongitudeDeg(global ? lonRef : lonMin);
    g.nLon = uint32_t(global ? std::max(1.0, std::round(360.0 / dLon)) : std::floor(lonSpan / dLon + 1e-9) + 1);
    g.dLonDeg = global ? 360.0 / double(g.nLon) : dLon;

    WeatherSnapshot out = resampleSnapshot(parts.front(), g);
    std::string layout = parts.front().provenance.count("grid") ? parts.front().provenance.at("grid") : "grid 1";
    for (size_t k = 1; k < parts.size(); ++k)
    {
        WeatherSnapshot fine = resampleSnapshot(parts[k], g);
        WeatherSnapshot blended;
        blendSnapshotFields(out, fine, BlendWeight{0.0f, &fine.dataWeight}, blended);
        for (size_t i = 0; i < blended.dataWeight.size(); ++i)
        {
            const float w = fine.dataWeight[i];
            blended.dataWeight[i] = w + (1.0f - w) * (out.dataWeight.empty() ? 1.0f : out.dataWeight[i]);
        }
        blended.grid = g;
        blended.validTimeUnixS = out.validTimeUnixS;
        blended.provenance = out.provenance;
        for (const auto& [key, value] : fine.provenance)
        {
            const auto below = out.provenance.find(key);
            blended.provenance[key] = below == out.provenance.end() || below->second == value
                                          ? value
                                          : value + "; outside it: " + below->second;
        }
        layout = (fine.provenance.count("grid") ? fine.provenance.at("grid") : "grid " + std::to_string(k + 1)) +
                 " over " + layout;
        out = std::move(blended);
    }
    out.provenance["grid"] = layout + "; the finer grid blends in over its outer 5 %";
    if (std::all_of(out.dataWeight.begin(), out.dataWeight.end(), [](float w) { return w >= 1.0f; }))
        out.dataWeight.clear();
    return out;
}

} // namespace sky
