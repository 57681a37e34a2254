// SPDX-License-Identifier: MIT
#include "weather_ingest/lat_lon_grid.h"

#include <algorithm>

namespace sky
{
namespace
{

/// Column corners and the fraction toward the second one, for a grid that wraps.
struct ColumnPair
{
    uint32_t first = 0, second = 0;
    double fraction = 0;
};

ColumnPair wrappedColumns(const LatLonGrid& g, double fx)
{
    const double cell = std::floor(fx);
    ColumnPair c;
    c.fraction = fx - cell;
    c.first = uint32_t(cell) % g.nLon;
    c.second = (c.first + 1) % g.nLon;
    return c;
}

/// Columns of a regional grid: a point past the east edge, or just west of column 0, reads the nearer edge.
ColumnPair regionalColumns(const LatLonGrid& g, double fx, bool& inside)
{
    const double lastColumn = double(g.nLon) - 1.0;
    if (fx > lastColumn + 0.5)
    {
        const double beyondEast = fx - lastColumn;
        const double beforeWest = 360.0 / g.dLonDeg - fx;
        fx = beyondEast <= beforeWest ? fx : -beforeWest;
        if (fx < -0.5 || fx > lastColumn + 0.5)
            inside = false;
    }
    fx = std::clamp(fx, 0.0, lastColumn);
    const double cell = std::min(std::floor(fx), std::max(lastColumn - 1.0, 0.0));
    ColumnPair c;
    c.fraction = fx - cell;
    c.first = uint32_t(cell);
    c.second = std::min(c.first + 1, g.nLon - 1);
    return c;
}

}  // namespace

double wrapLongitudeDeg(double lonDeg)
{
    double l = std::fmod(lonDeg + 180.0, 360.0);
    if (l < 0)
        l += 360.0;
    return l - 180.0;
}

bool LatLonGrid::wrapsInLongitude() const
{
    return std::abs(double(nLon) * dLonDeg - 360.0) < kGlobalSpanToleranceDeg;
}

GridPoint LatLonGrid::locate(double latDeg, double lonDeg) const
{
    GridPoint p;
    if (cellCount() == 0)
        return p;  // no grid (no weather given): nothing inside, every field absent
    const bool global = wrapsInLongitude();
    p.inside = true;

    double fy = (latDeg - lat0Deg) / dLatDeg;
    const double lastRow = double(nLat) - 1.0;
    if (fy < -0.5 || fy > lastRow + 0.5)
        p.inside = global;  // a global grid is clamped at the poles; a regional one ends
    fy = std::clamp(fy, 0.0, lastRow);
    const double rowCell = std::min(std::floor(fy), std::max(lastRow - 1.0, 0.0));
    const double ty = fy - rowCell;
    const uint32_t iy0 = uint32_t(rowCell);
    const uint32_t iy1 = std::min(iy0 + 1, nLat - 1);

    double dl = std::fmod(lonDeg - lon0Deg, 360.0);
    if (dl < 0.0)
        dl += 360.0;
    const ColumnPair x = global ? wrappedColumns(*this, dl / dLonDeg) : regionalColumns(*this, dl / dLonDeg, p.inside);
    const double tx = x.fraction;

    p.corner = {index(iy0, x.first), index(iy0, x.second), index(iy1, x.first), index(iy1, x.second)};
    p.weight = {(1.0 - ty) * (1.0 - tx), (1.0 - ty) * tx, ty * (1.0 - tx), ty * tx};
    p.nearest = p.corner[(ty >= 0.5 ? 2 : 0) + (tx >= 0.5 ? 1 : 0)];
    return p;
}

float LatLonGrid::sample(std::span<const float> values, const GridPoint& point, float missing) const
{
    if (cellCount() == 0 || values.size() != cellCount())
        return missing;
    double sum = 0;
    double weightSum = 0;
    int heaviest = -1;
    for (int k = 0; k < 4; ++k)
    {
        const float v = values[point.corner[k]];
        if (!std::isfinite(v))
            continue;
        sum += point.weight[k] * double(v);
        weightSum += point.weight[k];
        if (heaviest < 0 || point.weight[k] > point.weight[heaviest])
            heaviest = k;
    }
    if (weightSum > 0.0)
        return float(sum / weightSum);
    if (heaviest >= 0)
        return values[point.corner[heaviest]];  // only zero-weight corners are known
    return missing;
}

float sampleCoverage(const LatLonGrid& grid, std::span<const float> coverage, std::span<const float> base,
                     std::span<const float> top, const GridPoint& point, std::span<const float> cornerWeight)
{
    const size_t cells = grid.cellCount();
    if (!point.inside || cells == 0 || coverage.size() != cells || base.size() != cells || top.size() != cells)
        return 0.0f;
    const bool weighted = cornerWeight.size() == cells;
    double sum = 0;
    for (int k = 0; k < 4; ++k)
    {
        const size_t c = point.corner[k];
        if (!std::isfinite(coverage[c]) || !std::isfinite(base[c]) || !std::isfinite(top[c]))
            continue;
        const double w = weighted ? std::clamp(double(cornerWeight[c]), 0.0, 1.0) : 1.0;
        sum += point.weight[k] * std::clamp(double(coverage[c]), 0.0, 1.0) * w;
    }
    return float(std::clamp(sum, 0.0, 1.0));
}

}  // namespace sky
