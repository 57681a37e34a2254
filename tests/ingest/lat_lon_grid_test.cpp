// SPDX-License-Identifier: MIT
// LatLonGrid::locate / sample (weather_ingest/lat_lon_grid.h), the one sampler of the ingest, the
// service's regrid and the renderer's window: global wrap across the antimeridian, the poles, the edges
// of a regional grid, missing neighbours and a cell where nothing is known.
#include "weather_ingest/lat_lon_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace sky;

namespace
{

// 10-degree global grid from 85 S to 85 N, columns from 0 E: value = column (so wrapping is visible).
LatLonGrid globalGrid()
{
    return LatLonGrid{.lat0Deg = -85, .lon0Deg = 0, .dLatDeg = 10, .dLonDeg = 10, .nLat = 18, .nLon = 36};
}

std::vector<float> columnValues(const LatLonGrid& g)
{
    std::vector<float> v(g.cellCount());
    for (uint32_t r = 0; r < g.nLat; ++r)
        for (uint32_t c = 0; c < g.nLon; ++c)
            v[g.index(r, c)] = float(c);
    return v;
}

// 1-degree regional grid 40..44 N, 5..9 E, north to south: value = 10 * row + column.
LatLonGrid regionalGrid()
{
    return LatLonGrid{.lat0Deg = 44, .lon0Deg = 5, .dLatDeg = -1, .dLonDeg = 1, .nLat = 5, .nLon = 5};
}

std::vector<float> rowColumnValues(const LatLonGrid& g)
{
    std::vector<float> v(g.cellCount());
    for (uint32_t r = 0; r < g.nLat; ++r)
        for (uint32_t c = 0; c < g.nLon; ++c)
            v[g.index(r, c)] = float(10 * r + c);
    return v;
}

}  // namespace

TEST(LatLonGrid, GlobalWithinToleranceWraps)
{
    EXPECT_TRUE(globalGrid().wrapsInLongitude());
    LatLonGrid tenths{.lat0Deg = 0, .lon0Deg = 0, .dLatDeg = 0.1, .dLonDeg = 0.1000000001, .nLat = 2, .nLon = 3600};
    EXPECT_TRUE(tenths.wrapsInLongitude()) << "0.1 degrees written as a decimal string";
    EXPECT_FALSE(regionalGrid().wrapsInLongitude());
    LatLonGrid withDuplicate = globalGrid();
    withDuplicate.nLon = 37;  // 0..360 inclusive: not a wrap, a regional grid that covers all longitudes
    EXPECT_FALSE(withDuplicate.wrapsInLongitude());
}

TEST(LatLonGrid, WrapsAcrossTheAntimeridianInAnyConvention)
{
    const LatLonGrid g = globalGrid();
    const std::vector<float> v = columnValues(g);
    // 355 E is halfway between the last column (350 E, value 35) and the first (0 E, value 0).
    EXPECT_FLOAT_EQ(g.sample(v, 0.0, 355.0), 17.5f);
    EXPECT_FLOAT_EQ(g.sample(v, 0.0, -5.0), 17.5f);
    EXPECT_FLOAT_EQ(g.sample(v, 0.0, 715.0), 17.5f);
    EXPECT_FLOAT_EQ(g.sample(v, 0.0, -180.0), 18.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 0.0, 180.0), 18.0f);
    const GridPoint p = g.locate(0.0, 358.0);
    EXPECT_TRUE(p.inside);
    EXPECT_EQ(p.corner[0] % g.nLon, 35u);
    EXPECT_EQ(p.corner[1] % g.nLon, 0u);
    EXPECT_EQ(p.nearest % g.nLon, 0u) << "358 E is nearer 0 E than 350 E";
}

TEST(LatLonGrid, GlobalGridIsClampedAtThePoles)
{
    const LatLonGrid g = globalGrid();
    std::vector<float> v(g.cellCount());
    for (uint32_t r = 0; r < g.nLat; ++r)
        for (uint32_t c = 0; c < g.nLon; ++c)
            v[g.index(r, c)] = float(r);
    const GridPoint north = g.locate(90.0, 123.0), south = g.locate(-90.0, -77.0);
    EXPECT_TRUE(north.inside);
    EXPECT_TRUE(south.inside);
    EXPECT_FLOAT_EQ(g.sample(v, north), 17.0f);
    EXPECT_FLOAT_EQ(g.sample(v, south), 0.0f);
}

