// SPDX-License-Identifier: MIT
// CurvilinearResampler: fields on a grid given by 2D latitude/longitude arrays (WRF's XLAT/XLONG on a
// Lambert conformal, Mercator or polar stereographic projection) resampled onto a regular lat/lon grid.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <array>
#include <cstdint>
#include <vector>

namespace sky
{

class CurvilinearResampler
{
public:
    /// Chooses the target grid and precomputes the weights.
    ///
    /// The target grid covers the bounding box of the source points with the source's mean spacing
    /// (degrees of latitude; longitude spacing divided by cos(central latitude), so cells stay about
    /// square). Each target point inside a source quad gets the inverse-bilinear weights of that
    /// quad's four corners (Newton iteration in a local equirectangular plane); points outside every
    /// quad get none (NaN after resampling).
    ///
    /// @param[in] latDeg ny * nx latitudes (degrees), row-major (the nx index fastest).
    /// @param[in] lonDeg ny * nx longitudes (degrees, any convention; unwrapped around the first point).
    /// @param[in] ny rows, >= 2.
    /// @param[in] nx columns, >= 2.
    /// @param[in] maxCells refuse a target grid larger than this (throws std::length_error; the WRF
    ///   mapping turns it into an IngestError).
    CurvilinearResampler(const std::vector<float>& latDeg, const std::vector<float>& lonDeg, size_t ny, size_t nx,
                         size_t maxCells);

    const LatLonGrid& grid() const { return grid_; }

    /// @param[in] source ny * nx values.
    /// @return grid().cellCount() values; NaN outside the source domain. A NaN source corner is left out
    ///   and the other weights renormalised (so a cloud edge does not erase its neighbours).
    std::vector<float> resample(const std::vector<float>& source) const;

    /// Fraction of target cells that lie inside the source domain.
    double coveredFraction() const;

private:
    struct Weights
    {
        std::array<uint32_t, 4> index{};
        std::array<float, 4> weight{};  ///< all 0 when outside
    };
    LatLonGrid grid_;
    std::vector<Weights> weights_;
};

}  // namespace sky
