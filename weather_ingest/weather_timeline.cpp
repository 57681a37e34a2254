// SPDX-License-Identifier: MIT
#include "weather_ingest/weather_timeline.h"

#include "weather_ingest/snapshot_file.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

const std::vector<float> kNone;
const std::vector<uint8_t> kNoTypes;

/// out = a*(1-w) + b*w with the NaN rule of the header; an empty input counts as all-NaN, or as all
/// `missingAs` when that is finite (coverage of a layer that exists on one side only fades).
void blend(const std::vector<float>& a, const std::vector<float>& b, float w, size_t n, float missingAs,
           std::vector<float>& out)
{
    if (a.empty() && b.empty() && !std::isfinite(missingAs))
    {
        out.clear();
        return;
    }
    out.resize(n);
    const float wa = 1.0f - w;
    for (size_t i = 0; i < n; ++i)
    {
        const float va = a.empty() ? missingAs : a[i];
        const float vb = b.empty() ? missingAs : b[i];
        const bool fa = std::isfinite(va);
        const bool fb = std::isfinite(vb);
        out[i] = fa && fb ? va * wa + vb * w : (fa ? va : vb);
    }
}

void pickTypes(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, float w, size_t n,
               std::vector<uint8_t>& out)
{
    if (a.empty() && b.empty())
    {
        out.clear();
        return;
    }
    out.resize(n);
    const bool preferB = w >= 0.5f;
    for (size_t i = 0; i < n; ++i)
    {
        const uint8_t ta = a.empty() ? 0 : a[i];
        const uint8_t tb = b.empty() ? 0 : b[i];
        const uint8_t nearer = preferB ? tb : ta;
        out[i] = nearer != 0 ? nearer : (preferB ? ta : tb);
    }
}

void blendLayer(const CloudLayerFields* a, const CloudLayerFields* b, float w, size_t n, CloudLayerFields& out)
{
    static const CloudLayerFields kEmpty;
    const CloudLayerFields& la = a ? *a : kEmpty;
    const CloudLayerFields& lb = b ? *b : kEmpty;
    out.name = a ? a->name : b->name;
    blend(la.coverage, lb.coverage, w, n, 0.0f, out.coverage);
    const float nan = NAN;
    blend(la.baseAltitudeM, lb.baseAltitudeM, w, n, nan, out.baseAltitudeM);
    blend(la.topAltitudeM, lb.topAltitudeM, w, n, nan, out.topAltitudeM);
    pickTypes(la.type, lb.type, w, n, out.type);
    blend(la.precipitationMmH, lb.precipitationMmH, w, n, nan, out.precipitationMmH);
    blend(la.windEastMS, lb.windEastMS, w, n, nan, out.windEastMS);
    blend(la.windNorthMS, lb.windNorthMS, w, n, nan, out.windNorthMS);
}

const CloudLayerFields* findLayer(const WeatherSnapshot& s, const std::string& name)
{
    for (const CloudLayerFields& l : s.layers)
        if (l.name == name)
            return &l;
    return nullptr;
}

bool sameGrid(const LatLonGrid& a, const LatLonGrid& b)
{
    return a.nLat == b.nLat && a.nLon == b.nLon && a.lat0Deg == b.lat0Deg && a.lon0Deg == b.lon0Deg &&
           a.dLatDeg == b.dLatDeg && a.dLonDeg == b.dLonDeg;
}

}  // namespace

bool WeatherTimeline::setSnapshots(std::vector<WeatherSnapshot> snapshots, std::string& error)
{
    if (snapshots.empty())
    {
        error = "no snapshots";
        return false;
    }
    std::stable_sort(snapshots.begin(), snapshots.end(),
                     [](const WeatherSnapshot& a, const WeatherSnapshot& b) { return a.validTimeUnixS < b.validTimeUnixS; });
    for (size_t i = 0; i < snapshots.size(); ++i)
    {
        if (!validateSnapshot(snapshots[i], error))
            return false;
        if (i > 0 && snapshots[i].validTimeUnixS == snapshots[i - 1].validTimeUnixS)
        {
            error = "two snapshots have the same valid time " + std::to_string(snapshots[i].validTimeUnixS);
            return false;
        }
        if (!sameGrid(snapshots[i].grid, snapshots[0].grid))
        {
            error = "snapshots are on different grids; a timeline needs one grid";
            return false;
        }
    }
    snapshots_ = std::move(snapshots);
    return true;
}

