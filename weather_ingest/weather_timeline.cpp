// SPDX-License-Identifier: MIT
#include "weather_ingest/weather_timeline.h"

#include "weather_ingest/snapshot_blend.h"
#include "weather_ingest/snapshot_file.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

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
    out.grid = a.grid;
    out.validTimeUnixS = std::isfinite(timeUnixS) ? static_cast<int64_t>(std::floor(timeUnixS)) : a.validTimeUnixS;
    out.provenance = w >= 0.5f ? b.provenance : a.provenance;
    out.provenance["timeline"] = br.before == br.after
                                     ? "snapshot " + std::to_string(br.before) + (br.clamped ? " (held: time outside range)" : "")
                                     : "interpolated between snapshots " + std::to_string(br.before) + " and " +
                                           std::to_string(br.after) + ", weight " + std::to_string(w);

    blendSnapshotFields(a, b, BlendWeight{w, nullptr}, out);
}

}  // namespace sky
