// SPDX-License-Identifier: MIT
// What the GRIB and WRF mappings share: checking values, the default layer heights, precipitation
// attribution and the cloud-type pass over a finished snapshot.
#pragma once

#include "weather_ingest/cloud_type_rules.h"
#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

/// How strictly the mappings treat bad values.
struct MappingOptions
{
    /// false: coverage outside [0, 100] %, NaN in the data, or a base above its top is an error
    /// (IngestErrorKind::BadValues). true: clamp, drop or swap, and add a warning.
    bool lenient = false;
    /// Keep the optional 3D fields (cloud mixing ratio, cloud cover on levels) as levelFields.
    bool keepLevelFields = false;
    /// Amplification guard: the decoded fields, and the snapshot to write, may each take at most
    /// max(amplificationFloorBytes, maxAmplification x the input files' bytes). A few hundred bytes of
    /// GRIB2 can declare a constant 8192 x 8192 field: without the guard that is gigabytes of output.
    uint64_t amplificationFloorBytes = 64ull << 20;
    double maxAmplification = 100;
    bool allowLargeOutput = false;  ///< sky-ingest --allow-large-output: no guard
};

/// Snapshot layer indices (README "Snapshot layers").
inline constexpr size_t kLowLayer = 0;
inline constexpr size_t kMiddleLayer = 1;
inline constexpr size_t kConvectiveLayer = 2;

/// Default base and top pressures of a layer where a model gives coverage but no base/top (Pa). They
/// bracket the usual étages of the WMO Cloud Atlas at mid-latitudes (low below ~2 km, middle 2-7 km,
/// high above ~6 km) in the standard atmosphere.
struct LayerDefaults
{
    double basePa;
    double topPa;
};
LayerDefaults layerDefaults(LayerKind layer);

/// Checks values against the rules of MappingOptions, naming the field and source in errors.
class ValueChecker
{
public:
    ValueChecker(const MappingOptions& options, std::vector<std::string>& warnings, std::string file)
        : options_(options), warnings_(warnings), file_(std::move(file))
    {
    }

    /// NaN/inf in the data that were not flagged missing: an error, or a warning when lenient.
    void invalidValues(size_t count, const std::string& field, const std::string& source) const;

    /// Scales coverage to a fraction (scale 0.01 for %) and checks [0, 1] (0.5 % tolerance, then
    /// clamped); NaN stays NaN (unknown).
    void coverage(std::vector<float>& values, float scale, const std::string& field, const std::string& source,
                  const LatLonGrid& grid) const;

    /// Checks base <= top (1 m tolerance) cell by cell; lenient swaps them.
    void baseBelowTop(std::vector<float>& base, std::vector<float>& top, const std::string& field,
                      const std::string& source, const LatLonGrid& grid) const;

    /// A value range check for anything else (pressures, heights…).
    void range(std::vector<float>& values, float lo, float hi, const std::string& field, const std::string& source,
               const LatLonGrid& grid) const;

    void warn(const std::string& text) const { warnings_.push_back(file_ + ": " + text); }
    const MappingOptions& options() const { return options_; }

private:
    [[noreturn]] void fail(const std::string& field, const std::string& source, const std::string& detail) const;
    const MappingOptions& options_;
    std::vector<std::string>& warnings_;
    std::string file_;
};

/// Empty layers (all vectors of n cells: coverage 0, altitudes NaN, precipitation and wind 0).
std::vector<CloudLayerFields> makeEmptyLayers(size_t n);

/// Splits precipitation between layers: convective precipitation to the convective layer where it has
/// cloud, else to the low layer; the rest (large-scale) to the middle layer where it has more cover
/// than the low layer, else to the low layer. Either input may be empty (unknown).
void attributePrecipitation(WeatherSnapshot& s, const std::vector<float>& convectiveMmH,
                            const std::vector<float>& largeScaleMmH);

/// Sets every layer's and the high layer's type from cloudTypeRules().
///
/// @param[in] convectiveMmH convective precipitation per cell (may be empty).
void assignCloudTypes(WeatherSnapshot& s, const std::vector<float>& convectiveMmH);

/// "(lat, lon)" of a cell, for messages.
std::string cellName(const LatLonGrid& grid, size_t cell);

}  // namespace sky
