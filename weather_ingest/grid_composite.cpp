// SPDX-License-Identifier: MIT
#include "weather_ingest/grid_composite.h"

#include "weather_ingest/regular_grid.h"
#include "weather_ingest/snapshot_blend.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sky
{
namespace
{

/// Where a target cell falls on the source grid: four corners and weights, or outside.
struct SourcePosition
{
    bool inside = false;
    std::array<size_t, 4> corner{};
    std::array<float, 4> weight{};
    size_t nearest = 0;
};

std::vector<SourcePosition> positions(const LatLonGrid& src, const LatLonGrid& dst)
{
    std::vector<SourcePosition> out(dst.cellCount());
    const bool wraps = wrapsInLongitude(src);
    for (uint32_t r = 0; r < dst.nLat; ++r)
        for (uint32_t c = 0; c < dst.nLon; ++c)
        {
            const double y = (dst.lat0Deg + r * dst.dLatDeg - src.lat0Deg) / src.dLatDeg;
            double x = std::fmod(dst.lon0Deg + c * dst.dLonDeg - src.lon0Deg, 360.0);
            if (x < 0)
                x += 360.0;
            x /= src.dLonDeg;
            const double xMax = wraps ? double(src.nLon) : double(src.nLon - 1);
            if (!wraps && x > xMax + 1e-9 && x - 360.0 / src.dLonDeg >= -1e-9)
                x -= 360.0 / src.dLonDeg;
            const double yMax = double(src.nLat - 1);
            if (!(y >= -1e-9 && y <= yMax + 1e-9 && x >= -1e-9 && x <= xMax + 1e-9))
                continue;
            SourcePosition& p = out[dst.index(r, c)];
            const auto i0 = uint32_t(std::min(std::floor(std::max(y, 0.0)), std::max(yMax - 1, 0.0)));
            const auto j0 = uint32_t(std::min(std::floor(std::max(x, 0.0)), std::max(xMax - 1, 0.0)));
            const uint32_t i1 = std::min(i0 + 1, src.nLat - 1);
            const uint32_t j1 = wraps ? (j0 + 1) % src.nLon : std::min(j0 + 1, src.nLon - 1);
            const auto fy = float(std::clamp(y - double(i0), 0.0, 1.0));
            const auto fx = float(std::clamp(x - double(j0), 0.0, 1.0));
            p.inside = true;
            p.corner = {src.index(i0, j0 % src.nLon), src.index(i0, j1), src.index(i1, j0 % src.nLon),
                        src.index(i1, j1)};
            p.weight = {(1 - fy) * (1 - fx), (1 - fy) * fx, fy * (1 - fx), fy * fx};
            p.nearest = p.corner[(fy >= 0.5f ? 2 : 0) + (fx >= 0.5f ? 1 : 0)];
        }
    return out;
}

std::vector<float> sample(const std::vector<float>& v, const std::vector<SourcePosition>& pos, size_t offset = 0)
{
    if (v.empty())
        return {};
    std::vector<float> out(pos.size(), NAN);
    for (size_t t = 0; t < pos.size(); ++t)
    {
        const SourcePosition& p = pos[t];
        if (!p.inside)
            continue;
        float sum = 0, wsum = 0;
        for (size_t k = 0; k < 4; ++k)
        {
            const float x = v[offset + p.corner[k]];
            if (std::isfinite(x) && p.weight[k] > 0)
            {
                sum += p.weight[k] * x;
                wsum += p.weight[k];
            }
        }
        if (wsum > 0)
            out[t] = sum / wsum;
    }
    return out;
}

std::vector<uint8_t> nearest(const std::vector<uint8_t>& v, const std::vector<SourcePosition>& pos)
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
    return wrapsInLongitude(g) ? 360.0 : g.dLonDeg * double(g.nLon - 1);
}

} // namespace

WeatherSnapshot resampleSnapshot(const WeatherSnapshot& s, const LatLonGrid& target)
{
    const std::vector<SourcePosition> pos = positions(s.grid, target);
    WeatherSnapshot out;
    out.grid = target;
    out.validTimeUnixS = s.validTimeUnixS;
    out.provenance = s.provenance;
    for (const CloudLayerFields& l : s.layers)
    {
        CloudLayerFields o;
        o.name = l.name;
        o.coverage = sample(l.coverage, pos);
        o.baseAltitudeM = sample(l.baseAltitudeM, pos);
        o.topAltitudeM = sample(l.topAltitudeM, pos);
        o.type = nearest(l.type, pos);
        o.precipitationMmH = sample(l.precipitationMmH, pos);
        o.windEastMS = sample(l.windEastMS, pos);
        o.windNorthMS = sample(l.windNorthMS, pos);
        out.layers.push_back(std::move(o));
    }
    out.high.coverage = sample(s.high.coverage, pos);
    out.high.altitudeM = sample(s.high.altitudeM, pos);
    out.high.type = nearest(s.high.type, pos);
    out.high.windEastMS = sample(s.high.windEastMS, pos);
    out.high.windNorthMS = sample(s.high.windNorthMS, pos);
    out.capeJKg = sample(s.capeJKg, pos);
    out.tropopauseAltitudeM = sample(s.tropopauseAltitudeM, pos);
    for (const PressureLevelField& f : s.levelFields)
    {
        PressureLevelField o{f.name, f.units, f.pressurePa, {}};
        for (size_t k = 0; k < f.pressurePa.size(); ++k)
        {
            const std::vector<float> level = sample(f.values, pos, k * s.grid.cellCount());
            o.values.insert(o.values.end(), level.begin(), level.end());
        }
        out.levelFields.push_back(std::move(o));
    }
    const std::vector<float> ones(s.dataWeight.empty() ? s.grid.cellCount() : 0, 1.0f);
    out.dataWeight = sample(s.dataWeight.empty() ? ones : s.dataWeight, pos);
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
        global = global || wrapsInLongitude(g);
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
