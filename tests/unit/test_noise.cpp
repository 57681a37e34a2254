// SPDX-License-Identifier: MIT
// Cloud noise (docs/model.md): shaders/lib/noise.glsl compiled as C++ (docs/style.md §8) and the CPU blue noise.
#include "shaders/shared/noise_params.h"
#include "skyservice/sky/blue_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numeric>
#include <vector>

namespace glsl
{
using namespace glm;
#include "shaders/lib/noise.glsl"
}  // namespace glsl

namespace
{

using glm::uvec2;
using glm::uvec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// Deterministic test points (SplitMix-style hash of an index) in [lo, hi).
float testRandom(uint32_t index, uint32_t stream, float lo, float hi)
{
    uint32_t h = glsl::noisePcg3(uvec3(index, stream, 12345u)).x;
    return lo + (hi - lo) * glsl::noiseUnitFloat(h);
}

vec3 testPoint3(uint32_t index, float lo, float hi)
{
    return vec3(testRandom(index, 0, lo, hi), testRandom(index, 1, lo, hi), testRandom(index, 2, lo, hi));
}

struct Stats
{
    double mean = 0.0;
    double stddev = 0.0;
    double minValue = 1e30;
    double maxValue = -1e30;
};

template <typename F>
Stats sampleStats(int count, F&& f)
{
    double sum = 0.0;
    double sum2 = 0.0;
    Stats s;
    for (int i = 0; i < count; ++i)
    {
        double v = double(f(uint32_t(i)));
        sum += v;
        sum2 += v * v;
        s.minValue = std::min(s.minValue, v);
        s.maxValue = std::max(s.maxValue, v);
    }
    s.mean = sum / count;
    s.stddev = std::sqrt(std::max(0.0, sum2 / count - s.mean * s.mean));
    return s;
}

const vec3 kAxes[4] = {vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 1.0f, 1.0f)};

TEST(Noise, SeedKeysAreDeterministicAndDistinct)
{
    EXPECT_EQ(glsl::noiseSeedKey(7u, 1u), glsl::noiseSeedKey(7u, 1u));
    EXPECT_NE(glsl::noiseSeedKey(7u, 1u), glsl::noiseSeedKey(8u, 1u));
    EXPECT_NE(glsl::noiseSeedKey(7u, 1u), glsl::noiseSeedKey(7u, 2u));
}

TEST(Noise, PerlinTilesWithItsPeriod)
{
    const uvec3 key = glsl::noiseSeedKey(3u, NOISE_SALT_PERLIN);
    for (int period : {1, 4, 8})
        for (uint32_t i = 0; i < 300; ++i)
        {
            vec3 p = testPoint3(i, -float(period), float(period));
            float v = glsl::perlinNoise3(p, period, key);
            for (const vec3& axis : kAxes)
                EXPECT_NEAR(v, glsl::perlinNoise3(p + axis * float(period), period, key), 1e-5f) << period << " " << i;
            // far tiles too (positions are wrapped before the lattice lookup)
            EXPECT_NEAR(v, glsl::perlinNoise3(p + vec3(float(5 * period), float(-7 * period), 0.0f), period, key), 1e-4f);
        }
}

// p and p + period agree whenever the position is wrapped first, even when the lattice seam is broken;
// continuity across the seam (lattice index period-1 next to index 0) is what makes the texture tile.
TEST(Noise, ContinuousAcrossTheTileSeam)
{
    const uvec3 key = glsl::noiseSeedKey(3u, NOISE_SALT_PERLIN);
    const float delta = 1e-3f;
    const int period = 8;
    for (uint32_t i = 0; i < 200; ++i)
    {
        vec3 p = testPoint3(i, 0.0f, float(period));
        for (int axis = 0; axis < 3; ++axis)
        {
            vec3 below = p;
            vec3 above = p;
            below[axis] = -delta;
            above[axis] = delta;
            EXPECT_NEAR(glsl::perlinNoise3(below, period, key), glsl::perlinNoise3(above, period, key), 1e-2f);
            EXPECT_NEAR(glsl::worleyNoise3(below, period, key), glsl::worleyNoise3(above, period, key), 1e-2f);
        }
        vec2 q = vec2(p.x, p.y);
        EXPECT_NEAR(glsl::gradientNoise2(vec2(-delta, q.y), period, key).x,
                    glsl::gradientNoise2(vec2(delta, q.y), period, key).x, 1e-2f);
        EXPECT_NEAR(glsl::gradientNoise2(vec2(q.x, -delta), period, key).x,
                    glsl::gradientNoise2(vec2(q.x, delta), period, key).x, 1e-2f);
    }
}

