// SPDX-License-Identifier: MIT
// WeatherTimeline: the weather at any time, from snapshots at a few valid times.
//
// Rule between snapshots: linear interpolation in time of every continuous field (coverage,
// altitudes, precipitation, wind, CAPE, tropopause, level fields). Where a value is NaN (unknown) on
// one side only, the known side's value is used unchanged; NaN on both sides stays NaN. Cloud type is
// categorical: it is taken from the nearer snapshot, unless that side has no cloud there (None), in
// which case the other side's type is used, so a cloud fading in or out keeps its genus. Layers are
// matched by name; a layer present on one side only fades in or out (its coverage is scaled by the
// weight of the side that has it).
//
// Rule outside the range: the nearest snapshot is held unchanged (no extrapolation); bracket()
// reports it with `clamped`, so callers can warn that the weather is stale.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

class WeatherTimeline
{
public:
    /// Where a time falls between snapshots.
    struct Bracket
    {
        size_t before = 0;        ///< index of the snapshot at or before the time
        size_t after = 0;         ///< index of the snapshot after (== before when clamped or exact)
        double weightAfter = 0;   ///< interpolation weight of `after`, in [0, 1]
        bool clamped = false;     ///< the time is outside [firstTimeUnixS, lastTimeUnixS]
    };

    /// Replaces the content. Snapshots may come in any order; they are sorted by valid time.
    ///
    /// @param[in] snapshots at least one; all on the same grid, with distinct valid times.
    /// @param[out] error why they were refused (the timeline is then unchanged).
    /// @return true on success.
    bool setSnapshots(std::vector<WeatherSnapshot> snapshots, std::string& error);

    /// Loads every snapshot of a snapshot file (readSnapshotFile, then setSnapshots). On failure the
    /// timeline keeps what it had, so a service keeps its last good weather.
    bool loadFile(const std::string& path, std::string& error);

    bool empty() const { return snapshots_.empty(); }
    size_t size() const { return snapshots_.size(); }
    const WeatherSnapshot& snapshot(size_t i) const { return snapshots_.at(i); }
    int64_t firstTimeUnixS() const { return snapshots_.front().validTimeUnixS; }  ///< precondition: !empty()
    int64_t lastTimeUnixS() const { return snapshots_.back().validTimeUnixS; }    ///< precondition: !empty()

    /// @param[in] timeUnixS seconds since 1970-01-01T00:00:00Z (fractions allowed).
    /// @return the bracketing snapshots and weight. Precondition: !empty().
    Bracket bracket(double timeUnixS) const;

    /// The weather at a time, following the rules at the top of this file. validTimeUnixS of the
    /// result is the requested time rounded down. Precondition: !empty().
    WeatherSnapshot sample(double timeUnixS) const;

    /// As sample(), reusing out's allocations (for a service that samples every frame).
    void sampleInto(double timeUnixS, WeatherSnapshot& out) const;

private:
    std::vector<WeatherSnapshot> snapshots_;
};

}  // namespace sky
