// SPDX-License-Identifier: MIT
// GPU tests on the available Vulkan device (lavapipe in CI), validation on: a validation message fails
// the test. Small images and the "test" quality preset; statistics that would fail if a feature broke.
#include "shaders/shared/noise_params.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/atmosphere.h"
#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wshadow"
namespace glsl
{
using namespace glm;
#include "shaders/lib/noise.glsl"
}  // namespace glsl
#pragma GCC diagnostic pop

using namespace sky;
using namespace sky::testscenes;

namespace
{

class GpuRender : public GpuFixture
{
protected:

    RenderResult render(const WeatherSnapshot& weather, const ViewRequest& request, QualitySettings q = testQuality())
    {
        setWeather(*renderer, weather);
        RenderResult result;
        SkyStatus s = renderView(*renderer, request, q, result);
        EXPECT_TRUE(s.ok()) << s.message;
        return result;
    }
};

}  // namespace

TEST_F(GpuRender, ClearSkyHasNoCloudPixels)
{
    RenderResult r = render(clearSky(), lookUp(45.0, 7.0, 300.0, 30.0, "2026-06-21T12:00:00Z"));
    ImageStats s = cloudStats(r);
    EXPECT_EQ(s.cloudPixels, 0u);
    EXPECT_LT(s.maxAlpha, 1e-3f);
    EXPECT_TRUE(s.allFinite);
}

TEST_F(GpuRender, OvercastCoversTheSkyAboveTheHorizon)
{
    RenderResult r = render(uniformLayer(1.0f, CloudType::Stratus, 1000.0f, 1800.0f),
                            lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z"));
    ImageStats s = cloudStats(r);
    EXPECT_GE(double(s.cloudPixels) / double(s.skyPixels), 0.95);
}

TEST_F(GpuRender, ScatteredCoverageGivesPartialCloud)
{
    RenderResult r = render(uniformLayer(0.3f, CloudType::Cumulus, 1200.0f, 3000.0f),
                            lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z"));
    ImageStats s = cloudStats(r);
    double fraction = double(s.cloudPixels) / double(s.skyPixels);
    EXPECT_GT(fraction, 0.05);
    EXPECT_LT(fraction, 0.75);
}

// Inside a cloud the march advances by whole steps, also where steps are longer than the 60 m beyond
// which it bisects for a cloud's surface. A uniform sheet (coverage 1 makes the density 1 all through
// the layer, so the detail erosion changes nothing) 300 m thick at 13 km, seen from below at the zenith:
// the view samples there are 65 m apart, and the sheet's alpha must follow Beer's law over its
// thickness, 1 - exp(-0.002 x 0.6 x 300) = 0.30. It fails with the bisection that ran again at every
// sample after a surface (each sample crept 2 m on while absorbing a whole step: alpha ~1).
TEST_F(GpuRender, LongStepsThroughAThinSheetFollowBeersLaw)
{
    QualitySettings q = testQuality();
    q.extinctionPerM = 0.002;
    RenderResult r = render(uniformLayer(1.0f, CloudType::Stratus, 13000.0f, 13300.0f),
                            lookUp(45.0, 7.0, 100.0, 89.0, "2026-06-21T12:00:00Z"), q);
    double alphaSum = 0.0;
    int count = 0;
    for (uint32_t y = r.height / 2 - 5; y < r.height / 2 + 5; ++y)
        for (uint32_t x = r.width / 2 - 5; x < r.width / 2 + 5; ++x, ++count)
            alphaSum += double(glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]));
    double expected = 1.0 - std::exp(-0.002 * 0.6 * 300.0);  // stratus: genusDensityScale 0.6
    // Whole steps of 65 m cover the 300 m with 4-5 samples: within 0.05 of Beer's law.
    std::printf("thin sheet alpha %.4f (Beer's law %.4f)\n", alphaSum / count, expected);
    EXPECT_NEAR(alphaSum / count, expected, 0.05);
}

TEST_F(GpuRender, SameInputsGiveSameBytes)
{
    WeatherSnapshot w = makeBuiltinWeather(0);
    ViewRequest v = cumulonimbusView("2026-06-21T14:00:00Z");
    RenderResult a = render(w, v);
    RenderResult b = render(w, v);
    EXPECT_EQ(a.displayRgba8, b.displayRgba8);
    EXPECT_EQ(a.cloudRgbaHalf, b.cloudRgbaHalf);
    EXPECT_EQ(a.cloudDepthM, b.cloudDepthM);
}

