// SPDX-License-Identifier: MIT
// WeatherTimeline: interpolation between snapshots and the hold rule outside the range.
#include "weather_ingest/snapshot_file.h"
#include "weather_ingest/weather_timeline.h"

#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sky
{
namespace
{

TEST(WeatherTimeline, InterpolatesLinearlyBetweenSnapshots)
{
    WeatherTimeline tl;
    std::string error;
    // Given out of order on purpose: setSnapshots sorts.
    ASSERT_TRUE(tl.setSnapshots({test::makeSnapshot(3600, 1.0f), test::makeSnapshot(0, 0.0f)}, error)) << error;
    EXPECT_EQ(tl.firstTimeUnixS(), 0);
    const WeatherSnapshot s = tl.sample(900.0);  // a quarter of the way
    EXPECT_EQ(s.validTimeUnixS, 900);
    EXPECT_NEAR(s.layers[1].coverage[3], 0.25f, 1e-6f);
    EXPECT_NEAR(s.layers[1].windEastMS[3], 2.5f, 1e-5f);
    EXPECT_NEAR(s.layers[1].baseAltitudeM[0], 1250.0f, 1e-3f);
    EXPECT_TRUE(std::isnan(s.layers[1].baseAltitudeM[5]));  // NaN on both sides stays NaN
    const WeatherTimeline::Bracket b = tl.bracket(900.0);
    EXPECT_EQ(b.before, 0u);
    EXPECT_EQ(b.after, 1u);
    EXPECT_NEAR(b.weightAfter, 0.25, 1e-12);
    EXPECT_FALSE(b.clamped);
}

TEST(WeatherTimeline, HoldsTheNearestSnapshotOutsideTheRange)
{
    WeatherTimeline tl;
    std::string error;
    ASSERT_TRUE(tl.setSnapshots({test::makeSnapshot(0, 0.2f), test::makeSnapshot(3600, 0.8f)}, error));
    EXPECT_TRUE(tl.bracket(-100.0).clamped);
    EXPECT_TRUE(tl.bracket(1e9).clamped);
    EXPECT_FALSE(tl.bracket(3600.0).clamped);
    EXPECT_FLOAT_EQ(tl.sample(-1e6).layers[1].coverage[0], 0.2f);
    EXPECT_FLOAT_EQ(tl.sample(1e6).layers[1].coverage[0], 0.8f);
    EXPECT_NE(tl.sample(1e6).provenance.at("timeline").find("held"), std::string::npos);
}

TEST(WeatherTimeline, NanOnOneSideUsesTheKnownSideAndTypesComeFromTheNearerSide)
{
    WeatherSnapshot a = test::makeSnapshot(0, 0.5f);
    WeatherSnapshot b = test::makeSnapshot(100, 0.5f);
    a.layers[0].topAltitudeM[1] = NAN;
    b.layers[0].topAltitudeM[1] = 5000.0f;
    a.layers[0].type[2] = uint8_t(CloudType::Stratus);
    b.layers[0].type[2] = uint8_t(CloudType::Cumulus);
    a.layers[0].type[3] = uint8_t(CloudType::None);
    WeatherTimeline tl;
    std::string error;
    ASSERT_TRUE(tl.setSnapshots({a, b}, error));
    EXPECT_FLOAT_EQ(tl.sample(10.0).layers[0].topAltitudeM[1], 5000.0f);
    EXPECT_EQ(tl.sample(10.0).layers[0].type[2], uint8_t(CloudType::Stratus));
    EXPECT_EQ(tl.sample(90.0).layers[0].type[2], uint8_t(CloudType::Cumulus));
    EXPECT_EQ(tl.sample(10.0).layers[0].type[3], uint8_t(CloudType::Stratocumulus));  // None takes the other
}

TEST(WeatherTimeline, LayerOnOneSideFadesIn)
{
    WeatherSnapshot a = test::makeSnapshot(0, 0.6f);
    WeatherSnapshot b = test::makeSnapshot(100, 0.6f);
    a.layers.pop_back();  // "middle" only exists at t = 100
    WeatherTimeline tl;
    std::string error;
    ASSERT_TRUE(tl.setSnapshots({a, b}, error));
    const WeatherSnapshot s = tl.sample(25.0);
    ASSERT_EQ(s.layers.size(), 2u);
    EXPECT_EQ(s.layers[1].name, "middle");
    EXPECT_NEAR(s.layers[1].coverage[0], 0.15f, 1e-6f);
    EXPECT_FLOAT_EQ(s.layers[1].topAltitudeM[0], 3000.0f);
}

TEST(WeatherTimeline, RefusesMixedGridsAndDuplicateTimesAndKeepsOldContent)
{
    WeatherTimeline tl;
    std::string error;
    ASSERT_TRUE(tl.setSnapshots({test::makeSnapshot(0, 0.5f)}, error));
    WeatherSnapshot other = test::makeSnapshot(10, 0.5f);
    other.grid.lat0Deg = 51;
    EXPECT_FALSE(tl.setSnapshots({test::makeSnapshot(0, 0.5f), other}, error));
    EXPECT_FALSE(tl.setSnapshots({test::makeSnapshot(0, 0.5f), test::makeSnapshot(0, 0.1f)}, error));
    EXPECT_FALSE(tl.loadFile("/nonexistent.skywx", error));
    EXPECT_EQ(tl.size(), 1u);
}

TEST(WeatherTimeline, LoadsAFileWithSeveralTimes)
{
    const std::string path = test::tempPath("tl.skywx");
    std::string error;
    ASSERT_TRUE(writeSnapshotFile(path, {test::makeSnapshot(0, 0.0f), test::makeSnapshot(600, 0.6f)}, error));
    WeatherTimeline tl;
    ASSERT_TRUE(tl.loadFile(path, error)) << error;
    EXPECT_NEAR(tl.sample(300.0).layers[1].coverage[0], 0.3f, 1e-6f);
}

}  // namespace
}  // namespace sky
