// SPDX-License-Identifier: MIT
#include "skyservice/sky/builtin_weather.h"

#include "skyservice/earth/geodesy.h"

#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/Math.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sky
{

namespace
{

constexpr double kGridLat0Deg = 40.0;
constexpr double kGridLon0Deg = 0.0;
constexpr double kGridStepDeg = 0.025;
constexpr uint32_t kGridRows = 401;     // 40..50 N inclusive
constexpr uint32_t kGridColumns = 481;  // 0..12 E inclusive

// Soft region edges: coverage ramps up over this distance inside the (noise-displaced) edge line.
constexpr double kEdgeRampKm = 25.0;
// How far low-frequency noise moves the edge line in or out.
constexpr double kEdgeDisplacementKm = 25.0;
// Regions are rounded rectangles: no weather system has square corners.
constexpr double kCornerRadiusKm = 80.0;

struct Region
{
    double lonMinDeg, lonMaxDeg, latMinDeg, latMaxDeg;
    uint32_t seed;
};

constexpr Region kDeck = {0.5, 4.5, 43.0, 48.0, 11u};
constexpr Region kCumulus = {6.0, 11.0, 43.0, 47.0, 23u};
constexpr Region kAltocumulus = {1.0, 5.0, 47.0, 49.5, 37u};
constexpr Region kCirrus = {3.0, 10.0, 44.0, 49.0, 41u};

// Integer hash to [0, 1) (a xorshift-multiply mix in the style of Thomas Mueller's hash32).
double latticeValue(int32_t x, int32_t y, uint32_t seed)
{
    uint32_t h = uint32_t(x) * 0x27d4eb2du ^ uint32_t(y) * 0x165667b1u ^ seed * 0x9e3779b9u;
    h = ((h >> 16) ^ h) * 0x45d9f3bu;
    h = ((h >> 16) ^ h) * 0x45d9f3bu;
    h = (h >> 16) ^ h;
    return double(h & 0xffffffu) / double(0x1000000u);
}

double quintic(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Value noise in [0, 1) with a lattice spacing of periodKm.
double valueNoise(double xKm, double yKm, double periodKm, uint32_t seed)
{
    const double fx = xKm / periodKm;
    const double fy = yKm / periodKm;
    const double cx = std::floor(fx);
    const double cy = std::floor(fy);
    const double tx = quintic(fx - cx);
    const double ty = quintic(fy - cy);
    const int32_t ix = int32_t(cx);
    const int32_t iy = int32_t(cy);
    const double v00 = latticeValue(ix, iy, seed);
    const double v10 = latticeValue(ix + 1, iy, seed);
    const double v01 = latticeValue(ix, iy + 1, seed);
    const double v11 = latticeValue(ix + 1, iy + 1, seed);
    const double bottom = v00 + (v10 - v00) * tx;
    const double topRow = v01 + (v11 - v01) * tx;
    return bottom + (topRow - bottom) * ty;
}

// Three octaves, mapped to [-1, 1].
double signedNoise(double xKm, double yKm, uint32_t seed)
{
    const double n = 0.55 * valueNoise(xKm, yKm, 150.0, seed) + 0.3 * valueNoise(xKm, yKm, 60.0, seed + 101u) +
                     0.15 * valueNoise(xKm, yKm, 25.0, seed + 202u);
    return 2.0 * n - 1.0;
}

double smoothstep(double edge0, double edge1, double x)
{
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// A cell's position for the noise and the region edges, in kilometres on a local plane.
struct CellKm
{
    double latDeg, lonDeg;
    double kmPerDegLat, kmPerDegLon;
    double xKm, yKm;
};

// 0 outside the region, 1 well inside it, with a noisy soft edge.
double regionMask(const Region& region, const CellKm& cell)
{
    // Signed distance to a rounded rectangle (positive inside), on the cell's local plane.
    const double halfXKm = 0.5 * (region.lonMaxDeg - region.lonMinDeg) * cell.kmPerDegLon;
    const double halfYKm = 0.5 * (region.latMaxDeg - region.latMinDeg) * cell.kmPerDegLat;
    const double qx = std::abs((cell.lonDeg - 0.5 * (region.lonMinDeg + region.lonMaxDeg)) * cell.kmPerDegLon) -
                      (halfXKm - kCornerRadiusKm);
    const double qy = std::abs((cell.latDeg - 0.5 * (region.latMinDeg + region.latMaxDeg)) * cell.kmPerDegLat) -
                      (halfYKm - kCornerRadiusKm);
    const double outsideKm = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) -
                             kCornerRadiusKm;
    const double insideKm = -outsideKm;
    if (insideKm < -kEdgeDisplacementKm)
        return 0.0;
    const double displacedKm = insideKm + kEdgeDisplacementKm * signedNoise(cell.xKm, cell.yKm, region.seed);
    return smoothstep(0.0, kEdgeRampKm, displacedKm);
}

// Coverage inside a region: mean +- amplitude, varying smoothly.
double regionCoverage(const Region& region, const CellKm& cell, double mean, double amplitude)
{
    const double mask = regionMask(region, cell);
    if (mask <= 0.0)
        return 0.0;
    return mask * (mean + amplitude * signedNoise(cell.xKm, cell.yKm, region.seed + 7u));
}

// Wind towards east and north from a speed and the meteorological direction it blows from.
void windFrom(double fromDeg, double speedMS, float& eastMS, float& northMS)
{
    double s = 0;
    double c = 0;
    GeographicLib::Math::sincosd(fromDeg, s, c);
    eastMS = float(-speedMS * s);
    northMS = float(-speedMS * c);
}

CloudLayerFields makeLayer(const char* name, size_t cells)
{
    CloudLayerFields layer;
    layer.name = name;
    layer.coverage.assign(cells, 0.0f);
    layer.baseAltitudeM.assign(cells, 0.0f);
    layer.topAltitudeM.assign(cells, 0.0f);
    layer.type.assign(cells, uint8_t(CloudType::None));
    layer.precipitationMmH.assign(cells, 0.0f);
    layer.windEastMS.assign(cells, 0.0f);
    layer.windNorthMS.assign(cells, 0.0f);
    return layer;
}

// A snapshot on the built-in grid with every field allocated and at its background value (no cloud,
// the background CAPE, the fixed tropopause).
WeatherSnapshot emptyBuiltinSnapshot(int64_t validTimeUnixS)
{
    WeatherSnapshot snapshot;
    snapshot.grid.lat0Deg = kGridLat0Deg;
    snapshot.grid.lon0Deg = kGridLon0Deg;
    snapshot.grid.dLatDeg = kGridStepDeg;
    snapshot.grid.dLonDeg = kGridStepDeg;
    snapshot.grid.nLat = kGridRows;
    snapshot.grid.nLon = kGridColumns;
    snapshot.validTimeUnixS = validTimeUnixS;
    snapshot.provenance["source"] = "builtin";

    const size_t cells = snapshot.grid.cellCount();
    snapshot.layers.push_back(makeLayer("low", cells));
    snapshot.layers.push_back(makeLayer("middle", cells));
    snapshot.layers.push_back(makeLayer("convective", cells));
    HighCloudFields& high = snapshot.high;
    high.coverage.assign(cells, 0.0f);
    high.altitudeM.assign(cells, kBuiltinCirrusAltitudeM);
    high.type.assign(cells, uint8_t(CloudType::Cirrus));
    high.windEastMS.assign(cells, 0.0f);
    high.windNorthMS.assign(cells, 0.0f);
    snapshot.capeJKg.assign(cells, kBuiltinBackgroundCapeJKg);
    snapshot.tropopauseAltitudeM.assign(cells, kBuiltinTropopauseM);
    return snapshot;
}

struct Wind
{
    float eastMS = 0, northMS = 0;
};

// One wind per layer, the same in every cell.
struct BuiltinWinds
{
    Wind low, middle, convective, high;
};

BuiltinWinds builtinWinds()
{
    BuiltinWinds w;
    windFrom(225.0, 6.0, w.low.eastMS, w.low.northMS);                // south-west
    windFrom(247.5, 15.0, w.middle.eastMS, w.middle.northMS);         // west-south-west
    windFrom(270.0, 25.0, w.convective.eastMS, w.convective.northMS); // west
    windFrom(247.5, 30.0, w.high.eastMS, w.high.northMS);             // west-south-west
    return w;
}

// The low layer: the stratocumulus deck west of the split, the cumulus field east of it.
void fillLowCell(CloudLayerFields& low, size_t c, const CellKm& cell, const Wind& wind)
{
    // Lon 5.25 E lies midway between the deck and the cumulus field, where both are clear.
    constexpr double kDeckCumulusSplitLonDeg = 5.25;
    if (cell.lonDeg < kDeckCumulusSplitLonDeg)
    {
        low.coverage[c] = float(regionCoverage(kDeck, cell, 0.90, 0.04));
        low.baseAltitudeM[c] = kBuiltinDeckBaseM;
        low.topAltitudeM[c] = kBuiltinDeckTopM;
        low.type[c] = uint8_t(CloudType::Stratocumulus);
    }
    else
    {
        low.coverage[c] = float(regionCoverage(kCumulus, cell, 0.40, 0.04));
        low.baseAltitudeM[c] = kBuiltinCumulusBaseM;
        low.topAltitudeM[c] = kBuiltinCumulusTopM;
        low.type[c] = uint8_t(CloudType::Cumulus);
    }
    low.windEastMS[c] = wind.eastMS;
    low.windNorthMS[c] = wind.northMS;
}

void fillMiddleCell(CloudLayerFields& middle, size_t c, const CellKm& cell, const Wind& wind)
{
    middle.coverage[c] = float(regionCoverage(kAltocumulus, cell, 0.50, 0.05));
    middle.baseAltitudeM[c] = kBuiltinAltocumulusBaseM;
    middle.topAltitudeM[c] = kBuiltinAltocumulusTopM;
    middle.type[c] = uint8_t(CloudType::Altocumulus);
    middle.windEastMS[c] = wind.eastMS;
    middle.windNorthMS[c] = wind.northMS;
}

// The cumulonimbus around cellCentre, and the CAPE that peaks under it.
void fillConvectiveCell(CloudLayerFields& convective, float& capeJKg, size_t c, const CellKm& cell,
                        const GeographicLib::LocalCartesian& cellCentre, const Wind& wind)
{
    // CAPE falls from the cell's value to the background over this distance from its centre.
    constexpr double kCapeInnerM = 5000.0;
    constexpr double kCapeOuterM = 60000.0;
    double distanceM = std::numeric_limits<double>::infinity();
    if (std::abs(cell.latDeg - kBuiltinCumulonimbusLatDeg) < 1.0 &&
        std::abs(cell.lonDeg - kBuiltinCumulonimbusLonDeg) < 1.5)
    {
        double x = 0, y = 0, z = 0;
        cellCentre.Forward(cell.latDeg, cell.lonDeg, 0.0, x, y, z);
        distanceM = std::hypot(x, y);
    }
    const double cbCoverage =
        1.0 - smoothstep(kBuiltinCumulonimbusCoreRadiusM, kBuiltinCumulonimbusRadiusM, distanceM);
    convective.coverage[c] = float(cbCoverage);
    convective.baseAltitudeM[c] = kBuiltinCumulonimbusBaseM;
    convective.topAltitudeM[c] = kBuiltinCumulonimbusTopM;
    convective.type[c] = uint8_t(CloudType::Cumulonimbus);
    convective.precipitationMmH[c] = float(cbCoverage) * kBuiltinCumulonimbusPrecipitationMmH;
    convective.windEastMS[c] = wind.eastMS;
    convective.windNorthMS[c] = wind.northMS;
    const double capeWeight = 1.0 - smoothstep(kCapeInnerM, kCapeOuterM, distanceM);
    capeJKg = float(double(kBuiltinBackgroundCapeJKg) +
                    capeWeight * double(kBuiltinCumulonimbusCapeJKg - kBuiltinBackgroundCapeJKg));
}

void fillHighCell(HighCloudFields& high, size_t c, const CellKm& cell, const Wind& wind)
{
    high.coverage[c] = float(regionCoverage(kCirrus, cell, 0.50, 0.08));
    high.windEastMS[c] = wind.eastMS;
    high.windNorthMS[c] = wind.northMS;
}

}  // namespace

WeatherSnapshot makeBuiltinWeather(int64_t validTimeUnixS)
{
    WeatherSnapshot snapshot = emptyBuiltinSnapshot(validTimeUnixS);
    CloudLayerFields& low = snapshot.layers[0];
    CloudLayerFields& middle = snapshot.layers[1];
    CloudLayerFields& convective = snapshot.layers[2];
    const BuiltinWinds winds = builtinWinds();
    const GeographicLib::LocalCartesian cellCentre(kBuiltinCumulonimbusLatDeg, kBuiltinCumulonimbusLonDeg, 0.0);

    for (uint32_t iLat = 0; iLat < kGridRows; ++iLat)
    {
        CellKm cell{};
        cell.latDeg = kGridLat0Deg + double(iLat) * kGridStepDeg;
        cell.kmPerDegLat = metersPerDegreeLatitude(cell.latDeg) / 1000.0;
        cell.kmPerDegLon = metersPerDegreeLongitude(cell.latDeg) / 1000.0;
        cell.yKm = (cell.latDeg - kGridLat0Deg) * cell.kmPerDegLat;
        for (uint32_t iLon = 0; iLon < kGridColumns; ++iLon)
        {
            cell.lonDeg = kGridLon0Deg + double(iLon) * kGridStepDeg;
            cell.xKm = (cell.lonDeg - kGridLon0Deg) * cell.kmPerDegLon;
            const size_t c = snapshot.grid.index(iLat, iLon);
            fillLowCell(low, c, cell, winds.low);
            fillMiddleCell(middle, c, cell, winds.middle);
            fillConvectiveCell(convective, snapshot.capeJKg[c], c, cell, cellCentre, winds.convective);
            fillHighCell(snapshot.high, c, cell, winds.high);
        }
    }
    return snapshot;
}

}  // namespace sky