// The clouds drift with the wind within a second (ViewRequest::unixTimeFractionS): 0.9 s into a second
// with a 5 m/s wind they lie 4.5 m on, nearly where the next whole second puts them (5 m), not where the
// second began. Without the fraction the frame 0.9 s in equals the one at the second's start.
TEST_F(GpuRender, CloudsDriftWithinASecond)
{
    const WeatherSnapshot w = uniformLayer(0.3f, CloudType::Cumulus, 1200.0f, 3000.0f);
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z");
    const RenderResult start = render(w, v);
    v.unixTimeFractionS = 0.9;
    const RenderResult late = render(w, v);
    v.unixTimeFractionS = 0.0;
    v.unixTimeS += 1;
    const RenderResult next = render(w, v);
    auto meanDifference = [](const RenderResult& a, const RenderResult& b) {
        double sum = 0;
        for (size_t i = 0; i < a.displayRgba8.size(); ++i)
            sum += std::abs(int(a.displayRgba8[i]) - int(b.displayRgba8[i]));
        return sum / double(a.displayRgba8.size());
    };
    ASSERT_EQ(start.displayRgba8.size(), next.displayRgba8.size());
    const double startToNext = meanDifference(start, next), lateToNext = meanDifference(late, next);
    std::printf("  mean |difference| to the next second: from its start %.3f, from 0.9 s in %.3f\n", startToNext,
                lateToNext);
    EXPECT_GT(startToNext, 0.0) << "the clouds drift with the wind";
    EXPECT_LT(lateToNext, 0.5 * startToNext);
}

// One cumulus cell 12 km east of the eye, seen at the same low sun elevation from its sunlit side
// (afternoon, sun behind the eye) and from its shadow side (morning, sun behind the cloud).
TEST_F(GpuRender, SunSideOfACumulusIsBrighterThanItsShadowSide)
{
    const double lat = 45.0, lon = 7.0;
    WeatherSnapshot cell = isolatedCell(lat, lon + 0.15, 4000.0, CloudType::Cumulus, 1000.0f, 3000.0f);
    ViewRequest v = lookUp(lat, lon, 1800.0, 3.0, "2026-06-21T17:00:00Z");
    v.pose.headingDeg = 90.0;
    v.fovYDeg = 40.0;
    v.unixTimeS = timeOfSunElevation(lat, lon, "2026-06-21T14:00:00Z", 25.0);
    RenderResult lit = render(cell, v);
    int64_t morning = parseTime("2026-06-21T04:00:00Z");  // the sun rises through 25 degrees
    while (computeSunMoon(morning, lat, lon, 0.0).sun.elevationDeg < 25.0)
        morning += 60;
    v.unixTimeS = morning;
    RenderResult shadow = render(cell, v);
    ImageStats a = cloudStats(lit), b = cloudStats(shadow);
    ASSERT_GT(a.opaquePixels, 300u);
    ASSERT_GT(b.opaquePixels, 300u);
    EXPECT_NEAR(lit.sunElevationDeg, shadow.sunElevationDeg, 1.0);
    // The cell is 12 km away: the light volume's far cascade lights it, and a cascade of 640 m texels
    // fails the 1.3x (the measured figures: BENCHMARKS.md, "Test figures").
    std::printf("opaque luminance: sunlit side %.4f, shadow side %.4f\n", a.meanOpaqueLuminance, b.meanOpaqueLuminance);
    // Opaque pixels only: thin backlit edges are rightly bright (forward scattering, silver lining).
    EXPECT_GT(a.meanOpaqueLuminance, 1.3 * b.meanOpaqueLuminance)
        << "lit " << a.meanOpaqueLuminance << " shadow " << b.meanOpaqueLuminance;
}

// Deep in a cloud (view transmittance below RenderTuning::detailMinTransmittance, 0.2) the view
// samples skip the detail erosion: a deck seen from above stays within 38 dB of the render that erodes
// every sample (the measured figures: BENCHMARKS.md, "Test figures"), and differs from it (the rule is in use).
TEST_F(GpuRender, DeepSamplesWithoutDetailChangeLittle)
{
    WeatherSnapshot w = deckBelowWeather();
    ViewRequest v = deckFromAboveView();
    RenderTuning everySample;
    everySample.detailMinTransmittance = 0.0;
    renderer->tuning = everySample;
    RenderResult eroded = render(w, v);
    renderer->tuning = RenderTuning{};
    RenderResult shipped = render(w, v);
    ASSERT_GT(cloudStats(eroded).opaquePixels, 2000u);
    EXPECT_NE(shipped.cloudRgbaHalf, eroded.cloudRgbaHalf);
    double psnr = psnrCloud(shipped, eroded);
    std::printf("deep samples without detail: %.2f dB\n", psnr);
    EXPECT_GE(psnr, 38.0);
}

