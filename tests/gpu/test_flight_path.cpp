// SPDX-License-Identifier: MIT
// Scripted flight-path gates of temporal reprojection (docs/tests.md "Temporal reprojection"), on lavapipe with
// validation on, 128x72, test quality, 60 Hz frame steps over a stratocumulus deck (coverage 0.7,
// 1500-2100 m): cruise at 280 m/s, a 60 deg/s turn and a 90 deg/s turn at 250 m/s, a climb through
// the deck (march block 4 -> 2 -> 1 -> 2 -> 4, reprojection.h); and a 60 deg/s turn inside an overcast
// deck (coverage 0.9, block 2).
//
// Every measured frame is compared with a full-resolution render of the same pose (flight_path.h).
// Gates are on the display image (the frame the user sees: tone-mapped sRGB, peak 255); the cloud
// image (linear premultiplied radiance and alpha, peak = the reference's largest value) is printed
// and gated lower, because at this size two full renders a fraction of a pixel apart already differ
// there (test_world_jitter.cpp): sub-pixel cloud detail that no resampling can reproduce.
// "No smearing at the screen edges": the 8-pixel column band on the side the view turns toward (both
// sides when flying straight), where history is missing or oldest, is gated on its own (cloud-image
// PSNR >= 16 dB) and, in turns, against the whole frame (at most 5 dB below it).
#include "tests/gpu/flight_path.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class FlightPath : public GpuFixture
{
protected:
    void SetUp() override
    {
        setWeather(*renderer, uniformLayer(0.7f, CloudType::Stratocumulus, 1500.0f, 2100.0f));
        dropHistory(*renderer);
    }
};

// 600 m above the deck top, looking east and 8 degrees down at it.
ViewRequest aboveDeck()
{
    ViewRequest v = lookUp(45.0, 7.0, 2700.0, -8.0, "2026-06-21T10:00:00Z");
    v.pose.headingDeg = 90.0;
    v.width = 128;
    v.height = 72;
    return v;
}

// Gates of every flight segment: the display frame >= 30 dB (the quality gate); the cloud image >= 18 dB,
// about what the full render scores against itself one frame earlier in a turn; the edge bands >= 16 dB
// (cloud image). In a turn the band the view turns toward has no history or the oldest: there it must
// also be at most 5 dB below the whole frame: a smear, history stretched in from the border, shows there
// first. The bounds sit under the measured figures (the measured figures: BENCHMARKS.md, "Test figures").
//
// Sharpness (sharpness.h: neighbour differences of the display luma, against the full render's): the
// display keeps its detail while the view moves. Bilinear history reads blurred it a little more in every
// frame a pixel lived on in the history, which the 0.8 bound refuses; Catmull-Rom reads
// (reconstruct.comp.glsl cubicHistory) pass it (the measured figures: BENCHMARKS.md, "Test figures").
// Inside the overcast deck the full render is nearly flat and the ratio meaningless (it is large), but
// never low.
void expectGates(const FlightStats& s, bool turning = false)
{
    EXPECT_GE(s.lowestSharpness, 0.8);
    EXPECT_EQ(s.historyDrops, 0);
    EXPECT_GE(s.worstDisplayDb, 30.0);
    EXPECT_GE(s.worstCloudDb, 18.0);
    EXPECT_GE(s.worstEdgeCloudDb, 16.0);
    if (turning)
    {
        EXPECT_LE(s.worstEdgeDeficitDb, 5.0);
    }
}

}  // namespace

TEST_F(FlightPath, CruiseAt280MetresPerSecond)
{
    ViewRequest v = aboveDeck();
    expectGates(flySegment(*renderer, v, {280.0, 0.0, 0.0}, 16, 12, "cruise", "/tmp/sky-reprojection-cruise.png"));
}

TEST_F(FlightPath, TurnAt60DegreesPerSecond)
{
    ViewRequest v = aboveDeck();
    expectGates(flySegment(*renderer, v, {250.0, 60.0, 0.0}, 16, 12, "turn 60", "/tmp/sky-reprojection-turn60.png"),
                true);
}

// 1.5 degrees per frame is far inside the 30-degree history limit: history must be kept, not dropped.
TEST_F(FlightPath, TurnAt90DegreesPerSecondKeepsHistory)
{
    ViewRequest v = aboveDeck();
    expectGates(flySegment(*renderer, v, {250.0, 90.0, 0.0}, 16, 12, "turn 90", "/tmp/sky-reprojection-turn90.png"),
                true);
}

