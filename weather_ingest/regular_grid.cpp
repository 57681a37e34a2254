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

int64_t unixTimeFromCivil(int year, int month, int day, int hour, int minute, int second)
{
    // Days from 1970-01-01 in the proleptic Gregorian calendar: count years from March so that the
    // leap day is the last day of the year (the usual era/day-of-era decomposition, 400-year cycles).
    const int y = year - (month <= 2 ? 1 : 0);
    const int era = (y >= 0 ? y : y - 399) / 400;
    const int yoe = y - era * 400;
    const int mp = (month + 9) % 12;  // March = 0
    const int doy = (153 * mp + 2) / 5 + day - 1;
    const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    const int64_t days = int64_t(era) * 146097 + doe - 719468;  // 719468 = days from 0000-03-01 to 1970-01-01
    return days * 86400 + int64_t(hour) * 3600 + int64_t(minute) * 60 + second;
}

}  // namespace sky