// The march's steps inside a cloud (RenderTuning::maxStepOpticalDepth 1: at most one optical depth)
// against steps of 0.2 with 4x the step budget, close to the converged integral: a deck from above and
// a sunlit cumulus cell from the side. The light matched to the path-traced reference (cloud_lighting.glsl)
// keeps light deep inside the clouds through its diffuse octave remainder, which the coarser steps
// integrate less exactly than the skin alone, so the bounds are lower than under the earlier light
// (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(GpuRender, CloudStepsConvergeOnFinerSteps)
{
    QualitySettings fine = testQuality();
    fine.maxViewSteps = 256;
    RenderTuning fineSteps;
    fineSteps.maxStepOpticalDepth = 0.2;
    // Each finer render with the finer steps, the renderer's default tuning around it.
    const auto renderFine = [&](const WeatherSnapshot& weather, const ViewRequest& view) {
        renderer->tuning = fineSteps;
        RenderResult r = render(weather, view, fine);
        renderer->tuning = RenderTuning{};
        return r;
    };
    WeatherSnapshot deck = deckBelowWeather();
    ViewRequest deckView = deckFromAboveView();
    double deckPsnr = psnrCloud(render(deck, deckView), renderFine(deck, deckView));
    WeatherSnapshot cell = isolatedCell(45.0, 7.15, 4000.0, CloudType::Cumulus, 1000.0f, 3000.0f);
    ViewRequest cellView = lookUp(45.0, 7.0, 1800.0, 3.0, "2026-06-21T17:00:00Z");
    cellView.pose.headingDeg = 90.0;
    cellView.fovYDeg = 40.0;
    cellView.unixTimeS = timeOfSunElevation(45.0, 7.0, "2026-06-21T14:00:00Z", 25.0);
    double cellPsnr = psnrCloud(render(cell, cellView), renderFine(cell, cellView));
    std::printf("against 5x finer cloud steps: deck %.2f dB, cumulus cell %.2f dB\n", deckPsnr, cellPsnr);
    EXPECT_GE(deckPsnr, 29.0);
    EXPECT_GE(cellPsnr, 34.0);
}

// Empty-space skipping (shaders/shared/column_bounds.h) changes only where the search samples, never
// which clouds there are: the built-in weather toward the cumulonimbus from above the cumulus field, and
// from FL350 over the deck, where rays graze the empty shell for 100+ km (most of the search skipped).
// What differs is sampling noise at the far deck and the tower, which accumulating frames averages down
// (8 are taken: the light tuned to the path-traced reference is noisier per sample, its cone's long
// sample standing for twice the path); a hidden cloud top is no noise and does not average away: skipping
// that hid the top 300 m of the clouds failed the tower's bound (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(GpuRender, EmptySpaceSkippingDrawsTheSameClouds)
{
    WeatherSnapshot w = makeBuiltinWeather(0);
    // A step budget that neither runs out of (with the test preset's 64, stepping every search sample ran
    // out before the far deck).
    QualitySettings skipping = testQuality();
    skipping.maxViewSteps = 512;
    skipping.accumulationFrames = 8;
    RenderTuning everyStep;
    everyStep.emptySpaceSkipping = false;
    ViewRequest cb = cumulonimbusView("2026-06-21T15:00:00Z");
    ViewRequest fl350 = lookUp(kBuiltinDeckLatDeg, kBuiltinDeckLonDeg + 1.0, 10668.0, -8.0, "2026-06-21T09:30:00Z");
    fl350.pose.headingDeg = 250.0;
    fl350.fovYDeg = 70.0;
    const struct
    {
        ViewRequest view;
        double minPsnr;
    } cases[] = {{cb, 42.0}, {fl350, 35.0}};
    for (const auto& c : cases)
    {
        ViewRequest v = c.view;
        v.width = 160;
        v.height = 90;
        RenderResult skipped = render(w, v, skipping);
        renderer->tuning = everyStep;
        RenderResult stepped = render(w, v, skipping);
        renderer->tuning = RenderTuning{};
        ImageStats a = cloudStats(skipped), b = cloudStats(stepped);
        double psnr = psnrCloud(skipped, stepped);
        std::printf("skipping against every step: %.2f dB, cloud pixels %u against %u\n", psnr, a.cloudPixels,
                    b.cloudPixels);
        ASSERT_GT(b.cloudPixels, 2000u);
        EXPECT_GE(psnr, c.minPsnr);
        EXPECT_NEAR(double(a.cloudPixels), double(b.cloudPixels), 0.005 * double(b.cloudPixels));
        EXPECT_NEAR(a.meanCloudLuminance, b.meanCloudLuminance, 0.01 * b.meanCloudLuminance);
    }
}

