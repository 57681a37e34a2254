// SPDX-License-Identifier: MIT
// The cloud-type rule table: which WMO genus a layer's cloud is, from the layer, its thickness, coverage,
// precipitation and convective signals. The table is data (cloudTypeRules()) so that the README and
// `sky-ingest info` print exactly what the code applies.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <cmath>

#include <string>
#include <vector>

namespace sky
{

/// The layer a cloud belongs to.
enum class LayerKind : uint8_t
{
    Low,         ///< snapshot layer 0
    Middle,      ///< snapshot layer 1
    Convective,  ///< snapshot layer 2 (cumulus / cumulonimbus towers)
    High,        ///< WeatherSnapshot::high (2D texture layer)
};

/// How strong the convective signals must be for a rule.
enum class ConvectiveSignal : uint8_t
{
    Any,     ///< no condition
    Weak,    ///< CAPE >= 300 J/kg or convective precipitation >= 0.1 mm/h
    Strong,  ///< CAPE >= 1000 J/kg or convective precipitation >= 1 mm/h
};

/// Thresholds of ConvectiveSignal. CAPE classes after the usual forecasting guidance (e.g. NOAA/SPC:
/// < 1000 J/kg marginal, 1000-2500 moderate instability); 1 mm/h convective rain is a shower that a
/// cumulonimbus, not a cumulus, produces.
inline constexpr float kWeakCapeJKg = 300.0f;
inline constexpr float kStrongCapeJKg = 1000.0f;
inline constexpr float kWeakConvPrecipMmH = 0.1f;
inline constexpr float kStrongConvPrecipMmH = 1.0f;

/// Below this coverage (fraction) a cell has no cloud (type None).
inline constexpr float kMinCloudCoverage = 0.01f;

/// One row of the table. A rule matches when every condition holds; the first match wins. An unknown
/// (NaN) thickness fails any thickness condition; unknown CAPE counts as 0.
struct CloudTypeRule
{
    LayerKind layer;
    float minThicknessM;     ///< thickness >= this (use -inf for none)
    float maxThicknessM;     ///< thickness < this (use +inf for none)
    float minCoverage;       ///< coverage >= this
    float maxCoverage;       ///< coverage < this (2 for none)
    float minPrecipMmH;      ///< precipitation falling from this layer >= this
    ConvectiveSignal signal;
    CloudType type;
    const char* why;         ///< one line for the README
};

/// The per-cell inputs of the classification.
struct CloudTypeInputs
{
    LayerKind layer = LayerKind::Low;
    float coverage = 0;          ///< fraction
    float thicknessM = NAN;      ///< top - base (m), NaN if unknown
    float precipMmH = 0;         ///< precipitation attributed to this layer (mm/h)
    float capeJKg = NAN;         ///< NaN if unknown
    float convPrecipMmH = 0;     ///< convective precipitation at the cell (mm/h)
};

/// The table, in evaluation order.
const std::vector<CloudTypeRule>& cloudTypeRules();

/// @return the genus of the first matching rule (None below kMinCloudCoverage or for NaN coverage).
CloudType classifyCloud(const CloudTypeInputs& in);

/// The table as Markdown (README "Cloud types" and `sky-ingest info --rules`).
std::string cloudTypeRulesMarkdown();

/// "Cumulonimbus", "low", … for messages and tables.
const char* cloudTypeName(CloudType type);
const char* layerKindName(LayerKind layer);

}  // namespace sky
