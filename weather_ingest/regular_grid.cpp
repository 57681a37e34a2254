// SPDX-License-Identifier: MIT
#include "weather_ingest/regular_grid.h"

#include <algorithm>
#include <cmath>

namespace sky
{

double wrapLongitudeDeg(double lonDeg)
{
    double l = std::fmod(lonDeg + 180.0, 360.0);
    if (l < 0)
        l += 360.0;
    return l - 180.0;
}

bool sameGrid(const LatLonGrid& a, const LatLonGrid& b, double toleranceDeg)
{
    return a.nLat == b.nLat && a.nLon == b.nLon && std::abs(a.lat0Deg - b.lat0Deg) <= toleranceDeg &&
           std::abs(wrapLongitudeDeg(a.lon0Deg - b.lon0Deg)) <= toleranceDeg &&
           std::abs(a.dLatDeg - b.dLatDeg) <= toleranceDeg && std::abs(a.dLonDeg - b.dLonDeg) <= toleranceDeg;
}

bool wrapsInLongitude(const LatLonGrid& grid)
{
    return std::abs(double(grid.nLon) * grid.dLonDeg - 360.0) < 1e-6;
}

float sampleBilinear(const GridField& field, double latDeg, double lonDeg)
{
    const LatLonGrid& g = field.grid;
    const double y = (latDeg - g.lat0Deg) / g.dLatDeg;
    double x = (lonDeg - g.lon0Deg) / g.dLonDeg;
    const bool wraps = wrapsInLongitude(g);
    if (wraps)
    {
        x = std::fmod(x, double(g.nLon));
        if (x < 0)
            x += double(g.nLon);
    }
    else
    {
        // Longitudes of a regional grid may be given in another convention than the point's.
        const double span = 360.0 / g.dLonDeg;
        x = std::fmod(x, span);
        if (x < 0)
            x += span;
    }
    const double yMax = double(g.nLat - 1);
    const double xMax = wraps ? double(g.nLon) : double(g.nLon - 1);
    if (!(y >= -1e-9 && y <= yMax + 1e-9 && x >= -1e-9 && x <= xMax + 1e-9))
        return NAN;
    const auto i0 = static_cast<uint32_t>(std::min(std::floor(std::max(y, 0.0)), std::max(yMax - 1, 0.0)));
    const auto j0 = static_cast<uint32_t>(std::min(std::floor(std::max(x, 0.0)), std::max(xMax - 1, 0.0)));
    const uint32_t i1 = std::min(i0 + 1, g.nLat - 1);
    const uint32_t j1 = wraps ? (j0 + 1) % g.nLon : std::min(j0 + 1, g.nLon - 1);
    const double fy = std::clamp(y - double(i0), 0.0, 1.0);
    const double fx = std::clamp(x - double(j0), 0.0, 1.0);
    const auto v = [&](uint32_t i, uint32_t j) { return double(field.values[g.index(i, j)]); };
    const double top = v(i0, j0) * (1 - fx) + v(i0, j1) * fx;
    const double bottom = v(i1, j0) * (1 - fx) + v(i1, j1) * fx;
    return static_cast<float>(top * (1 - fy) + bottom * fy);
}

}  // namespace sky