TEST_F(GpuRender, SunsetLightIsRedderThanNoonLight)
{
    WeatherSnapshot w = uniformLayer(0.9f, CloudType::Stratocumulus, 900.0f, 1700.0f);
    int64_t sunset = timeOfSunElevation(45.5, 2.5, "2026-06-21T17:00:00Z", 3.0);
    RenderResult noon = render(w, lookDown(45.5, 2.5, 3500.0, parseTime("2026-06-21T11:50:00Z")));
    RenderResult dusk = render(w, lookDown(45.5, 2.5, 3500.0, sunset));
    ImageStats n = cloudStats(noon), d = cloudStats(dusk);
    ASSERT_GT(n.cloudPixels, 1000u);
    ASSERT_GT(d.cloudPixels, 1000u);
    std::printf("cloud red/blue: noon %.4f, sun at 3 degrees %.4f\n", n.meanCloudRed / n.meanCloudBlue,
                d.meanCloudRed / d.meanCloudBlue);
    // Finer cloud steps give about the same ratio (CloudStepsConvergeOnFinerSteps), so 1.2x is the light,
    // not the step; without the reddening of the sunlight it would be ~1 (the measured figures: BENCHMARKS.md, "Test figures").
    EXPECT_GT(d.meanCloudRed / d.meanCloudBlue, 1.2 * (n.meanCloudRed / n.meanCloudBlue));
}

TEST_F(GpuRender, NightIsDarkMoonlitAndFinite)
{
    WeatherSnapshot w = uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2800.0f);
    RenderResult day = render(w, lookUp(45.0, 7.0, 200.0, 30.0, "2026-06-29T12:00:00Z"));
    RenderResult night = render(w, lookUp(45.0, 7.0, 200.0, 30.0, "2026-06-29T23:30:00Z"));  // full moon
    ImageStats n = cloudStats(night), d = cloudStats(day);
    EXPECT_TRUE(n.allFinite);
    EXPECT_TRUE(night.moonIsKeyLight);
    EXPECT_GT(night.moonElevationDeg, 5.0);
    EXPECT_LT(n.meanDisplayLuminance, 0.5 * d.meanDisplayLuminance);
    EXPECT_GT(n.meanCloudLuminance, 0.0);  // moonlit, not black
}

// GPU against the CPU reference: the sky of a clear view equals the CPU-compiled atmosphere.
TEST_F(GpuRender, ClearSkyMatchesCpuAtmosphere)
{
    ViewRequest v = lookUp(45.0, 7.0, 300.0, 20.0, "2026-06-21T09:00:00Z");
    RenderResult r = render(clearSky(), v);
    std::vector<SkyProbe> probes = cpuSkyProbes(*renderer, v, 12);
    ASSERT_EQ(probes.size(), 12u);
    for (const SkyProbe& p : probes)
    {
        size_t i = (size_t(p.y) * r.width + size_t(p.x)) * 4;
        for (int c = 0; c < 3; ++c)
        {
            float gpu = glm::unpackHalf1x16(r.linearRgbaHalf[i + size_t(c)]);
            float cpu = p.radiance[c] * float(r.exposure);
            EXPECT_NEAR(gpu, cpu, 0.03f * cpu + 1e-4f) << "pixel " << p.x << "," << p.y;
        }
    }
}

