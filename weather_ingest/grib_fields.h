// SPDX-License-Identifier: MIT
// Which GRIB messages the mapping uses (NCEP GFS and ECMWF names), and reading them from a file.
// README "Field mapping" is generated from the same table (gribRoleTable()).
#pragma once

#include "weather_ingest/grib_file.h"
#include "weather_ingest/ingest_progress.h"

#include <optional>
#include <string>
#include <vector>

namespace sky
{

/// What a message is used for.
enum class GribRole : uint8_t
{
    CoverLow, CoverMiddle, CoverHigh, CoverConvective, CoverBoundaryLayer, CoverTotal,
    PresLowBottom, PresLowTop, PresMiddleBottom, PresMiddleTop, PresHighBottom, PresHighTop,
    PresConvBottom, PresConvTop,
    Cape, PrecipRate, ConvPrecipRate, TotalPrecipAcc, ConvPrecipAcc, LargeScalePrecipAcc,
    TropopausePressure, TropopauseHeight, CloudBaseHeight, Orography, SurfaceGeopotential,
    LevelHeight, LevelGeopotential, LevelU, LevelV, LevelCloudMixingRatio, LevelCloudCover, LevelCloudLiquid,
    LevelCloudIce,
    Count
};

/// One row of the mapping table.
struct GribRoleRow
{
    GribRole role;
    const char* shortNames;    ///< ecCodes short names, '|' separated
    const char* typeOfLevels;  ///< '|' separated, "*" for any
    int priority;              ///< lower wins when several messages have the same role and level
    const char* source;        ///< "GFS", "ECMWF", "GFS, ECMWF"
    const char* meaning;       ///< what the field is
    const char* target;        ///< what it becomes in the snapshot
};

/// The whole table, in the order the README prints it.
const std::vector<GribRoleRow>& gribRoleTable();

/// @return the role of a message, or nothing when the mapping does not use it.
std::optional<GribRoleRow> gribRoleOf(const GribMessageInfo& info);

/// @return true for roles given on isobaric levels (one message per level).
bool isLevelRole(GribRole role);

/// A decoded message with its role.
struct GribRecord
{
    GribMessageInfo info;
    GribRoleRow row;
    double levelPa = 0;  ///< pressure of an isobaric level (Pa); 0 otherwise
    GridField field;
    std::string source;  ///< "gfs.grib2 message 250 tcc/lowCloudLayer/0"
    std::string file;    ///< path of the file it came from
};

/// Reads a GRIB file and decodes every message that has a role (others are skipped undecoded).
///
/// @param[in] file an open file, read from its current position.
/// @param[in] maxCells largest grid accepted.
/// @param[in] progress optional progress callback.
/// @return the records in file order. Throws IngestError: NotRecognized when the file has no GRIB
///   message at all; Corrupt, UnsupportedGrid, TooLarge from the decoder.
std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress);

}  // namespace sky
