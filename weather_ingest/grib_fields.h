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
    CoverLow,
    CoverMiddle,
    CoverHigh,
    CoverConvective,
    CoverBoundaryLayer,
    CoverTotal,
    PresLowBottom,
    PresLowTop,
    PresMiddleBottom,
    PresMiddleTop,
    PresHighBottom,
    PresHighTop,
    PresConvBottom,
    PresConvTop,
    Cape,
    PrecipRate,
    ConvPrecipRate,
    TotalPrecipAcc,
    ConvPrecipAcc,
    LargeScalePrecipAcc,
    TropopausePressure,
    TropopauseHeight,
    CloudBaseHeight,
    CloudBaseHeightMsl,
    CloudTopHeightMsl,
    Visibility,
    Orography,
    SurfaceGeopotential,
    LevelHeight,
    LevelGeopotential,
    LevelU,
    LevelV,
    LevelCloudMixingRatio,
    LevelCloudCover,
    LevelCloudLiquid,
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
    std::shared_ptr<const GribGrid> grid; ///< the GRIB grid it was decoded from (shared)
    std::string source;  ///< "gfs.grib2 message 250 tcc/lowCloudLayer/0"
    std::string file;    ///< path of the file it came from
};

/// Reads a GRIB file and decodes every message that has a role (others are skipped undecoded). Winds
/// given relative to a projected grid (u/v pairs of one level and grid) are turned to east/north.
///
/// @param[in] file an open file, read from its current position.
/// @param[in] maxCells largest grid accepted.
/// @param[in] progress optional progress callback.
/// @param[in,out] grids grids located so far (shared between the files of one conversion).
/// @return the records in file order. Throws IngestError: NotRecognized when the file has no GRIB
///   message at all; Corrupt, UnsupportedGrid, TooLarge from the decoder.
std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress,
                                        GribGridCache& grids);
std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress);

/// The model family whose names a message's centre and grid suggest, for `sky-ingest info`, e.g.
/// "NCEP HRRR/NAM/RAP (regional)", "ECMWF IFS", "DWD ICON".
std::string mappingName(long centre, const std::string& gridType);

}  // namespace sky