// GPU against the CPU reference: the base noise texture equals shaders/lib/noise.glsl run as C++.
TEST_F(GpuRender, BaseNoiseMatchesCpuCompiledShaderMath)
{
    std::vector<uint8_t> texels;
    SkyStatus s = readbackImage(renderer->ctx, renderer->memory, renderer->noise.base, texels);
    ASSERT_TRUE(s.ok()) << s.message;
    ASSERT_EQ(texels.size(), size_t(BASE_NOISE_SIZE) * BASE_NOISE_SIZE * BASE_NOISE_SIZE * 4);
    for (uint32_t k = 0; k < 40; ++k)
    {
        glm::uvec3 t((k * 37u) % BASE_NOISE_SIZE, (k * 91u + 5u) % BASE_NOISE_SIZE, (k * 53u + 11u) % BASE_NOISE_SIZE);
        glm::vec4 cpu = glsl::baseNoiseTexel(t, BASE_NOISE_SIZE, 7u);
        size_t i = ((size_t(t.z) * BASE_NOISE_SIZE + t.y) * BASE_NOISE_SIZE + t.x) * 4;
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(float(texels[i + size_t(c)]) / 255.0f, cpu[c], 1.5f / 255.0f) << "texel " << k << " ch " << c;
    }
}

// The weather window is cached while the eye stands still: a new weather at the same eye must still be
// drawn (the cache is keyed on setWeather), and the same weather again gives the same bytes.
TEST_F(GpuRender, NewWeatherAtTheSameEyeIsDrawn)
{
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z");
    v.width = 96;
    v.height = 54;
    RenderResult clear1 = render(clearSky(), v);
    RenderResult overcast = render(uniformLayer(1.0f, CloudType::Stratus, 1000.0f, 1800.0f), v);
    RenderResult clear2 = render(clearSky(), v);
    EXPECT_EQ(cloudStats(clear1).cloudPixels, 0u);
    EXPECT_GT(cloudStats(overcast).cloudPixels, 0.9 * 96 * 54);
    EXPECT_EQ(clear1.displayRgba8, clear2.displayRgba8);
}

// The 2D high cloud is sampled after the march and composited in front of its result when the eye is above
// it (shaders/clouds/cloud_march.comp.glsl, CloudPath): seen from above, a cirrostratus sheet lies over an
// opaque deck, so it changes the deck's pixels and pulls their transmittance-weighted depth toward it. Were
// it composited behind the deck, the opaque deck would hide it: the same radiance and depth as without it.
TEST_F(GpuRender, HighCloudSeenFromAboveLiesInFrontOfTheDeck)
{
    ViewRequest v = lookUp(45.0, 7.0, 10000.0, -45.0, "2026-06-21T12:00:00Z");
    v.width = 96;
    v.height = 54;
    WeatherSnapshot deck = uniformLayer(1.0f, CloudType::Stratus, 900.0f, 2900.0f);
    WeatherSnapshot deckAndHigh = deck;
    size_t n = deck.grid.cellCount();
    deckAndHigh.high.coverage.assign(n, 1.0f);
    deckAndHigh.high.altitudeM.assign(n, 8000.0f);
    deckAndHigh.high.type.assign(n, uint8_t(CloudType::Cirrostratus));
    deckAndHigh.high.windEastMS.assign(n, 10.0f);
    deckAndHigh.high.windNorthMS.assign(n, 0.0f);
    RenderResult a = render(deck, v);
    RenderResult b = render(deckAndHigh, v);

    // Pixels where the deck alone is opaque: their mean depth and mean radiance with and without the sheet.
    double depthA = 0, depthB = 0, lumA = 0, lumB = 0;
    uint32_t opaque = 0;
    for (size_t i = 0; i < size_t(v.width) * v.height; ++i)
    {
        float alphaA = glm::unpackHalf1x16(a.cloudRgbaHalf[i * 4 + 3]);
        if (alphaA < 0.999f)
            continue;
        ++opaque;
        depthA += double(a.cloudDepthM[i]);
        depthB += double(b.cloudDepthM[i]);
        for (int k = 0; k < 3; ++k)
        {
            lumA += double(glm::unpackHalf1x16(a.cloudRgbaHalf[i * 4 + size_t(k)]));
            lumB += double(glm::unpackHalf1x16(b.cloudRgbaHalf[i * 4 + size_t(k)]));
        }
    }
    ASSERT_GT(opaque, uint32_t(0.5 * v.width * v.height));
    depthA /= opaque;
    depthB /= opaque;
    // The deck top lies 10 km and more away along these rays, the sheet 3 km and more: the sheet's alpha pulls
    // the depth in and dims the radiance (the measured figures: BENCHMARKS.md, "Test figures").
    EXPECT_GT(depthA, 8000.0);
    EXPECT_LT(depthB, 0.95 * depthA) << "deck alone " << depthA << " m, with the sheet " << depthB << " m";
    EXPECT_GT(std::abs(lumB - lumA), 0.02 * lumA) << "deck alone " << lumA << ", with the sheet " << lumB;
}