bool WeatherTimeline::loadFile(const std::string& path, std::string& error)
{
    std::vector<WeatherSnapshot> loaded;
    return readSnapshotFile(path, loaded, error) && setSnapshots(std::move(loaded), error);
}

WeatherTimeline::Bracket WeatherTimeline::bracket(double timeUnixS) const
{
    Bracket r;
    const size_t last = snapshots_.size() - 1;
    if (!(timeUnixS > double(firstTimeUnixS())))  // also catches NaN
    {
        r.clamped = timeUnixS != double(firstTimeUnixS());
        return r;
    }
    if (timeUnixS >= double(lastTimeUnixS()))
    {
        r.before = r.after = last;
        r.clamped = timeUnixS > double(lastTimeUnixS());
        return r;
    }
    const auto it = std::upper_bound(snapshots_.begin(), snapshots_.end(), timeUnixS,
                                     [](double t, const WeatherSnapshot& s) { return t < double(s.validTimeUnixS); });
    r.after = size_t(it - snapshots_.begin());
    r.before = r.after - 1;
    const double t0 = double(snapshots_[r.before].validTimeUnixS);
    const double t1 = double(snapshots_[r.after].validTimeUnixS);
    r.weightAfter = (timeUnixS - t0) / (t1 - t0);
    return r;
}

WeatherSnapshot WeatherTimeline::sample(double timeUnixS) const
{
    WeatherSnapshot out;
    sampleInto(timeUnixS, out);
    return out;
}

void WeatherTimeline::sampleInto(double timeUnixS, WeatherSnapshot& out) const
{
    const Bracket br = bracket(timeUnixS);
    const WeatherSnapshot& a = snapshots_[br.before];
    const WeatherSnapshot& b = snapshots_[br.after];
    const auto w = static_cast<float>(br.weightAfter);
    const size_t n = a.grid.cellCount();
    const float nan = NAN;

    out.grid = a.grid;
    out.validTimeUnixS = std::isfinite(timeUnixS) ? static_cast<int64_t>(std::floor(timeUnixS)) : a.validTimeUnixS;
    out.provenance = w >= 0.5f ? b.provenance : a.provenance;
    out.provenance["timeline"] = br.before == br.after
                                     ? "snapshot " + std::to_string(br.before) + (br.clamped ? " (held: time outside range)" : "")
                                     : "interpolated between snapshots " + std::to_string(br.before) + " and " +
                                           std::to_string(br.after) + ", weight " + std::to_string(w);

    std::vector<std::string> names;
    for (const CloudLayerFields& l : a.layers)
        names.push_back(l.name);
    for (const CloudLayerFields& l : b.layers)
        if (std::find(names.begin(), names.end(), l.name) == names.end())
            names.push_back(l.name);
    names.resize(std::min(names.size(), size_t(kMaxCloudLayers)));
    out.layers.resize(names.size());
    for (size_t i = 0; i < names.size(); ++i)
        blendLayer(findLayer(a, names[i]), findLayer(b, names[i]), w, n, out.layers[i]);

    blend(a.high.coverage, b.high.coverage, w, n, a.high.coverage.empty() || b.high.coverage.empty() ? 0.0f : nan,
          out.high.coverage);
    blend(a.high.altitudeM, b.high.altitudeM, w, n, nan, out.high.altitudeM);
    pickTypes(a.high.type, b.high.type, w, n, out.high.type);
    blend(a.high.windEastMS, b.high.windEastMS, w, n, nan, out.high.windEastMS);
    blend(a.high.windNorthMS, b.high.windNorthMS, w, n, nan, out.high.windNorthMS);
    if (a.high.coverage.empty() && b.high.coverage.empty())
        out.high.coverage.clear();
    blend(a.capeJKg, b.capeJKg, w, n, nan, out.capeJKg);
    blend(a.tropopauseAltitudeM, b.tropopauseAltitudeM, w, n, nan, out.tropopauseAltitudeM);

    // Level fields interpolate only when both sides have the same levels; otherwise the nearer side's.
    out.levelFields.clear();
    for (const PressureLevelField& fa : a.levelFields)
    {
        const PressureLevelField* fb = nullptr;
        for (const PressureLevelField& f : b.levelFields)
            if (f.name == fa.name && f.pressurePa == fa.pressurePa)
                fb = &f;
        PressureLevelField f = fa;
        if (fb)
            blend(fa.values, fb->values, w, fa.values.size(), nan, f.values);
        out.levelFields.push_back(std::move(f));
    }
}

}  // namespace sky