TEST(Noise, PerlinIsZeroOnLatticeAndBounded)
{
    const uvec3 key = glsl::noiseSeedKey(3u, NOISE_SALT_PERLIN);
    for (int x = 0; x < 8; ++x)
        EXPECT_NEAR(glsl::perlinNoise3(vec3(float(x), float(7 - x), float(x / 2)), 8, key), 0.0f, 1e-6f);
    Stats s = sampleStats(20000, [&](uint32_t i) { return glsl::perlinNoise3(testPoint3(i, 0.0f, 8.0f), 8, key); });
    EXPECT_NEAR(s.mean, 0.0, 0.03);
    EXPECT_GT(s.stddev, 0.1);
    EXPECT_LT(s.stddev, 0.45);
    EXPECT_GE(s.minValue, -1.1);
    EXPECT_LE(s.maxValue, 1.1);
}

TEST(Noise, WorleyTilesWithItsPeriod)
{
    const uvec3 key = glsl::noiseSeedKey(5u, NOISE_SALT_WORLEY);
    for (int period : {1, 3, 16})
        for (uint32_t i = 0; i < 300; ++i)
        {
            vec3 p = testPoint3(i, -float(period), float(period));
            float v = glsl::worleyNoise3(p, period, key);
            for (const vec3& axis : kAxes)
                EXPECT_NEAR(v, glsl::worleyNoise3(p + axis * float(period), period, key), 1e-5f) << period << " " << i;
            // far tiles too (positions are wrapped before the lattice lookup)
            EXPECT_NEAR(v, glsl::worleyNoise3(p + vec3(float(5 * period), float(-7 * period), 0.0f), period, key), 1e-4f);
        }
}

TEST(Noise, WorleyIsOneAtFeaturePointsWithSensibleMean)
{
    const uvec3 key = glsl::noiseSeedKey(5u, NOISE_SALT_WORLEY);
    const int period = 8;
    for (int x = 0; x < period; ++x)
    {
        int y = (3 * x + 1) % period;
        int z = (5 * x + 2) % period;
        uvec3 h = glsl::noiseHashCell(x, y, z, key);
        vec3 feature = vec3(float(x) + glsl::noiseUnitFloat(h.x), float(y) + glsl::noiseUnitFloat(h.y),
                            float(z) + glsl::noiseUnitFloat(h.z));
        EXPECT_NEAR(glsl::worleyNoise3(feature, period, key), 1.0f, 1e-3f);
        // half a cell away from the feature point the value has clearly dropped
        EXPECT_LT(glsl::worleyNoise3(feature + vec3(0.5f, 0.0f, 0.0f), period, key), 0.55f);
    }
    Stats s = sampleStats(20000, [&](uint32_t i) { return glsl::worleyNoise3(testPoint3(i, 0.0f, 8.0f), period, key); });
    EXPECT_GE(s.minValue, 0.0);
    EXPECT_LE(s.maxValue, 1.0);
    EXPECT_GT(s.mean, 0.35);
    EXPECT_LT(s.mean, 0.75);
    EXPECT_GT(s.stddev, 0.08);
}

TEST(Noise, FbmStatisticsAreInASaneBand)
{
    Stats perlin = sampleStats(5000, [](uint32_t i) { return glsl::perlinFbm3(testPoint3(i, 0.0f, 1.0f), 4, 4, 9u); });
    EXPECT_NEAR(perlin.mean, 0.5, 0.05);
    EXPECT_GT(perlin.stddev, 0.05);
    EXPECT_LT(perlin.stddev, 0.25);
    EXPECT_GE(perlin.minValue, 0.0);
    EXPECT_LE(perlin.maxValue, 1.0);

    Stats worley = sampleStats(5000, [](uint32_t i) {
        return glsl::worleyFbm3(testPoint3(i, 0.0f, 1.0f), 4, 9u, NOISE_SALT_WORLEY);
    });
    EXPECT_GT(worley.mean, 0.35);
    EXPECT_LT(worley.mean, 0.75);
    EXPECT_GT(worley.stddev, 0.05);
    EXPECT_LT(worley.stddev, 0.3);
    EXPECT_GE(worley.minValue, 0.0);
    EXPECT_LE(worley.maxValue, 1.0);
}

