// SPDX-License-Identifier: MIT
// GribGrid: how the values of one GRIB grid become a field on the snapshot's regular lat/lon grid, built
// once per distinct grid (GRIB's grid section) and shared by every message on it.
//
// Regular lat/lon grids are used as they are (only reordered). Every other grid whose points ecCodes can
// locate (Lambert conformal, polar stereographic, Mercator, rotated lat/lon, regular Gaussian: Ni x Nj
// points; reduced Gaussian, octahedral and reduced lat/lon: rows of varying length, first expanded to
// rows of equal length by linear interpolation along each row) is resampled by CurvilinearResampler.
#pragma once

#include "weather_ingest/curvilinear_resampler.h"
#include "weather_ingest/weather_snapshot.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sky
{

/// Width of the soft edge of a regional grid: its outer 5 % on each side (WeatherSnapshot::dataWeight).
inline constexpr double kRegionalEdgeFraction = 0.05;

/// Where each point of a GRIB grid lies, in the order of the message's values (from ecCodes' iterator).
struct GribGridPoints
{
    std::string gridType;    ///< ecCodes gridType, e.g. "lambert", "reduced_gg"
    std::string description; ///< human-readable grid, size and resolution (for info and provenance)
    size_t ni = 0;           ///< points along a row (structured grids); 0 for reduced grids
    size_t nj = 0;           ///< rows
    std::vector<long> pl;    ///< points per row, reduced grids only
    bool iScansNegatively = false;
    bool jPointsAreConsecutive = false;
    bool alternativeRowScanning = false;
    std::vector<double> latDeg; ///< one per value
    std::vector<double> lonDeg; ///< one per value
};

/// A grid ready to turn message values into snapshot fields.
class GribGrid
{
  public:
    /// A regular lat/lon grid that needs no resampling (values already in canonical order).
    GribGrid(const LatLonGrid& grid, std::string description);

    /// Any other grid. Throws std::invalid_argument (what the grid lacks) or std::length_error (too large).
    GribGrid(const GribGridPoints& points, size_t maxCells);

    const LatLonGrid& target() const { return target_; }
    const std::string& description() const { return description_; }
    const std::string& gridType() const { return gridType_; }
    size_t sourcePoints() const { return sourcePoints_; }

    /// True when the grid covers only part of the globe (dataWeight() is then non-empty).
    bool regional() const { return !dataWeight_.empty(); }

    /// Per target cell: 1 inside, ramping to 0 over the outer kRegionalEdgeFraction, 0 outside. Empty
    /// for a global grid.
    const std::vector<float>& dataWeight() const { return dataWeight_; }

    /// Rotates grid-relative winds (u along the grid's x axis, v along y) to east/north, in place.
    /// A no-op on grids whose axes are east and north.
    void rotateToEarth(std::vector<float>& u, std::vector<float>& v) const;

    /// @param[in] values one per point in the message's order; NaN = missing.
    /// @return target().cellCount() values (NaN = missing or outside the grid).
    std::vector<float> resample(const std::vector<double>& values) const;

  private:
    std::vector<float> structured(const std::vector<double>& values) const;
    void makeEdgeWeights(const std::vector<float>& structuredLat, bool periodic);
    /// Reduced grid: sets the row tables and nx_/ny_, and the expanded structured coordinates.
    void expandReducedRows(const GribGridPoints& p, std::vector<float>& lat, std::vector<float>& lon);
    /// ni x nj grid: sets nx_/ny_ and order_ (for other scanning modes) and the coordinates in (j, i) order.
    void orderStructuredPoints(const GribGridPoints& p, std::vector<float>& lat, std::vector<float>& lon);
    /// Sets xAxisCos_/xAxisSin_ for winds given relative to the grid.
    void makeXAxisDirections(const GribGridPoints& p, const std::vector<float>& lat, const std::vector<float>& lon);

    std::string gridType_;
    std::string description_;
    size_t sourcePoints_ = 0;
    LatLonGrid target_;
    std::vector<float> dataWeight_;
    std::vector<float> xAxisCos_, xAxisSin_; ///< direction of the grid's x axis (east = 0), per target cell
    size_t nx_ = 0, ny_ = 0;                 ///< the structured layout (after expanding reduced rows)
    std::vector<uint32_t> order_;            ///< structured index -> value index (empty: identity)
    std::vector<size_t> rowStart_;           ///< reduced grids: first value of each row
    std::vector<long> rowPoints_;            ///< reduced grids: points in each row
    std::vector<double> rowShift_;           ///< reduced grids: first column's offset in the row (in points)
    std::unique_ptr<CurvilinearResampler> resampler_;
};

/// Grids by their grid section's checksum, so each is located and weighted once per conversion.
class GribGridCache
{
  public:
    std::shared_ptr<const GribGrid> find(const std::string& key) const
    {
        const auto it = grids_.find(key);
        return it == grids_.end() ? nullptr : it->second;
    }
    void add(const std::string& key, std::shared_ptr<const GribGrid> grid) { grids_[key] = std::move(grid); }

  private:
    std::map<std::string, std::shared_ptr<const GribGrid>> grids_;
};

} // namespace sky