// Pushing the nose down at 60 deg/s over the deck (a degree per frame, ~1.2 rows at 128x72): the rows
// that come in at the bottom are marched in full (reprojection.h NewLines), so the bottom band keeps the
// detail of the full render instead of the fill interpolated from one pixel in 16; with the rows left to
// the fill the band scores clearly lower (the measured figures: BENCHMARKS.md, "Test figures"). (The band's sharpness is too noisy at 8 rows of 128
// pixels to gate.)
TEST_F(FlightPath, PitchDownAt60DegreesPerSecond)
{
    ViewRequest v = aboveDeck();
    const FlightStats s =
        flySegment(*renderer, v, {250.0, 0.0, 0.0, -60.0}, 16, 12, "pitch -60", "/tmp/sky-reprojection-pitch60.png");
    expectGates(s, true);
    EXPECT_GE(s.worstEdgeCloudDb, 31.0);
    EXPECT_LE(s.worstEdgeMeanAbs, 0.0100);
}


// Climb through the deck (1500-2100 m) at 125 m/s (250 m/s on a 30-degree climb, 2.1 m per frame),
// nose 10 degrees up. Flying all of it at 60 Hz would be ~700 frames, too slow on lavapipe, so each test
// flies the frames around two of the four changes of march block, each from an empty history:
// entering the near zone below the base (4 -> 2) and the cloud (2 -> 1); leaving the cloud (1 -> 2)
// and the near zone above the top (2 -> 4). Inside the layer every pixel is marched, so those frames
// must equal the full render exactly.
namespace
{

constexpr double kClimbMS = 125.0;

ViewRequest climbingAt(double altitudeM)
{
    ViewRequest v = aboveDeck();
    v.pose.altitudeM = altitudeM;
    v.pose.pitchDeg = 10.0;
    return v;
}

}  // namespace

TEST_F(FlightPath, ClimbIntoTheDeckMarchesMorePixels)
{
    ViewRequest v = climbingAt(1175.0);  // 325 m below the base: block 4, near zone after ~12 frames
    FlightStats below = flySegment(*renderer, v, {0.0, 0.0, kClimbMS}, 16, 6, "climb below base");
    expectGates(below);
    EXPECT_EQ(below.maxBlockPx, 2u);
    EXPECT_NE(below.lastBlockReason.find("near"), std::string::npos) << below.lastBlockReason;

    dropHistory(*renderer);
    v = climbingAt(1470.0);  // crosses the base (1500 m) in the 7th measured frame
    FlightStats base = flySegment(*renderer, v, {0.0, 0.0, kClimbMS}, 8, 8, "climb through base",
                                  "/tmp/sky-reprojection-climb-base.png");
    expectGates(base);
    EXPECT_EQ(base.maxBlockPx, 2u);
    EXPECT_EQ(base.lastBlockPx, 1u);
    EXPECT_NE(base.lastBlockReason.find("inside"), std::string::npos) << base.lastBlockReason;
    EXPECT_EQ(base.fullBlockFramesNotExact, 0);
}

TEST_F(FlightPath, ClimbOutOfTheDeckReturnsToOneSixteenth)
{
    ViewRequest v = climbingAt(2082.0);  // crosses the top (2100 m) in the 5th measured frame
    FlightStats top = flySegment(*renderer, v, {0.0, 0.0, kClimbMS}, 4, 8, "climb through top");
    expectGates(top);
    EXPECT_EQ(top.minBlockPx, 1u);
    EXPECT_EQ(top.lastBlockPx, 2u);
    EXPECT_EQ(top.fullBlockFramesNotExact, 0);

    dropHistory(*renderer);
    v = climbingAt(2375.0);  // leaves the near zone (2400 m) in the 4th measured frame
    FlightStats above = flySegment(*renderer, v, {0.0, 0.0, kClimbMS}, 8, 8, "climb above top",
                                   "/tmp/sky-reprojection-climb-above.png");
    expectGates(above);
    EXPECT_EQ(above.minBlockPx, 2u);
    EXPECT_EQ(above.lastBlockPx, 4u);
    EXPECT_TRUE(above.lastBlockReason.empty()) << above.lastBlockReason;
}

// Inside an overcast deck (coverage 0.9: fog all around, reprojection.h kOvercastCoverage), turning at
// 60 deg/s at 250 m/s with a quarter of the pixels marched per frame (RenderTuning::insideCloudBlockPx
// 2): the gates of the flights above the deck hold, and by far (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(FlightPath, TurnInsideAnOvercastDeckAt60DegreesPerSecond)
{
    setWeather(*renderer, uniformLayer(0.9f, CloudType::Stratocumulus, 1500.0f, 2100.0f));
    dropHistory(*renderer);
    ViewRequest v = aboveDeck();
    v.pose.altitudeM = 1800.0;
    v.pose.pitchDeg = 0.0;
    FlightStats inside = flySegment(*renderer, v, {250.0, 60.0, 0.0}, 16, 12, "turn 60 inside the overcast deck",
                                    "/tmp/sky-reprojection-inside-turn60.png");
    expectGates(inside, true);
    EXPECT_EQ(inside.minBlockPx, 2u);
    EXPECT_EQ(inside.maxBlockPx, 2u);
    EXPECT_NE(inside.lastBlockReason.find("inside overcast"), std::string::npos) << inside.lastBlockReason;
}