TEST(Noise, FbmTilesInTextureCoordinates)
{
    for (uint32_t i = 0; i < 200; ++i)
    {
        vec3 uvw = testPoint3(i, 0.0f, 1.0f);
        for (const vec3& axis : kAxes)
        {
            EXPECT_NEAR(glsl::perlinFbm3(uvw, 4, 4, 2u), glsl::perlinFbm3(uvw + axis, 4, 4, 2u), 1e-5f);
            EXPECT_NEAR(glsl::worleyFbm3(uvw, 4, 2u, NOISE_SALT_WORLEY),
                        glsl::worleyFbm3(uvw + axis, 4, 2u, NOISE_SALT_WORLEY), 1e-5f);
        }
    }
}

TEST(Noise, PerlinWorleyRemapStaysInRangeAndDilates)
{
    EXPECT_FLOAT_EQ(glsl::perlinWorley(0.3f, 0.0f), 0.3f);  // no Worley: Perlin unchanged
    EXPECT_FLOAT_EQ(glsl::perlinWorley(0.3f, 1.0f), 1.0f);  // at a cell centre: full
    for (float p = 0.0f; p <= 1.0f; p += 0.125f)
        for (float w = 0.0f; w <= 1.0f; w += 0.125f)
        {
            float v = glsl::perlinWorley(p, w);
            EXPECT_GE(v, p);
            EXPECT_LE(v, 1.0f);
        }
}

// The texel recipes of the three textures: range, tiling across the texture edge, determinism.
TEST(Noise, BaseTextureTexelsTileAndStayInRange)
{
    const uint32_t size = BASE_NOISE_SIZE;
    Stats channel[4];
    for (uint32_t i = 0; i < 400; ++i)
    {
        uvec3 t = uvec3(glm::min(testPoint3(i, 0.0f, float(size)), vec3(float(size - 1))));
        vec4 v = glsl::baseNoiseTexel(t, size, 1u);
        for (int c = 0; c < 4; ++c)
        {
            EXPECT_GE(v[c], 0.0f);
            EXPECT_LE(v[c], 1.0f);
            channel[c].mean += double(v[c]) / 400.0;
        }
        // texel t + size lies one tile further: the same value (up to float rounding of the coordinate)
        vec4 wrapped = glsl::baseNoiseTexel(t + uvec3(size, 0u, size), size, 1u);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(v[c], wrapped[c], 1e-4f);
        // G is the shared low-frequency Worley FBM
        EXPECT_NEAR(v.y, glsl::worleyFbm3(glsl::noiseTexelCoord3(t, size), BASE_NOISE_WORLEY_PERIOD, 1u, NOISE_SALT_WORLEY),
                    1e-6f);
    }
    for (int c = 0; c < 4; ++c)
    {
        EXPECT_GT(channel[c].mean, 0.3) << c;
        EXPECT_LT(channel[c].mean, 0.9) << c;
    }
}

TEST(Noise, DetailTextureTexelsTileAndStayInRange)
{
    const uint32_t size = DETAIL_NOISE_SIZE;
    for (uint32_t i = 0; i < 200; ++i)
    {
        uvec3 t = uvec3(glm::min(testPoint3(i, 0.0f, float(size)), vec3(float(size - 1))));
        vec4 v = glsl::detailNoiseTexel(t, size, 1u);
        vec4 wrapped = glsl::detailNoiseTexel(t + uvec3(0u, size, size), size, 1u);
        for (int c = 0; c < 4; ++c)
        {
            EXPECT_GE(v[c], 0.0f);
            EXPECT_LE(v[c], 1.0f);
            EXPECT_NEAR(v[c], wrapped[c], 1e-4f);
        }
    }
}

