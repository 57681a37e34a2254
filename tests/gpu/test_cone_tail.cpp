// SPDX-License-Identifier: MIT
// Lit samples take light from earlier cones (shaders/clouds/cloud_lighting.glsl): far ones the far part
// of the last cone that marched it (RenderTuning::coneTailReuseM, ConeTail), deep ones the whole light
// of the last cone (deepLightReuseM); far cones take their detailed near samples as one
// (coneNearMergeBeyondM). The march takes fewer lookups, the picture stays that of every cone marched in
// full, and lit samples nearer than the limits march their own cones.
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <numeric>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class ConeTail : public GpuFixture
{
protected:
    static RenderTuning tail(double reuseM, double beyondM)
    {
        RenderTuning t;
        t.coneTailReuseM = reuseM;
        t.coneTailReuseBeyondM = beyondM;
        return t;
    }
    /// The default knobs with one distance set.
    static RenderTuning with(double RenderTuning::*knob, double valueM)
    {
        RenderTuning t;
        t.*knob = valueM;
        return t;
    }
    static double totalLookups(const RenderResult& r)
    {
        return std::accumulate(r.marchRowLookups.begin(), r.marchRowLookups.end(), 0.0);
    }
};

}  // namespace

TEST_F(ConeTail, FarLitSamplesTakeTheLastTailAndKeepThePicture)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    const RenderResult marched = renderTuned(v, testQuality(), tail(0.0, 15000.0));
    const RenderResult reused = renderTuned(v, testQuality(), tail(400.0, 15000.0));
    ASSERT_GT(cloudStats(marched).cloudPixels, 5000u);
    const double psnr = psnrCloud(reused, marched);
    const double fewer = 1.0 - totalLookups(reused) / totalLookups(marched);
    std::printf("cone tail reuse 400 m vs every cone marched, Cb from 40 km: PSNR %.2f dB, %.1f %% fewer lookups "
                "(slowest workgroups' counts)\n",
                psnr, 100.0 * fewer);
    EXPECT_NE(reused.cloudRgbaHalf, marched.cloudRgbaHalf);  // tails were taken
    // Bounds below the measured figures (BENCHMARKS.md, "Test figures"): testQuality's 4 cone samples leave
    // 2 plus the long one in the tail, so the saving is a few per cent.
    EXPECT_GT(fewer, 0.05);
    EXPECT_GT(psnr, 40.0);
    // Not brighter or darker overall: a taken tail that were dropped instead would light the cloud.
    const double brightness = cloudStats(reused).meanCloudLuminance / cloudStats(marched).meanCloudLuminance;
    EXPECT_NEAR(brightness, 1.0, 0.01);
}

TEST_F(ConeTail, LitSamplesNearerThanTheLimitMarchTheirOwnCones)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    const RenderResult marched = renderTuned(v, testQuality(), tail(0.0, 15000.0));
    // Nothing lies beyond 1000 km: no tail is taken, and the picture is the same to the bit.
    const RenderResult limited = renderTuned(v, testQuality(), tail(400.0, 1.0e6));
    EXPECT_EQ(limited.cloudRgbaHalf, marched.cloudRgbaHalf);
    EXPECT_EQ(limited.marchRowLookups, marched.marchRowLookups);
}

// Lit samples behind a view transmittance below 0.2 (RenderTuning::detailMinTransmittance) take the
// light of the last cone marched: fewer lookups in a thick deck, and what they add reaches the eye through
// less than a fifth (the figures with other thresholds: BENCHMARKS.md, "Test figures").
TEST_F(ConeTail, DeepLitSamplesTakeTheLastConesLight)
{
    setWeather(*renderer, deckBelowWeather());
    const ViewRequest v = deckFromAboveView();
    const RenderResult marched = renderTuned(v, testQuality(), with(&RenderTuning::deepLightReuseM, 0.0));
    const RenderResult reused = renderTuned(v, testQuality(), with(&RenderTuning::deepLightReuseM, 400.0));
    ASSERT_GT(cloudStats(marched).cloudPixels, v.width * v.height / 2);
    const double psnr = psnrCloud(reused, marched);
    const double fewer = 1.0 - totalLookups(reused) / totalLookups(marched);
    std::printf("deep light reuse 400 m vs every deep cone marched, deck from above: PSNR %.2f dB, %.1f %% fewer "
                "lookups\n",
                psnr, 100.0 * fewer);
    EXPECT_NE(reused.cloudRgbaHalf, marched.cloudRgbaHalf);
    EXPECT_GT(fewer, 0.02);
    EXPECT_GT(psnr, 40.0);
}

// Beyond coneNearMergeBeyondM a cone's two detailed near samples are one sample over their length: the
// Cb's cumulus field lies 40-110 km away at 320x180. Fewer lookups, the picture close to two samples.
TEST_F(ConeTail, FarConesTakeTheirNearSamplesAsOne)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    const RenderResult separate = renderTuned(v, testQuality(), with(&RenderTuning::coneNearMergeBeyondM, 0.0));
    const RenderResult merged = renderTuned(v, testQuality(), with(&RenderTuning::coneNearMergeBeyondM, 40000.0));
    ASSERT_GT(cloudStats(separate).cloudPixels, 5000u);
    const double psnr = psnrCloud(merged, separate);
    const double fewer = 1.0 - totalLookups(merged) / totalLookups(separate);
    std::printf("near cone samples merged beyond 40 km vs two, Cb from 40 km: PSNR %.2f dB, %.1f %% fewer lookups\n",
                psnr, 100.0 * fewer);
    EXPECT_NE(merged.cloudRgbaHalf, separate.cloudRgbaHalf);
    // The slowest workgroups' counts: most rays stop nearer, so the saving is small (BENCHMARKS.md, "Test figures").
    EXPECT_GT(fewer, 0.005);
    EXPECT_GT(psnr, 35.0);
    // The one sample sees less of the thin sunlit skin, so far clouds come out a little brighter. Dropping
    // the near samples instead would brighten them far more.
    const double brightness = cloudStats(merged).meanCloudLuminance / cloudStats(separate).meanCloudLuminance;
    EXPECT_GT(brightness, 1.0);
    EXPECT_LT(brightness, 1.025);
    // With the limit past every cloud nothing is merged: the same bytes as two samples.
    const RenderResult none = renderTuned(v, testQuality(), with(&RenderTuning::coneNearMergeBeyondM, 1.0e6));
    EXPECT_EQ(none.cloudRgbaHalf, separate.cloudRgbaHalf);
    EXPECT_EQ(none.marchRowLookups, separate.marchRowLookups);
}
