// SPDX-License-Identifier: MIT
// IngestError: the one error type of sky_ingest. It names the file, the message (GRIB) or variable
// (NetCDF) and the field, and its kind decides the exit code of sky-ingest (README "Exit codes").
#pragma once

#include <stdexcept>
#include <string>

namespace sky
{

enum class IngestErrorKind
{
    Io,              ///< the file cannot be opened or read (missing, permission, I/O error)
    NotRecognized,   ///< neither GRIB nor NetCDF (empty file, PNG renamed .grib2…)
    Corrupt,         ///< recognised but damaged: truncated message, decoder error
    UnsupportedGrid, ///< a grid ecCodes cannot locate (spectral, unstructured) or a degenerate projection
    TooLarge,        ///< an absurd grid size (over kMaxSnapshotCells) or dimension
    MissingFields,   ///< none of the fields a cloud layer needs
    BadValues,       ///< values outside physical ranges: coverage beyond [0, 100] %, NaN, base above top
    Output,          ///< the snapshot could not be written
};

/// Thrown by sky_ingest functions (documented per function). what() is the full message.
class IngestError : public std::runtime_error
{
public:
    /// @param[in] kind what went wrong.
    /// @param[in] file path of the input (or output).
    /// @param[in] location "message 12" (GRIB, 1-based) or "variable QCLOUD" (NetCDF); may be empty.
    /// @param[in] field the field involved (e.g. "tcc/lowCloudLayer"); may be empty.
    /// @param[in] detail the reason, for a human.
    IngestError(IngestErrorKind kind, const std::string& file, const std::string& location, const std::string& field,
                const std::string& detail);

    IngestErrorKind kind() const { return kind_; }
    const std::string& file() const { return file_; }
    const std::string& location() const { return location_; }
    const std::string& field() const { return field_; }

private:
    IngestErrorKind kind_;
    std::string file_;
    std::string location_;
    std::string field_;
};

/// The exit code of sky-ingest for an error kind: Io 3, NotRecognized 4, Corrupt 5, UnsupportedGrid 6,
/// TooLarge 6, MissingFields 7, BadValues 8, Output 9 (0 success, 1 internal error, 2 usage).
int exitCodeFor(IngestErrorKind kind);

/// A short name of the kind ("io", "not-recognized", …) for messages.
const char* kindName(IngestErrorKind kind);

}  // namespace sky
