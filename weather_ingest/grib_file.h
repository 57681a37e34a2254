// SPDX-License-Identifier: MIT
// GribFile / GribMessage: the only place that calls ecCodes for reading (docs/style.md §11). Handles are owned
// by std::unique_ptr with codes_handle_delete; every ecCodes error becomes an IngestError that names the
// file, the message number (1-based) and the key or field.
#pragma once

#include "weather_ingest/grib_grid.h"
#include "weather_ingest/regular_grid.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

struct grib_handle;  // ecCodes' codes_handle, kept opaque so that callers never include eccodes.h

namespace sky
{

/// What the mapping needs to know about a message before decoding its values.
struct GribMessageInfo
{
    int number = 0;             ///< 1-based position in the file
    long edition = 0;           ///< 1 or 2
    std::string shortName;      ///< ecCodes short name, e.g. "tcc", "pres", "gh"
    std::string typeOfLevel;    ///< e.g. "lowCloudLayer", "isobaricInhPa", "surface"
    std::string units;          ///< as ecCodes reports them, e.g. "%", "Pa", "(0 - 1)"
    std::string name;           ///< long name
    std::string gridType;       ///< e.g. "regular_ll", "reduced_gg"
    long level = 0;             ///< level value in the unit of typeOfLevel
    long centre = 0;            ///< originating centre (7 NCEP, 98 ECMWF)
    int64_t validTimeUnixS = 0; ///< validity date and time
    double accumulationHours = 0;  ///< endStep - startStep (hours) for accumulated/averaged fields, else 0
    std::string stepRange;      ///< e.g. "120", "114-120"
    std::string gridDescription;   ///< grid type, size, resolution, e.g. "lambert 1799 x 1059, 3 km, ..." (for info)
    std::string gridKey;           ///< checksum of the grid section: messages with equal keys share a grid
    bool uvRelativeToGrid = false; ///< vector components along the grid's x/y axes, not east/north

    std::string label() const { return shortName + "/" + typeOfLevel + "/" + std::to_string(level); }
};

/// One GRIB message (owns its handle).
class GribMessage
{
public:
    GribMessage();
    ~GribMessage();
    GribMessage(GribMessage&&) noexcept;
    GribMessage& operator=(GribMessage&&) noexcept;

    const GribMessageInfo& info() const { return info_; }

    /// Decodes the values onto a regular lat/lon grid in canonical order (any scanning mode, any
    /// longitude convention; points missing from the bitmap become NaN). Regular lat/lon grids are
    /// taken as they are; every other grid whose points ecCodes can locate is resampled (GribGrid).
    ///
    /// @param[in] maxCells refuse grids larger than this (IngestErrorKind::TooLarge).
    /// @param[in,out] grids grids already located; a new grid is added.
    /// @param[out] grid optional: the grid the field is on.
    /// @return the field. Throws IngestError naming the grid: UnsupportedGrid when ecCodes cannot locate
    ///   the points (spectral, unstructured…) or the projection is degenerate, TooLarge, Corrupt when
    ///   the grid keys and the number of values disagree or ecCodes fails.
    GridField decode(size_t maxCells, GribGridCache& grids, std::shared_ptr<const GribGrid>* grid = nullptr) const;

    /// As above with a cache of its own (one message).
    GridField decode(size_t maxCells) const;

private:
    friend class GribFile;
    GridField decodeRegular(size_t maxCells) const;
    GribGridPoints locatePoints(size_t maxCells) const;
    struct HandleDeleter
    {
        void operator()(grib_handle* h) const;
    };
    std::unique_ptr<grib_handle, HandleDeleter> handle_;
    std::string file_;
    GribMessageInfo info_;
};

/// A GRIB1/GRIB2 file read message by message (a GRIB2 multi-field message counts as one message per
/// field, as `grib_ls` counts them). The file is read into memory and framed by grib_framing.h first.
class GribFile
{
public:
    /// Reads a file. Throws IngestError(Io) when it cannot be read.
    explicit GribFile(const std::string& path);

    /// Reads GRIB from bytes in memory (the fuzzer's entry); the bytes are copied.
    GribFile(const std::string& name, const void* data, size_t size);

    ~GribFile();
    GribFile(const GribFile&) = delete;
    GribFile& operator=(const GribFile&) = delete;

    /// Reads the next message and its GribMessageInfo (values are decoded only by decode()).
    ///
    /// @return false at the end of the file. Throws IngestError(Corrupt) for a damaged message (e.g.
    ///   truncated, sections that do not chain to the end marker), naming the message number.
    bool next(GribMessage& message);

    const std::string& path() const { return path_; }
    int messagesRead() const { return count_; }

    /// Fraction of the file's bytes read so far, in [0, 1] (for progress bars).
    double fractionRead() const;

private:
    std::string path_;
    std::vector<uint8_t> bytes_;
    size_t offset_ = 0;
    std::deque<std::vector<uint8_t>> pending_;  // fields of the current multi-field message
    int count_ = 0;
};

}  // namespace sky