TEST(Noise, SameSeedSameValuesOtherSeedOtherValues)
{
    int differing = 0;
    const int count = 100;
    for (uint32_t i = 0; i < uint32_t(count); ++i)
    {
        uvec3 t = uvec3(glm::min(testPoint3(i, 0.0f, 128.0f), vec3(127.0f)));
        vec4 a = glsl::baseNoiseTexel(t, BASE_NOISE_SIZE, 42u);
        EXPECT_EQ(a, glsl::baseNoiseTexel(t, BASE_NOISE_SIZE, 42u));
        vec4 b = glsl::baseNoiseTexel(t, BASE_NOISE_SIZE, 43u);
        if (glm::abs(a.x - b.x) > 1e-3f && glm::abs(a.w - b.w) > 1e-3f)
            ++differing;
        uvec2 t2 = uvec2(t.x, t.y);
        EXPECT_EQ(glsl::curlNoiseTexel(t2, CURL_NOISE_SIZE, 42u), glsl::curlNoiseTexel(t2, CURL_NOISE_SIZE, 42u));
        EXPECT_NE(glsl::curlNoiseTexel(t2, CURL_NOISE_SIZE, 42u), glsl::curlNoiseTexel(t2, CURL_NOISE_SIZE, 43u));
    }
    EXPECT_GT(differing, count * 9 / 10);
}

TEST(Noise, GradientNoise2DerivativeMatchesFiniteDifferences)
{
    const uvec3 key = glsl::noiseSeedKey(11u, NOISE_SALT_CURL);
    const float h = 1e-3f;
    for (uint32_t i = 0; i < 200; ++i)
    {
        vec2 p = vec2(testRandom(i, 0, 0.0f, 8.0f), testRandom(i, 1, 0.0f, 8.0f));
        vec3 n = glsl::gradientNoise2(p, 8, key);
        float dx = (glsl::gradientNoise2(p + vec2(h, 0.0f), 8, key).x - glsl::gradientNoise2(p - vec2(h, 0.0f), 8, key).x) / (2.0f * h);
        float dy = (glsl::gradientNoise2(p + vec2(0.0f, h), 8, key).x - glsl::gradientNoise2(p - vec2(0.0f, h), 8, key).x) / (2.0f * h);
        EXPECT_NEAR(n.y, dx, 2e-3f);
        EXPECT_NEAR(n.z, dy, 2e-3f);
        // tiles with its period
        vec3 wrapped = glsl::gradientNoise2(p + vec2(8.0f, -8.0f), 8, key);
        EXPECT_NEAR(n.x, wrapped.x, 1e-5f);
        EXPECT_NEAR(n.y, wrapped.y, 1e-4f);
    }
}

TEST(Noise, CurlTilesAndIsDivergenceFree)
{
    const float h = 1e-3f;  // in texture coordinates; the finest octave has 16 cells per tile
    double divergenceSum = 0.0;
    double derivativeSum = 0.0;
    for (uint32_t i = 0; i < 500; ++i)
    {
        vec2 uv = vec2(testRandom(i, 0, 0.0f, 1.0f), testRandom(i, 1, 0.0f, 1.0f));
        vec2 c = glsl::curlNoise2(uv, CURL_NOISE_PERIOD, CURL_NOISE_OCTAVES, 4u);
        for (vec2 shift : {vec2(1.0f, 0.0f), vec2(0.0f, 1.0f), vec2(-1.0f, 1.0f)})
        {
            vec2 w = glsl::curlNoise2(uv + shift, CURL_NOISE_PERIOD, CURL_NOISE_OCTAVES, 4u);
            EXPECT_NEAR(c.x, w.x, 1e-4f);
            EXPECT_NEAR(c.y, w.y, 1e-4f);
        }
        auto curl = [](vec2 p) { return glsl::curlNoise2(p, CURL_NOISE_PERIOD, CURL_NOISE_OCTAVES, 4u); };
        float dxdu = (curl(uv + vec2(h, 0.0f)).x - curl(uv - vec2(h, 0.0f)).x) / (2.0f * h);
        float dydv = (curl(uv + vec2(0.0f, h)).y - curl(uv - vec2(0.0f, h)).y) / (2.0f * h);
        divergenceSum += double(std::fabs(dxdu + dydv));
        derivativeSum += double(std::fabs(dxdu) + std::fabs(dydv));
    }
    EXPECT_GT(derivativeSum, 0.0);
    EXPECT_LT(divergenceSum, 0.01 * derivativeSum);
}

