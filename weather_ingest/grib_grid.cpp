// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_grid.h"

#include "weather_ingest/regular_grid.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace sky
{
namespace
{

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// A grid that goes round in longitude and reaches beyond these latitudes is global: it has no edge.
constexpr double kGlobalLatitudeDeg = 60.0;

/// 0 at either end of 0..n-1, rising smoothly (smoothstep) to 1 at kRegionalEdgeFraction of the way in.
float edgeRamp(size_t i, size_t n)
{
    if (n <= 1)
        return 1.0f;
    const double fromEdge = double(std::min(i, n - 1 - i));
    const double t = std::clamp(fromEdge / (kRegionalEdgeFraction * double(n - 1)), 0.0, 1.0);
    return float(t * t * (3.0 - 2.0 * t));
}

double wrap360(double deg)
{
    const double d = std::fmod(deg, 360.0);
    return d < 0 ? d + 360.0 : d;
}

} // namespace

GribGrid::GribGrid(const LatLonGrid& grid, std::string description)
    : gridType_("regular_ll"), description_(std::move(description)), sourcePoints_(grid.cellCount()), target_(grid)
{
    const double latA = grid.lat0Deg, latB = grid.lat0Deg + grid.dLatDeg * double(grid.nLat - 1);
    const bool periodic = grid.wrapsInLongitude();
    if (periodic && std::min(latA, latB) < -kGlobalLatitudeDeg && std::max(latA, latB) > kGlobalLatitudeDeg)
        return;
    dataWeight_.resize(grid.cellCount());
    for (uint32_t r = 0; r < grid.nLat; ++r)
        for (uint32_t c = 0; c < grid.nLon; ++c)
            dataWeight_[grid.index(r, c)] = std::min(edgeRamp(r, grid.nLat), periodic ? 1.0f : edgeRamp(c, grid.nLon));
}

GribGrid::GribGrid(const GribGridPoints& p, size_t maxCells)
    : gridType_(p.gridType), description_(p.description), sourcePoints_(p.latDeg.size())
{
    const size_t n = p.latDeg.size();
    if (p.lonDeg.size() != n || n < 4)
        throw std::invalid_argument("fewer than 4 located points");
    std::vector<float> lat, lon;
    if (!p.pl.empty())
        expandReducedRows(p, lat, lon);
    else
        orderStructuredPoints(p, lat, lon);
    resampler_ = std::make_unique<CurvilinearResampler>(lat, lon, ny_, nx_, maxCells);
    target_ = resampler_->grid();
    makeEdgeWeights(lat, resampler_->periodicColumns());
    if (p.pl.empty() && !resampler_->periodicColumns())
        makeXAxisDirections(p, lat, lon);
}

void GribGrid::expandReducedRows(const GribGridPoints& p, std::vector<float>& lat, std::vector<float>& lon)
{
    const size_t n = p.latDeg.size();
    // Reduced grid: rows of pl[j] points evenly spaced round the globe, expanded to max(pl) columns.
    // Rows of no points (ECMWF's reduced lat/lon grids have them at the poles) are left out.
    if (p.pl.size() != p.nj || p.nj < 2)
        throw std::invalid_argument("reduced grid with " + std::to_string(p.pl.size()) + " row lengths for " +
                                    std::to_string(p.nj) + " rows");
    size_t start = 0;
    for (const long count : p.pl)
    {
        if (count < 0 || start + size_t(count) > n)
            throw std::invalid_argument("reduced grid row lengths do not add up to the " + std::to_string(n) +
                                        " points");
        if (count == 0)
            continue;
        rowStart_.push_back(start);
        rowPoints_.push_back(count);
        start += size_t(count);
    }
    if (start != n)
        throw std::invalid_argument("reduced grid row lengths add up to " + std::to_string(start) + ", not the " +
                                    std::to_string(n) + " points");
    if (rowPoints_.size() < 2)
        throw std::invalid_argument("reduced grid with fewer than 2 rows of points");
    nx_ = size_t(*std::max_element(rowPoints_.begin(), rowPoints_.end()));
    ny_ = rowPoints_.size();
    const double lon0 = p.lonDeg[0];
    for (size_t j = 0; j < ny_; ++j)
    {
        const double spacing = 360.0 / double(rowPoints_[j]);
        const double first = p.lonDeg[rowStart_[j]];
        const double last = p.lonDeg[rowStart_[j] + size_t(rowPoints_[j]) - 1];
        if (std::abs(wrapLongitudeDeg(last - first - spacing * double(rowPoints_[j] - 1))) > 0.25 * spacing)
            throw std::invalid_argument("reduced grid rows do not go all the way round (a sub-area)");
        rowShift_.push_back(wrap360(lon0 - first) / spacing);
    }
    lat.resize(nx_ * ny_);
    lon.resize(nx_ * ny_);
    for (size_t j = 0; j < ny_; ++j)
        for (size_t c = 0; c < nx_; ++c)
        {
            lat[j * nx_ + c] = float(p.latDeg[rowStart_[j]]);
            lon[j * nx_ + c] = float(lon0 + double(c) * 360.0 / double(nx_));
        }
}

void GribGrid::orderStructuredPoints(const GribGridPoints& p, std::vector<float>& lat, std::vector<float>& lon)
{
    const size_t n = p.latDeg.size();
    if (p.ni * p.nj != n)
        throw std::invalid_argument(std::to_string(p.ni) + " x " + std::to_string(p.nj) + " points declared, " +
                                    std::to_string(n) + " located");
    nx_ = p.ni;
    ny_ = p.nj;
    if (p.jPointsAreConsecutive || p.alternativeRowScanning)
    {
        order_.resize(n);
        for (size_t s = 0; s < n; ++s)
        {
            size_t i = p.jPointsAreConsecutive ? s / ny_ : s % nx_;
            size_t j = p.jPointsAreConsecutive ? s % ny_ : s / nx_;
            if (p.alternativeRowScanning && !p.jPointsAreConsecutive && (j & 1u))
                i = nx_ - 1 - i;
            if (p.alternativeRowScanning && p.jPointsAreConsecutive && (i & 1u))
                j = ny_ - 1 - j;
            order_[j * nx_ + i] = uint32_t(s);
        }
    }
    lat.resize(n);
    lon.resize(n);
    for (size_t k = 0; k < n; ++k)
    {
        const size_t s = order_.empty() ? k : order_[k];
        lat[k] = float(p.latDeg[s]);
        lon[k] = float(p.lonDeg[s]);
    }
}

void GribGrid::makeXAxisDirections(const GribGridPoints& p, const std::vector<float>& lat,
                                   const std::vector<float>& lon)
{
    // Direction of the grid's x axis (towards increasing i in the grid's own sense), for winds that
    // GRIB gives relative to the grid (NCEP's Lambert and polar stereographic grids do).
    std::vector<float> cosA(lat.size()), sinA(lat.size());
    for (size_t j = 0; j < ny_; ++j)
        for (size_t i = 0; i < nx_; ++i)
        {
            const size_t a = j * nx_ + (i + 1 < nx_ ? i : i - 1), b = a + 1;
            const double east =
                wrapLongitudeDeg(double(lon[b]) - double(lon[a])) * std::cos(double(lat[a]) * kRadPerDeg);
            const double north = double(lat[b]) - double(lat[a]);
            // cos and sin of atan2(north, east), turned by 180° where i runs westwards.
            const double length = std::hypot(east, north), sign = p.iScansNegatively ? -1.0 : 1.0;
            cosA[j * nx_ + i] = float(length > 0 ? sign * east / length : sign);
            sinA[j * nx_ + i] = float(length > 0 ? sign * north / length : 0.0);
        }
    xAxisCos_ = resampler_->resample(cosA);
    xAxisSin_ = resampler_->resample(sinA);
}

void GribGrid::makeEdgeWeights(const std::vector<float>& structuredLat, bool periodic)
{
    const auto [latLo, latHi] = std::minmax_element(structuredLat.begin(), structuredLat.end());
    if (periodic && double(*latLo) < -kGlobalLatitudeDeg && double(*latHi) > kGlobalLatitudeDeg)
        return;
    std::vector<float> w(nx_ * ny_);
    for (size_t j = 0; j < ny_; ++j)
        for (size_t i = 0; i < nx_; ++i)
            w[j * nx_ + i] = std::min(edgeRamp(j, ny_), periodic ? 1.0f : edgeRamp(i, nx_));
    dataWeight_ = resampler_->resample(w);
    for (float& x : dataWeight_)
        x = std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 0.0f;
}

std::vector<float> GribGrid::structured(const std::vector<double>& values) const
{
    std::vector<float> out(nx_ * ny_);
    if (!rowStart_.empty())
    {
        for (size_t j = 0; j < ny_; ++j)
        {
            const auto count = size_t(rowPoints_[j]);
            const double* row = values.data() + rowStart_[j];
            for (size_t c = 0; c < nx_; ++c)
            {
                const double pos = rowShift_[j] + double(c) * double(count) / double(nx_);
                const double cell = std::floor(pos);
                const double f = pos - cell;
                const size_t k0 = size_t(cell) % count, k1 = (k0 + 1) % count;
                const double near = f < 0.5 ? row[k0] : row[k1];
                const double far = f < 0.5 ? row[k1] : row[k0];
                // A missing point stays missing; a known one is not averaged with a missing neighbour.
                out[j * nx_ + c] = float(!std::isfinite(near)  ? std::nan("")
                                         : !std::isfinite(far) ? near
                                                               : row[k0] * (1.0 - f) + row[k1] * f);
            }
        }
        return out;
    }
    for (size_t k = 0; k < out.size(); ++k)
        out[k] = float(values[order_.empty() ? k : order_[k]]);
    return out;
}

std::vector<float> GribGrid::resample(const std::vector<double>& values) const
{
    if (!resampler_)
        return std::vector<float>(values.begin(), values.end());
    return resampler_->resample(structured(values));
}

void GribGrid::rotateToEarth(std::vector<float>& u, std::vector<float>& v) const
{
    if (xAxisCos_.empty() || u.size() != xAxisCos_.size() || v.size() != u.size())
        return;
    for (size_t k = 0; k < u.size(); ++k)
    {
        const float c = xAxisCos_[k], s = xAxisSin_[k];
        const float len = std::hypot(c, s);
        if (!(len > 1e-6f))
            continue;
        const float ue = (u[k] * c - v[k] * s) / len, vn = (u[k] * s + v[k] * c) / len;
        u[k] = ue;
        v[k] = vn;
    }
}

} // namespace sky
