// SPDX-License-Identifier: MIT
// Cloud shader math (shaders/lib/shell.glsl, cloud_shape.glsl, large_scale.glsl) compiled as C++ and checked
// against analytic cases and a double-precision reference (docs/style.md §8, §14).
#include "shaders/shared/noise_params.h"
#include "shaders/shared/weather_window.h"

#include <gtest/gtest.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
namespace glsl
{
using namespace glm;
#include "shaders/lib/shell.glsl"
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/large_scale.glsl"
#include "shaders/lib/noise.glsl"
#include "shaders/lib/world_jitter.glsl"
#include "shaders/lib/cloud_history.glsl"
}  // namespace glsl
#pragma GCC diagnostic pop

#include <cmath>
#include <random>
#include <set>

namespace
{

// Double-precision roots of |o + t d|^2 = (R + hs)^2 for the eye at (0, 0, R + hc).
bool referenceRoots(double R, double hc, double hs, double mu, double& tNear, double& tFar)
{
    long double rc = R + hc, rs = R + hs;
    long double b = rc * mu;
    long double c = rc * rc - rs * rs;
    long double disc = b * b - c;
    if (disc < 0)
        return false;
    long double s = std::sqrt(disc);
    tNear = double(-b - s);
    tFar = double(-b + s);
    return true;
}

}  // namespace

// Vertical ray from 10 km below a shell at 6.4e6 m: the distance is exactly the height difference.
TEST(CloudMath, VerticalRayToShellIsHeightDifference)
{
    float tNear, tFar;
    const float R = 6.4e6f;
    ASSERT_TRUE(glsl::raySphereRoots(R + 1000.0f, 1.0f, 1000.0f, 1500.0f, R, tNear, tFar));
    EXPECT_NEAR(tFar, 500.0f, 1e-3f);
}

// The cancellation-free form keeps float within centimetres of the double reference at earth radius,
// where the naive form (rc^2 - rs^2 with rc ~ 6.4e6) loses metres.
TEST(CloudMath, ShellIntersectionMatchesDoubleReference)
{
    const double R = 6.4e6;
    int checked = 0;
    for (double hc : {1.0, 300.0, 1200.0, 11000.0})
        for (double hs : {900.0, 1700.0, 9500.0})
            for (double mu = -0.3; mu <= 1.0; mu += 0.013)
            {
                double rn, rf;
                float tn, tf;
                bool ref = referenceRoots(R, hc, hs, mu, rn, rf);
                bool got = glsl::raySphereRoots(float(R + hc), float(mu), float(hc), float(hs), float(R), tn, tf);
                if (!ref || !got || std::fabs(rn * rn - rf * rf) < 1.0)
                    continue;
                // Relative float accuracy of the distance itself, plus 5 cm.
                EXPECT_NEAR(tf, rf, 0.05 + 2e-6 * std::fabs(rf)) << "hc " << hc << " hs " << hs << " mu " << mu;
                if (std::fabs(rn) < 1e6)
                {
                    EXPECT_NEAR(tn, rn, 0.05 + 2e-6 * std::fabs(rn)) << "hc " << hc << " hs " << hs << " mu " << mu;
                }
                ++checked;
            }
    EXPECT_GT(checked, 500);
}

