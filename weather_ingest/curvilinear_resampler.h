// SPDX-License-Identifier: MIT
// CurvilinearResampler: fields on a structured grid given by 2D latitude/longitude arrays (WRF's XLAT/XLONG,
// or any GRIB grid whose points ecCodes locates: Lambert conformal, polar stereographic, Mercator, rotated
// or Gaussian latitude/longitude) resampled onto a regular lat/lon grid.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <cstdint>
#include <vector>

namespace sky
{

class CurvilinearResampler
{
  public:
    /// Chooses the target grid and precomputes the weights.
    ///
    /// The target grid covers the source points with the source's mean spacing (degrees of latitude;
    /// longitude spacing divided by cos(mean latitude), so cells stay about square). It goes all the way
    /// round in longitude when the source does (columns that close on themselves, e.g. a Gaussian grid:
    /// then the target keeps the source's column count) or when the source encloses a pole (a polar
    /// stereographic grid: then it reaches the pole). Otherwise it covers the source's longitude span,
    /// across the antimeridian when needed.
    ///
    /// Each target point inside a source quad gets the inverse-bilinear weights of that quad's four
    /// corners, solved by Newton iteration in the gnomonic projection centred on the quad (great circles
    /// are straight there, so neighbouring quads share their edges exactly and the poles need no special
    /// case); points outside every quad get none (NaN after resampling).
    ///
    /// @param[in] latDeg ny * nx latitudes (degrees), row-major (the nx index fastest).
    /// @param[in] lonDeg ny * nx longitudes (degrees, any convention).
    /// @param[in] ny rows, >= 2.
    /// @param[in] nx columns, >= 2.
    /// @param[in] maxCells refuse a target grid larger than this (throws std::length_error; callers turn
    ///   it into an IngestError). Throws std::invalid_argument for missing or degenerate coordinates.
    CurvilinearResampler(const std::vector<float>& latDeg, const std::vector<float>& lonDeg, size_t ny, size_t nx,
                         size_t maxCells);

    const LatLonGrid& grid() const { return grid_; }

    /// True when the source's columns close on themselves (column nx-1 is next to column 0).
    bool periodicColumns() const { return periodic_; }

    /// True when the target grid goes all the way round in longitude (a global or polar source).
    bool global() const { return global_; }

    /// @param[in] source ny * nx values.
    /// @return grid().cellCount() values; NaN outside the source domain. A NaN source corner is left out
    ///   and the other weights renormalised (so a cloud edge does not erase its neighbours).
    std::vector<float> resample(const std::vector<float>& source) const;
    /// The same from double values (each taken as float first: the same result as from floats).
    std::vector<float> resample(const std::vector<double>& source) const;

    /// Fraction of target cells that lie inside the source domain.
    double coveredFraction() const;

  private:
    /// Where a target cell lies: the source quad (its corner at row j, column i is j * nx + i; kWrapsRound set
    /// where column i + 1 is column 0, a grid whose columns close on themselves) and the position (a along
    /// columns, b along rows, both in [0, 1], in 1/65535) inside it. 8 bytes: resampling streams these for
    /// every field.
    struct QuadPosition
    {
        uint32_t quad = kOutside;
        uint16_t a = 0;
        uint16_t b = 0;
    };
    static constexpr uint32_t kOutside = UINT32_MAX;
    static constexpr uint32_t kWrapsRound = 0x80000000u;
    static constexpr float kFractionUnit = 65535.0f;

    template <typename T> std::vector<float> resampleValues(const T* source) const;

    LatLonGrid grid_;
    size_t nx_ = 0;
    size_t ny_ = 0;
    bool periodic_ = false;
    bool global_ = false;
    std::vector<QuadPosition> cells_;
};

} // namespace sky
