// SPDX-License-Identifier: MIT
// Test fixtures written with ecCodes from Debian's samples: one cloud disc at a known latitude/longitude on
// a grid of a given kind (the grid-type placement and geo-reference tests). Not used by conversion.
#pragma once

#include <string>

namespace sky
{

/// Grid kinds of writeCloudDiscFixture(). Projected and rotated grids put the disc a third of the way in
/// along both axes (not the middle, so a grid read mirrored moves it); their spacing is divided by
/// CloudDiscFixture::scale and their side multiplied by CloudDiscFixture::extent.
enum class FixtureGrid
{
    Lambert,             ///< 60 x 50 at 20 km, tangent at the disc's latitude
    LambertTwoParallels, ///< the same with standard parallels 7° south and 5° north of it
    PolarNorth,          ///< 60 x 60 at 50 km on the north polar plane (true at 60° N, oriented along 0° E)
    PolarSouth,          ///< the same on the south polar plane
    Mercator,            ///< 60 x 50 at 20 km, true at the disc's latitude
    Rotated,             ///< 81 x 61 at 0.25°, the rotated equator and prime meridian crossing at the disc
    ReducedGaussian,     ///< ecCodes' reduced Gaussian sample of N = 32 x scale (global: N32)
    ReducedLatLon,       ///< ecCodes' global 0.36° reduced lat/lon sample, rows 0.36° / scale apart
};

/// One fixture: low cloud cover (NCEP tcc on lowCloudLayer, %) in a disc, 0 elsewhere.
struct CloudDiscFixture
{
    FixtureGrid kind = FixtureGrid::Lambert;
    double latDeg = 0; ///< the disc's centre
    double lonDeg = 0;
    double radiusKm = 150;
    double coveragePercent = 80;
    /// false: coveragePercent everywhere within radiusKm. true: coveragePercent * (1 - (d / r)^3), a
    /// smooth cell whose interpolated image stays centred on its place on any grid.
    bool tapered = false;
    bool iScansNegatively = false; ///< projected and rotated grids
    bool jScansPositively = true;  ///< projected and rotated grids
    double scale = 1;              ///< spacing divided by this (reduced Gaussian: N = 32 x scale, a sample's N)
    double extent = 1;             ///< projected and rotated grids: side multiplied by this
    /// Reduced grids: keep only the rows within this many degrees of the disc's latitude (rows still go
    /// all the way round); 0 keeps the whole globe.
    double bandHalfWidthDeg = 0;
};

/// Writes the fixture as one GRIB2 message (with dataDate 20240301 12 UTC, centre kwbc). The disc is drawn
/// where ecCodes locates each point, at great-circle distance on a 6371 km sphere. Throws IngestError(Output)
/// naming the key ecCodes refused.
void writeCloudDiscFixture(const std::string& path, const CloudDiscFixture& fixture);

} // namespace sky