TEST(CloudMath, ShellIntervalCases)
{
    const float R = 6.371e6f;
    float a, b;
    // Below the shell looking up: enter at base, leave at top.
    ASSERT_TRUE(glsl::rayShellInterval(1.0f, 0.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    EXPECT_NEAR(a, 1000.0f, 0.01f);
    EXPECT_NEAR(b, 3000.0f, 0.01f);
    // Below the shell looking down: the ground comes first.
    EXPECT_FALSE(glsl::rayShellInterval(-0.5f, 100.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    // Inside looking down: from the eye to the base.
    ASSERT_TRUE(glsl::rayShellInterval(-1.0f, 2000.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    EXPECT_NEAR(a, 0.0f, 1e-3f);
    EXPECT_NEAR(b, 1000.0f, 0.01f);
    // Above looking down: from the top to the base.
    ASSERT_TRUE(glsl::rayShellInterval(-1.0f, 11000.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    EXPECT_NEAR(a, 8000.0f, 0.01f);
    EXPECT_NEAR(b, 10000.0f, 0.01f);
    // Above looking up: nothing.
    EXPECT_FALSE(glsl::rayShellInterval(0.5f, 11000.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    // Horizontal from inside: a long path out of the top of the shell (curvature), ~ sqrt(2 R dh).
    ASSERT_TRUE(glsl::rayShellInterval(0.0f, 1000.0f, 500.0f, 3000.0f, R, 1e7f, a, b));
    EXPECT_NEAR(b, std::sqrt(2.0 * 6.371e6 * 2000.0), 200.0);
}

// Regression: a ray on the shell's base heading down (where the reference tracer looks for the next stretch
// after a ray leaves a cloud through its base) got the stretch to the far side of the outer sphere, through
// the earth, up to the distance limit: it has none left. Along the base or upward it still crosses the shell.
TEST(CloudMath, RayLeavingThroughTheBaseHasNoStretchLeft)
{
    const float R = 6.371e6f;
    float a, b;
    for (float mu : {-1.0f, -0.3f, -0.01f})
        EXPECT_FALSE(glsl::rayShellInterval(mu, 1000.0f, 1000.0f, 3000.0f, R, 7e5f, a, b)) << "mu " << mu;
    // 1 cm above the base, 60 deg below the horizon: 2 cm of shell left.
    ASSERT_TRUE(glsl::rayShellInterval(-0.5f, 1000.01f, 1000.0f, 3000.0f, R, 7e5f, a, b));
    EXPECT_NEAR(a, 0.0f, 1e-6f);
    EXPECT_NEAR(b, 0.02f, 0.002f);
    ASSERT_TRUE(glsl::rayShellInterval(0.0f, 1000.0f, 1000.0f, 3000.0f, R, 7e5f, a, b));
    EXPECT_NEAR(b, std::sqrt(2.0 * 6.371e6 * 2000.0), 200.0);
    ASSERT_TRUE(glsl::rayShellInterval(1.0f, 1000.0f, 1000.0f, 3000.0f, R, 7e5f, a, b));
    EXPECT_NEAR(b, 2000.0f, 0.01f);
}

// Regression: an eye at exactly 0 m made downward rays march the whole shell (rayGroundDistance
// returned -1 for hc <= 0), ~100x slower per pixel.
TEST(CloudMath, EyeOnTheGroundStopsDownwardRays)
{
    const float R = 6.371e6f;
    EXPECT_EQ(glsl::rayGroundDistance(R, -0.3f, 0.0f, R), 0.0f);
    EXPECT_LT(glsl::rayGroundDistance(R, 0.3f, 0.0f, R), 0.0f);
    float a, b;
    EXPECT_FALSE(glsl::rayShellInterval(-0.3f, 0.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
    EXPECT_TRUE(glsl::rayShellInterval(0.3f, 0.0f, 1000.0f, 3000.0f, R, 1e6f, a, b));
}

TEST(CloudMath, HeightProfilesStayInUnitRangeAndVanishAtEnds)
{
    for (int type = 0; type <= 10; ++type)
    {
        EXPECT_NEAR(glsl::cloudHeightProfile(type, 0.0f), 0.0f, 1e-6f) << type;
        EXPECT_NEAR(glsl::cloudHeightProfile(type, 1.0f), 0.0f, 1e-6f) << type;
        float peak = 0.0f;
        for (float h = -0.2f; h <= 1.2f; h += 0.01f)
        {
            float v = glsl::cloudHeightProfile(type, h);
            EXPECT_GE(v, 0.0f);
            EXPECT_LE(v, 1.0f);
            peak = std::max(peak, v);
        }
        EXPECT_GT(peak, 0.9f) << type;
    }
    // Cumulus rounds off lower than stratus: at 80% height stratus is denser than cumulus.
    EXPECT_GT(glsl::cloudHeightProfile(CLOUD_TYPE_STRATUS, 0.8f), glsl::cloudHeightProfile(CLOUD_TYPE_CUMULUS, 0.8f));
}

TEST(CloudMath, BeerPowderMatchesFormula)
{
    for (float d = 0.0f; d < 8.0f; d += 0.25f)
        EXPECT_NEAR(glsl::beerPowder(d), 2.0f * std::exp(-d) * (1.0f - std::exp(-2.0f * d)), 1e-6f);
    EXPECT_NEAR(glsl::beerPowder(0.0f), 0.0f, 1e-7f);
    // Maximum at d = ln(3)/2.
    float dMax = std::log(3.0f) / 2.0f;
    EXPECT_GT(glsl::beerPowder(dMax), glsl::beerPowder(dMax - 0.1f));
    EXPECT_GT(glsl::beerPowder(dMax), glsl::beerPowder(dMax + 0.1f));
}

TEST(CloudMath, CoverageRemap)
{
    EXPECT_EQ(glsl::applyCoverage(0.9f, 0.0f), 0.0f);
    EXPECT_NEAR(glsl::applyCoverage(1.0f, 1.0f), 1.0f, 1e-6f);
    // Shapes below the threshold vanish; more coverage gives more cloud; full coverage has no holes.
    EXPECT_EQ(glsl::applyCoverage(0.5f, 0.3f), 0.0f);
    EXPECT_NEAR(glsl::applyCoverage(0.0f, 1.0f), 1.0f, 1e-6f);
    EXPECT_EQ(glsl::applyCoverage(0.98f, 0.01f), 0.0f);
    EXPECT_GT(glsl::applyCoverage(0.8f, 0.6f), glsl::applyCoverage(0.8f, 0.3f));
}

// Häggström's anvil: the exponent widens the top (shape grows) only above 65% of the height, and the
// density term falls to 0.2 at the top.
TEST(CloudMath, AnvilTerms)
{
    EXPECT_NEAR(glsl::anvilShape(0.4f, 0.3f, 0.8f), 0.4f, 1e-6f);
    EXPECT_GT(glsl::anvilShape(0.4f, 0.95f, 0.8f), 0.75f);
    EXPECT_NEAR(glsl::anvilDensity(1.0f), 0.2f, 1e-5f);
    EXPECT_NEAR(glsl::anvilDensity(0.0f), 0.0f, 1e-6f);
    EXPECT_GT(glsl::anvilDensity(0.2f), glsl::anvilDensity(0.9f));
}

// Energy-conserving step: with a constant source, integrating two half steps with transmittance in
// between equals one full step (Hillaire 2016), and thin media reduce to source * dt.
TEST(CloudMath, EnergyConservingIntegrationIsSplitInvariant)
{
    vec3 S(0.7f, 0.5f, 0.3f);
    float sigma = 0.05f, dt = 40.0f;
    vec3 whole = glsl::integrateScattering(S, sigma, dt);
    vec3 halves = glsl::integrateScattering(S, sigma, dt / 2) +
                  std::exp(-sigma * dt / 2) * glsl::integrateScattering(S, sigma, dt / 2);
    EXPECT_NEAR(whole.x, halves.x, 1e-5f);
    EXPECT_NEAR(glsl::integrateScattering(S, 0.0f, dt).y, S.y * dt, 1e-4f);
}

// The coverage mapping assumes the base shape's distribution (BASE_SHAPE_MEAN, BASE_SHAPE_SD in
// cloud_shape.glsl): recompute it from the noise recipe, as cloud_density.glsl combines it (R and most
// of the low-frequency FBM from one texel, 8-bit quantised, BASE_SHAPE_LARGE_WEIGHT from largeScaleFbm at a
// random place).
TEST(CloudMath, BaseShapeStatisticsMatchTheEqualisationConstants)
{
    std::mt19937 rng(3);
    std::uniform_int_distribution<uint32_t> texel(0, BASE_NOISE_SIZE - 1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float modulusM = 384000.0f;  // the offset modulus by default (frame_params.h)
    double sum = 0, sumSq = 0;
    const int n = 20000;
    std::vector<float> equalised;
    for (int i = 0; i < n; ++i)
    {
        glm::vec4 a = glsl::baseNoiseTexel(glm::uvec3(texel(rng), texel(rng), texel(rng)), BASE_NOISE_SIZE, 1u);
        a = glm::round(a * 255.0f) / 255.0f;
        const glm::vec3 place(modulusM * unit(rng), modulusM * unit(rng), modulusM * unit(rng));
        const float large = glsl::largeScaleFbm(place, float(2.0 * M_PI / double(modulusM)));
        float low = glm::mix(a.y * 0.625f + a.z * 0.25f + a.w * 0.125f, large, glsl::BASE_SHAPE_LARGE_WEIGHT);
        float shape = glsl::remapValue(a.x, low - 1.0f, 1.0f, 0.0f, 1.0f);
        sum += double(shape);
        sumSq += double(shape) * double(shape);
        equalised.push_back(glsl::equalizeBaseShape(shape));
    }
    double mean = sum / n, sd = std::sqrt(sumSq / n - mean * mean);
    std::printf("base shape: mean %.4f, sd %.4f\n", mean, sd);
    EXPECT_NEAR(mean, double(glsl::BASE_SHAPE_MEAN), 0.003);
    EXPECT_NEAR(sd, double(glsl::BASE_SHAPE_SD), 0.003);
    // Equalised, the shape is close to uniform: coverage c leaves a fraction ~c (within 0.04).
    for (float c : {0.1f, 0.3f, 0.5f, 0.7f, 0.9f})
    {
        double above = 0;
        for (float e : equalised)
            above += e > 1.0f - c ? 1.0 : 0.0;
        EXPECT_NEAR(above / n, double(c), 0.04) << "coverage " << c;
    }
}

// World-space march jitter (shaders/lib/world_jitter.glsl): a function of the direction only,
// in range, each cube face elsewhere in the tile, one texel angle apart is one texel apart.
TEST(WorldJitter, NeighbouringDirectionsReadNeighbouringTexels)
{
    const float texel = 0.01f;  // rad
    // One direction in every face: in range, and a step of one texel angle moves one texel.
    const glm::vec3 dirs[] = {{1, 0.2f, 0.1f}, {-1, 0.3f, -0.2f}, {0.1f, 1, 0.4f},
                              {0.2f, -1, 0.1f}, {0.3f, 0.1f, 1}, {-0.2f, 0.4f, -1}};
    std::set<int> starts;
    for (glm::vec3 d : dirs)
    {
        glm::vec3 u = glm::normalize(d);
        glm::ivec2 t = glsl::worldJitterTexel(u, texel);
        ASSERT_GE(t.x, 0);
        ASSERT_LT(t.x, BLUE_NOISE_SIZE);
        ASSERT_GE(t.y, 0);
        ASSERT_LT(t.y, BLUE_NOISE_SIZE);
        starts.insert(t.x * BLUE_NOISE_SIZE + t.y);
        EXPECT_EQ(glsl::worldJitterTexel(u, texel), t) << "a function of the direction only";
    }
    EXPECT_EQ(starts.size(), 6u) << "each face starts elsewhere in the tile";
    // Along the +x face's u axis (atan(y/x) grows by the texel angle per texel).
    int moved = 0;
    for (int k = 0; k < 200; ++k)
    {
        float a0 = -0.37f + 0.0037f * float(k);
        glm::vec3 p(std::cos(a0), std::sin(a0), 0.05f), q(std::cos(a0 + texel), std::sin(a0 + texel), 0.05f);
        glm::ivec2 tp = glsl::worldJitterTexel(glm::normalize(p), texel);
        glm::ivec2 tq = glsl::worldJitterTexel(glm::normalize(q), texel);
        int dx = (tq.x - tp.x + BLUE_NOISE_SIZE) % BLUE_NOISE_SIZE;
        moved += dx == 1 && tq.y == tp.y;
    }
    EXPECT_GE(moved, 190) << "one texel angle apart is one texel apart (up to rounding at cell edges)";
}

// The cloud history texel (shaders/lib/cloud_history.glsl, packed for the memory budget): its precision as the texture
// unit decodes it, and that decoding and packing again gives the same bits (a still pixel keeps its history).
namespace
{
glm::vec4 historyRoundTrip(glm::vec4 cloud, float depthM, float& depthBackM)
{
    glm::vec2 alphaDepth = glsl::unpackHistoryAlphaDepth(glsl::packHistoryAlphaDepth(cloud.w, depthM));
    depthBackM = glsl::historyDepthM(alphaDepth.y);
    return glm::vec4(glsl::unpackHistoryColour(glsl::packHistoryColour(glm::vec3(cloud))), alphaDepth.x);
}
}  // namespace

TEST(CloudHistory, PacksRadianceAlphaAndDepthWithinTheStatedPrecision)
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    float worstColour = 0.0f, worstAlpha = 0.0f, worstDepth = 0.0f;
    for (int i = 0; i < 20000; ++i)
    {
        float a = unit(rng);
        float bright = std::exp2(unit(rng) * 20.0f - 12.0f);  // 2^-12 .. 2^8: moonlight to sun glints
        glm::vec4 c(bright * unit(rng), bright * unit(rng), bright, a);
        float depthM = i % 7 == 0 ? 0.0f : std::exp2(unit(rng) * 21.0f);  // 1 m .. 2000 km
        float back = -1.0f;
        glm::vec4 u = historyRoundTrip(c, depthM, back);
        for (int k = 0; k < 3; ++k)
            worstColour = std::max(worstColour, std::abs(u[k] - c[k]) / bright);
        worstAlpha = std::max(worstAlpha, std::abs(u.w - a));
        if (depthM == 0.0f)
            ASSERT_EQ(back, 0.0f) << "no cloud stays exactly 0";
        else  // log(1 + d): relative error 1.16e-4 * (1 + d) / d, so 1.2e-4 beyond 100 m
            worstDepth = std::max(worstDepth, std::abs(back - depthM) / (depthM + 1.0f));
        // Decode -> pack is the identity on packed texels.
        uint32_t colourBits = glsl::packHistoryColour(glm::vec3(c));
        uint32_t alphaDepthBits = glsl::packHistoryAlphaDepth(a, depthM);
        glm::vec2 alphaDepth = glsl::unpackHistoryAlphaDepth(alphaDepthBits);
        ASSERT_EQ(glsl::packHistoryColour(glsl::unpackHistoryColour(colourBits)), colourBits) << i;
        ASSERT_EQ(glsl::packHistoryAlphaDepth(alphaDepth.x, glsl::historyDepthM(alphaDepth.y)), alphaDepthBits) << i;
    }
    std::printf("cloud history: colour error %.2e of the brightest channel, alpha %.2e, depth %.2e relative\n",
                double(worstColour), double(worstAlpha), double(worstDepth));
    EXPECT_LE(worstColour, std::exp2(-9.0f) * 1.0001f);
    EXPECT_LE(worstAlpha, 0.5f / 65535.0f + 1e-6f);
    EXPECT_LT(worstDepth, 1.2e-4f);
    float at1km = 0.0f, at100km = 0.0f;
    historyRoundTrip(glm::vec4(0.0f), 1000.3f, at1km);
    historyRoundTrip(glm::vec4(0.0f), 100003.0f, at100km);
    EXPECT_NEAR(at1km, 1000.3f, 0.12f);
    EXPECT_NEAR(at100km, 100003.0f, 12.0f);
    // Clamped, never wrapped: negative input, overflow, a black cloud.
    float d = 0.0f;
    glm::vec4 big = historyRoundTrip(glm::vec4(1e9f, -1.0f, 0.0f, 2.0f), 1e8f, d);
    EXPECT_EQ(big, glm::vec4(glsl::kHistoryMaxRadiance, 0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(d, glsl::kHistoryMaxDepthM, 0.001f * glsl::kHistoryMaxDepthM);
    EXPECT_EQ(historyRoundTrip(glm::vec4(0.0f), 0.0f, d), glm::vec4(0.0f));
    EXPECT_EQ(d, 0.0f);
}

// Cumulus domes: the coverage threshold rises with height, so the cloud narrows toward its
// top instead of standing as a column with vertical walls; other stratiform genera keep theirs.
TEST(CloudMath, CumulusNarrowsWithHeightAndTheAnvilThinsTowardItsEdge)
{
    float previous = 2.0f;
    for (float h = 0.0f; h <= 1.0f; h += 0.1f)
    {
        const float f = glsl::coverageHeightFactor(CLOUD_TYPE_CUMULUS, h);
        EXPECT_LE(f, previous) << h;
        EXPECT_GE(f, 0.0f);
        previous = f;
    }
    EXPECT_LT(glsl::coverageHeightFactor(CLOUD_TYPE_CUMULUS, 0.8f), 0.5f);
    EXPECT_EQ(glsl::coverageHeightFactor(CLOUD_TYPE_STRATUS, 0.8f), 1.0f);
    // The anvil slab: thick where its coverage is high, nothing below its upper part at a thin edge.
    EXPECT_GT(glsl::anvilSlabProfile(0.4f, 1.0f), 0.9f);
    EXPECT_EQ(glsl::anvilSlabProfile(0.4f, 0.3f), 0.0f);
    EXPECT_GT(glsl::anvilSlabProfile(0.85f, 0.3f), 0.2f);
    EXPECT_EQ(glsl::anvilSlabProfile(1.0f, 1.0f), 0.0f);  // flat top
}

// Ragged bases: stratus and nimbostratus bases are torn up to a share of the layer, other
// genera keep a flat base; the factor only removes cloud (never above 1, 0 below the local base), is 1
// above the torn part, and where the tear is 0 the base stays where it was.
TEST(CloudMath, StratusAndNimbostratusBasesAreRagged)
{
    EXPECT_GT(glsl::baseRaggedness(CLOUD_TYPE_STRATUS), 0.0f);
    EXPECT_GT(glsl::baseRaggedness(CLOUD_TYPE_NIMBOSTRATUS), 0.0f);
    EXPECT_EQ(glsl::baseRaggedness(CLOUD_TYPE_CUMULUS), 0.0f);
    EXPECT_EQ(glsl::baseRaggedness(CLOUD_TYPE_STRATOCUMULUS), 0.0f);
    const float r = glsl::baseRaggedness(CLOUD_TYPE_STRATUS);
    for (float tear = 0.0f; tear <= 1.0f; tear += 0.25f)
        for (float h = 0.0f; h <= 1.0f; h += 0.05f)
        {
            const float f = glsl::raggedBaseFactor(h, r, tear);
            EXPECT_GE(f, 0.0f);
            EXPECT_LE(f, 1.0f);
            if (h < r * tear)
            {
                EXPECT_EQ(f, 0.0f) << h << " " << tear;
            }
            if (h >= r + glsl::RAGGED_BASE_SOFTNESS)
            {
                EXPECT_EQ(f, 1.0f) << h << " " << tear;
            }
        }
    EXPECT_EQ(glsl::raggedBaseFactor(0.1f, r, 1.0f), 0.0f) << "a full tear lifts the base";
    EXPECT_GT(glsl::raggedBaseFactor(0.1f, r, 0.0f), 0.9f) << "no tear keeps it";
    EXPECT_EQ(glsl::raggedBaseFactor(0.0f, 0.0f, 1.0f), 1.0f) << "flat bases are untouched";
}

// The computed warp (large_scale.glsl) repeats with the noise offsets (whole cycles per 384 km modulus), so
// nothing jumps when the offsets wrap.
TEST(CloudMath, LargeScaleWarpRepeatsWithTheOffsets)
{
    const float modulusM = 384000.0f;
    const float radPerM = float(2.0 * M_PI / double(modulusM));
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> place(0.0f, 400000.0f);
    for (int i = 0; i < 1000; ++i)
    {
        const glm::vec3 p(place(rng), place(rng), place(rng));
        for (int axis = 0; axis < 3; ++axis)
        {
            glm::vec3 q = p;
            q[axis] -= modulusM;
            const glm::vec3 d = glsl::largeScaleWarp(p, radPerM, 1500.0f) - glsl::largeScaleWarp(q, radPerM, 1500.0f);
            EXPECT_LT(glm::length(d), 0.5f) << "axis " << axis;
        }
    }
}
