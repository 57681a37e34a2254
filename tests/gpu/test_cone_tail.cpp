// SPDX-License-Identifier: MIT
// Lit samples take light from earlier cones (shaders/clouds/cloud_lighting.glsl): far ones the far part
// of the last cone that marched it (QualitySettings::coneTailReuseM, ConeTail), deep ones the whole light
// of the last cone (deepLightReuseM). The march takes fewer lookups, the picture stays that of every cone
// marched in full, and lit samples nearer than coneTailReuseBeyondM march their own cones.
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
    static QualitySettings quality(double reuseM, double beyondM)
    {
        QualitySettings q = testQuality();
        q.coneTailReuseM = reuseM;
        q.coneTailReuseBeyondM = beyondM;
        return q;
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
    const RenderResult marched = renderOk(v, quality(0.0, 15000.0));
    const RenderResult reused = renderOk(v, quality(400.0, 15000.0));
    ASSERT_GT(cloudStats(marched).cloudPixels, 5000u);
    const double psnr = psnrCloud(reused, marched);
    const double fewer = 1.0 - totalLookups(reused) / totalLookups(marched);
    std::printf("cone tail reuse 400 m vs every cone marched, Cb from 40 km: PSNR %.2f dB, %.1f %% fewer lookups "
                "(slowest workgroups' counts)\n",
                psnr, 100.0 * fewer);
    EXPECT_NE(reused.cloudRgbaHalf, marched.cloudRgbaHalf);  // tails were taken
    EXPECT_GT(fewer, 0.05);  // 7.5 % measured (testQuality: 4 cone samples, 2 + the long one in the tail)
    EXPECT_GT(psnr, 40.0);  // 47.7 dB measured
    // Not brighter or darker overall: a taken tail that were dropped instead would light the cloud.
    const double brightness = cloudStats(reused).meanCloudLuminance / cloudStats(marched).meanCloudLuminance;
    EXPECT_NEAR(brightness, 1.0, 0.01);
}

TEST_F(ConeTail, LitSamplesNearerThanTheLimitMarchTheirOwnCones)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    const RenderResult marched = renderOk(v, quality(0.0, 15000.0));
    // Nothing lies beyond 1000 km: no tail is taken, and the picture is the same to the bit.
    const RenderResult limited = renderOk(v, quality(400.0, 1.0e6));
    EXPECT_EQ(limited.cloudRgbaHalf, marched.cloudRgbaHalf);
    EXPECT_EQ(limited.marchRowLookups, marched.marchRowLookups);
}

// Lit samples behind a view transmittance below 0.1 take the light of the last cone marched: fewer
// lookups in a thick deck, and what they add reaches the eye through less than a tenth.
TEST_F(ConeTail, DeepLitSamplesTakeTheLastConesLight)
{
    setWeather(*renderer, deckBelowWeather());
    const ViewRequest v = deckFromAboveView();
    QualitySettings own = testQuality();
    own.deepLightReuseM = 0.0;
    QualitySettings taken = testQuality();
    taken.deepLightReuseM = 400.0;
    const RenderResult marched = renderOk(v, own);
    const RenderResult reused = renderOk(v, taken);
    ASSERT_GT(cloudStats(marched).cloudPixels, v.width * v.height / 2);
    const double psnr = psnrCloud(reused, marched);
    const double fewer = 1.0 - totalLookups(reused) / totalLookups(marched);
    std::printf("deep light reuse 400 m vs every deep cone marched, deck from above: PSNR %.2f dB, %.1f %% fewer "
                "lookups\n",
                psnr, 100.0 * fewer);
    EXPECT_NE(reused.cloudRgbaHalf, marched.cloudRgbaHalf);
    EXPECT_GT(fewer, 0.02);  // 6.0 % measured
    EXPECT_GT(psnr, 45.0);  // 59.1 dB measured
}
