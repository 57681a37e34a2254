// SPDX-License-Identifier: MIT
#include "weather_ingest/regular_grid.h"

#include <algorithm>
#include <cmath>

namespace sky
{

bool sameGrid(const LatLonGrid& a, const LatLonGrid& b, double toleranceDeg)
{
    return a.nLat == b.nLat && a.nLon == b.nLon && std::abs(a.lat0Deg - b.lat0Deg) <= toleranceDeg &&
           std::abs(wrapLongitudeDeg(a.lon0Deg - b.lon0Deg)) <= toleranceDeg &&
           std::abs(a.dLatDeg - b.dLatDeg) <= toleranceDeg && std::abs(a.dLonDeg - b.dLonDeg) <= toleranceDeg;
}

}  // namespace sky