TEST(LatLonGrid, RegionalGridIsInsideToHalfACellAndReadsItsEdgeBeyond)
{
    const LatLonGrid g = regionalGrid();
    const std::vector<float> v = rowColumnValues(g);
    EXPECT_FLOAT_EQ(g.sample(v, 43.5, 6.5), 6.5f);  // rows 0..1 (44, 43 N), columns 1..2
    EXPECT_TRUE(g.locate(44.4, 7.0).inside);
    EXPECT_FALSE(g.locate(44.6, 7.0).inside);
    EXPECT_TRUE(g.locate(42.0, 4.6).inside);
    EXPECT_FALSE(g.locate(42.0, 4.4).inside);
    EXPECT_FALSE(g.locate(38.0, 7.0).inside);
    // Outside: the nearest edge's value (north edge row 0, south edge row 4; west column 0, east 4).
    EXPECT_FLOAT_EQ(g.sample(v, 50.0, 7.0), 2.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 30.0, 7.0), 42.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 42.0, 3.0), 20.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 42.0, 12.0), 24.0f);
    // Longitudes in another convention: 365 E is 5 E; 180 E is nearer the east edge (9 E) than the west.
    EXPECT_FLOAT_EQ(g.sample(v, 42.0, 365.0), 20.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 42.0, -175.0), 24.0f);
    EXPECT_FLOAT_EQ(g.sample(v, 42.0, 190.0), 20.0f) << "190 E = 170 W is nearer the west edge";
}

TEST(LatLonGrid, MissingNeighboursAreLeftOutAndTheOthersReweighted)
{
    const LatLonGrid g = regionalGrid();
    std::vector<float> v = rowColumnValues(g);
    v[g.index(1, 1)] = NAN;  // 43 N 6 E
    v[g.index(1, 2)] = INFINITY;
    // At 43.5 N 6.5 E the corners are (0,1)=1, (0,2)=2, (1,1)=missing, (1,2)=missing: the mean of the known.
    EXPECT_FLOAT_EQ(g.sample(v, 43.5, 6.5), 1.5f);
    // On the missing node itself every corner with weight is missing: a known zero-weight neighbour.
    const float onNode = g.sample(v, 43.0, 6.0);
    EXPECT_TRUE(std::isfinite(onNode));
    EXPECT_FLOAT_EQ(onNode, 21.0f) << "(1,2) is missing too: the first known corner is (2,1)";
}

TEST(LatLonGrid, NothingKnownGivesTheCallersValue)
{
    const LatLonGrid g = regionalGrid();
    const std::vector<float> missing(g.cellCount(), NAN);
    EXPECT_TRUE(std::isnan(g.sample(missing, 42.0, 7.0)));
    EXPECT_FLOAT_EQ(g.sample(missing, 42.0, 7.0, 11000.0f), 11000.0f);
    EXPECT_FLOAT_EQ(g.sample(std::vector<float>{}, 42.0, 7.0, 1.0f), 1.0f) << "an absent field";
    EXPECT_FLOAT_EQ(g.sample(std::vector<float>(3, 5.0f), 42.0, 7.0, 0.0f), 0.0f) << "a field of the wrong size";
    EXPECT_FALSE(LatLonGrid{}.locate(0.0, 0.0).inside) << "no grid at all";
}

TEST(LatLonGrid, CoverageCountsAMissingBaseOrTopAsClear)
{
    const LatLonGrid g = regionalGrid();
    std::vector<float> coverage(g.cellCount(), 0.8f), base(g.cellCount(), 1000.0f), top(g.cellCount(), 2000.0f);
    base[g.index(0, 1)] = NAN;
    const GridPoint p = g.locate(43.5, 6.5);  // corners (0,1), (0,2), (1,1), (1,2), a quarter each
    EXPECT_FLOAT_EQ(sampleCoverage(g, coverage, base, top, p), 0.6f);
    std::vector<float> weight(g.cellCount(), 0.5f);
    EXPECT_FLOAT_EQ(sampleCoverage(g, coverage, base, top, p, weight), 0.3f);
    EXPECT_FLOAT_EQ(sampleCoverage(g, coverage, base, top, g.locate(30.0, 7.0)), 0.0f) << "outside";
    EXPECT_FLOAT_EQ(sampleCoverage(g, coverage, base, std::vector<float>{}, p), 0.0f) << "no top";
}
