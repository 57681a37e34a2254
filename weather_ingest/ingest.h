// SPDX-License-Identifier: MIT
// The entry points of sky_ingest: recognise a weather file, describe it, convert files to snapshots.
#pragma once

#include "weather_ingest/ingest_progress.h"
#include "weather_ingest/layer_builder.h"
#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

enum class InputFormat
{
    Grib,    ///< GRIB edition 1 or 2 (ecCodes)
    NetCdf,  ///< NetCDF-3 classic / 64-bit offset / CDF-5, or NetCDF-4 (HDF5)
};

/// Recognises a file by its first bytes ("GRIB" within the first 4 KiB, which also skips WMO bulletin
/// headers; "CDF\x01", "CDF\x02", "CDF\x05"; the HDF5 signature).
///
/// @return the format. Throws IngestError: Io when unreadable, NotRecognized otherwise (the message
///   says what the file looks like: empty, PNG, text…).
InputFormat detectFormat(const std::string& path);

/// What conversion produced.
struct ConvertResult
{
    std::vector<WeatherSnapshot> snapshots;  ///< sorted by valid time
    std::vector<std::string> warnings;       ///< fallbacks and lenient repairs, for the user
};

/// Converts files (GRIB and NetCDF may be mixed) into snapshots. GRIB messages of all files are grouped
/// by valid time (one snapshot per time); a WRF file gives one snapshot per time in `Times`.
///
/// @param[in] paths input files, at least one.
/// @param[in] options strictness and 3D fields.
/// @param[in] progress optional.
/// @return the snapshots, each passing validateSnapshot(). Throws IngestError (the kind says why;
///   exitCodeFor() gives the CLI's code); two inputs with the same valid time on different grids are
///   an UnsupportedGrid error; the same valid time twice from WRF files is a BadValues error.
ConvertResult convertFiles(const std::vector<std::string>& paths, const MappingOptions& options,
                           const ProgressFn& progress);

/// A human-readable inventory of a file (`sky-ingest info`): format, grid, valid times, the fields
/// found and what each maps to, the fields the mapping looks for but did not find.
/// Throws IngestError as detectFormat() and the readers do.
std::string describeFile(const std::string& path);

}  // namespace sky