TEST(Noise, CurlTextureIsMostlyWithinUnitRange)
{
    const uint32_t size = CURL_NOISE_SIZE;
    int outside = 0;
    double sumSquares = 0.0;
    float maxAbs = 0.0f;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
        {
            vec4 v = glsl::curlNoiseTexel(uvec2(x, y), size, 6u);
            float m = std::max(std::fabs(v.x), std::fabs(v.y));
            maxAbs = std::max(maxAbs, m);
            outside += m > 1.0f ? 1 : 0;
            sumSquares += double(v.x * v.x + v.y * v.y);
            EXPECT_EQ(v.z, 0.0f);
        }
    double rms = std::sqrt(sumSquares / double(size * size));
    EXPECT_LT(outside, int(size * size / 1000));
    EXPECT_LT(maxAbs, 1.5f);
    EXPECT_GT(rms, 0.2);  // not a near-zero field
    std::printf("curl: rms %.3f, max |component| %.3f, outside [-1,1]: %d of %u\n", rms, double(maxAbs), outside, size * size);
}

// ---- blue noise ----

// Power of the mask's mean-free DFT over the frequencies with 0 < |k| < size/8 (toroidal, so the
// wrap-around seam counts too).
double lowFrequencyPower(const std::vector<uint8_t>& mask, uint32_t size)
{
    double mean = 0.0;
    for (uint8_t v : mask)
        mean += v;
    mean /= double(mask.size());
    const int radius = int(size / 8);
    const double twoPi = 6.283185307179586;
    double power = 0.0;
    for (int ky = -radius; ky <= radius; ++ky)
        for (int kx = -radius; kx <= radius; ++kx)
        {
            if ((kx == 0 && ky == 0) || kx * kx + ky * ky >= radius * radius)
                continue;
            std::complex<double> sum = 0.0;
            for (uint32_t y = 0; y < size; ++y)
                for (uint32_t x = 0; x < size; ++x)
                {
                    double phase = -twoPi * (kx * double(x) + ky * double(y)) / double(size);
                    sum += (double(mask[y * size + x]) - mean) * std::polar(1.0, phase);
                }
            power += std::norm(sum);
        }
    return power;
}

TEST(NoiseBlue, EveryLevelIsUsedEqually)
{
    const uint32_t size = BLUE_NOISE_SIZE;
    std::vector<uint8_t> mask = sky::makeBlueNoise(size, 1u);
    ASSERT_EQ(mask.size(), size_t(size * size));
    std::vector<int> histogram(256, 0);
    for (uint8_t v : mask)
        ++histogram[v];
    for (int level = 0; level < 256; ++level)
        EXPECT_EQ(histogram[size_t(level)], int(size * size / 256)) << level;
}

TEST(NoiseBlue, LowFrequencyPowerIsFarBelowWhiteNoise)
{
    const uint32_t size = BLUE_NOISE_SIZE;
    std::vector<uint8_t> mask = sky::makeBlueNoise(size, 1u);
    // white noise with the same histogram: a seeded Fisher-Yates shuffle of the same values
    std::vector<uint8_t> white = mask;
    for (uint32_t i = uint32_t(white.size()) - 1; i > 0; --i)
        std::swap(white[i], white[glsl::noisePcg3(uvec3(i, 99u, 0u)).x % (i + 1)]);
    double blue = lowFrequencyPower(mask, size);
    double whitePower = lowFrequencyPower(white, size);
    std::printf("low-frequency power: blue %.3g, white %.3g, ratio %.4f\n", blue, whitePower, blue / whitePower);
    EXPECT_LT(blue, 0.1 * whitePower);
}

TEST(NoiseBlue, DeterministicPerSeed)
{
    EXPECT_EQ(sky::makeBlueNoise(16, 5u), sky::makeBlueNoise(16, 5u));
    EXPECT_NE(sky::makeBlueNoise(16, 5u), sky::makeBlueNoise(16, 6u));
    EXPECT_THROW(sky::makeBlueNoise(2, 5u), std::invalid_argument);
}

}  // namespace
