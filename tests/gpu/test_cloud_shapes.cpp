// SPDX-License-Identifier: MIT
// Cloud shape tests (docs/model.md "Clouds": shapes that match the sky) on the available Vulkan device (lavapipe in
// CI), validation on, small images:
// - no cloud below the layer base: from under every base, looking down, alpha is zero on every pixel,
//   also where layers of very different bases meet clear cells (their interpolation in the weather
//   window once made bases that no cell has);
// - no repetition in the shadow map: over the built-in cumulus field, the autocorrelation of the 150 km
//   map has no peak above 0.3 at any lag beyond 5 km (the 8 km noise tile once showed at 0.5 and more);
// - cirrus without rows: the shadow map of a cirrus layer has no autocorrelation peak between 10 and 40 km
//   (its 24 km texture tile made rows across the wind).
#include "skyservice/render/renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class CloudShapes : public GpuFixture
{
};

// Cumulus in 0.25-degree blocks on a 0.05-degree grid around (45 N, 7 E): bases of 900 m and 1500 m
// side by side, and clear blocks whose base and top are 0 (what a forecast gives where there is no cloud).
WeatherSnapshot mixedBases()
{
    WeatherSnapshot w = uniformLayer(0.0f, CloudType::Cumulus, 0.0f, 0.0f);
    w.grid = {44.0, 6.0, 0.05, 0.05, 41, 41};
    const size_t n = w.grid.cellCount();
    CloudLayerFields& l = w.layers[0];
    l.coverage.assign(n, 0.0f);
    l.baseAltitudeM.assign(n, 0.0f);
    l.topAltitudeM.assign(n, 0.0f);
    l.type.assign(n, uint8_t(CloudType::Cumulus));
    l.precipitationMmH.assign(n, 0.0f);
    l.windEastMS.assign(n, 5.0f);
    l.windNorthMS.assign(n, 0.0f);
    for (uint32_t i = 0; i < w.grid.nLat; ++i)
        for (uint32_t j = 0; j < w.grid.nLon; ++j)
        {
            const uint32_t block = (i / 5) * 3 + (j / 5);
            const size_t c = w.grid.index(i, j);
            if (block % 3 == 0)
                continue;  // clear
            l.coverage[c] = 0.7f;
            l.baseAltitudeM[c] = block % 3 == 1 ? 900.0f : 1500.0f;
            l.topAltitudeM[c] = l.baseAltitudeM[c] + 2000.0f;
        }
    return w;
}

float maxAlpha(const RenderResult& r, uint32_t& nonZero)
{
    float m = 0.0f;
    nonZero = 0;
    for (size_t i = 0; i < size_t(r.width) * r.height; ++i)
    {
        const float a = glm::unpackHalf1x16(r.cloudRgbaHalf[4 * i + 3]);
        m = std::max(m, a);
        nonZero += a > 0.0f ? 1u : 0u;
    }
    return m;
}

// Pearson correlation of a square map of `size` texels with itself shifted by (dx, dy) texels (x east, y
// south: rows run from the north edge).
double lagCorrelation(const std::vector<float>& t, uint32_t size, int dx, int dy)
{
    double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
    size_t count = 0;
    for (int y = std::max(0, -dy); y < int(size) && y + dy < int(size); ++y)
        for (int x = std::max(0, -dx); x < int(size) && x + dx < int(size); ++x)
        {
            const double a = t[size_t(y) * size + size_t(x)];
            const double b = t[size_t(y + dy) * size + size_t(x + dx)];
            sx += a;
            sy += b;
            sxx += a * a;
            syy += b * b;
            sxy += a * b;
            ++count;
        }
    const double n = double(count);
    const double cov = sxy / n - (sx / n) * (sy / n);
    const double sa = sxx / n - (sx / n) * (sx / n), sb = syy / n - (sy / n) * (sy / n);
    return cov / std::sqrt(std::max(sa * sb, 1e-12));
}

struct CorrelationPeak
{
    double rho = -1;
    double eastM = 0, northM = 0;
};

// The largest lagCorrelation over the lags longer than minLagM whose east and north parts are at most maxLagM.
CorrelationPeak largestCorrelation(const std::vector<float>& t, uint32_t size, double texelM, double minLagM,
                                   double maxLagM)
{
    const int maxLag = int(maxLagM / texelM);
    CorrelationPeak peak;
    for (int dy = 0; dy <= maxLag; ++dy)
        for (int dx = -maxLag; dx <= maxLag; ++dx)
        {
            const double lagM = std::hypot(dx, dy) * texelM;
            if (lagM <= minLagM || (dy == 0 && dx < 0))
                continue;
            const double rho = lagCorrelation(t, size, dx, dy);
            if (rho > peak.rho)
                peak = {rho, dx * texelM, -dy * texelM};
        }
    return peak;
}

double variance(const std::vector<float>& t)
{
    double mean = 0;
    for (float x : t)
        mean += double(x);
    mean /= double(t.size());
    double v = 0;
    for (float x : t)
        v += (double(x) - mean) * (double(x) - mean);
    return v / double(t.size());
}

// The shadow map (transmittance, kSize^2 texels over `extentM`, north up) of `weather` around the eye at
// (latDeg, lonDeg), the sun near noon.
std::vector<float> shadowMapOf(Renderer& renderer, const WeatherSnapshot& weather, double latDeg, double lonDeg,
                               uint32_t size, double extentM, bool highCloud)
{
    setWeather(renderer, weather);
    ViewRequest v;
    v.pose = {latDeg, lonDeg, 500.0, 0.0, 10.0, 0.0};
    v.width = 16;
    v.height = 8;
    v.unixTimeS = parseTime("2026-06-21T11:30:00Z");
    v.shadowMap = true;
    v.shadowMapSize = size;
    v.shadowMapExtentM = extentM;
    QualitySettings q = testQuality();
    q.maxViewSteps = 16;
    q.shadowSteps = 24;
    q.highCloud = highCloud;
    RenderResult r;
    const SkyStatus st = renderView(renderer, v, q, r);
    EXPECT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(r.shadowTransmittance.size(), size_t(size) * size);
    return r.shadowTransmittance;
}

}  // namespace

// Every ray of these views goes down from below the lowest base (eye 600 m, rays 8-42 degrees below the
// horizon, the ground within 4.3 km): none may meet a cloud.
TEST_F(CloudShapes, NoCloudBelowTheLayerBase)
{
    QualitySettings q = testQuality();
    struct Case
    {
        const char* what;
        WeatherSnapshot weather;
        double latDeg, lonDeg;
    };
    const Case cases[] = {
        {"mixed bases and clear cells", mixedBases(), 45.0, 7.0},
        {"built-in cumulus (base 1200 m)", makeBuiltinWeather(0), kBuiltinCumulusLatDeg, kBuiltinCumulusLonDeg},
    };
    for (const Case& c : cases)
        for (double headingDeg : {0.0, 90.0, 225.0})
        {
            setWeather(*renderer, c.weather);
            ViewRequest v = lookUp(c.latDeg, c.lonDeg, 600.0, -25.0, "2026-06-21T11:30:00Z");
            v.pose.headingDeg = headingDeg;
            v.fovYDeg = 30.0;
            v.width = 160;
            v.height = 90;
            RenderResult r = renderOk(v, q);
            uint32_t nonZero = 0;
            EXPECT_EQ(maxAlpha(r, nonZero), 0.0f) << c.what << ", heading " << headingDeg << ": " << nonZero
                                                  << " pixels with cloud below every base";
        }
    // The same weather does have cloud where the rays go up into it (the test can see cloud at all).
    setWeather(*renderer, mixedBases());
    ViewRequest up = lookUp(45.0, 7.0, 600.0, 30.0, "2026-06-21T11:30:00Z");
    up.width = 160;
    up.height = 90;
    uint32_t nonZero = 0;
    EXPECT_GT(maxAlpha(renderOk(up, q), nonZero), 0.5f);
}

// Pearson correlation of the map with itself shifted by every lag up to 33 km (the old 8 km and 24 km
// tiles in every orientation the earth-fixed noise axes take on the ground); lags under 5 km are one
// cloud's own extent.
TEST_F(CloudShapes, ShadowMapDoesNotRepeat)
{
    constexpr uint32_t kSize = 256;
    constexpr double kExtentM = 150000.0;
    // Inside the cumulus field, away from the cumulonimbus; the sun at noon for short shadows. Without the
    // cirrus veil: a 2D layer with its own test of rows (CirrusHasNoRegularRows).
    const std::vector<float> t = shadowMapOf(*renderer, makeBuiltinWeather(0), kBuiltinCumulusLatDeg - 0.3,
                                             kBuiltinCumulusLonDeg + 1.0, kSize, kExtentM, false);
    ASSERT_EQ(t.size(), size_t(kSize) * kSize);
    ASSERT_GT(variance(t), 0.01) << "the map must hold cloud shadows and gaps";

    const double texelM = kExtentM / kSize;
    const CorrelationPeak p = largestCorrelation(t, kSize, texelM, 5000.0, 33000.0);
    const double worst = p.rho;
    EXPECT_LT(worst, 0.3) << "autocorrelation peak at a lag of (" << p.eastM / 1000.0 << ", " << p.northM / 1000.0
                          << ") km east, north";
    std::printf("shadow map autocorrelation beyond 5 km: largest %.3f at (%.1f, %.1f) km\n", worst,
                p.eastM / 1000.0, p.northM / 1000.0);
}

// Cirrus fibres lie along the upper wind (east here), read from a 24 km texture tile; without a warp that
// is not periodic with the tile, the fibres come back every tile in regular rows (the map correlated 0.66
// with itself 14 km west and 34 km south). Over a 100 km map no lag beyond 10 km (up to 40 km east and
// north) correlates above 0.3 (0.19 with the computed warp).
TEST_F(CloudShapes, CirrusHasNoRegularRows)
{
    constexpr uint32_t kSize = 160;
    constexpr double kExtentM = 100000.0;
    const std::vector<float> t =
        shadowMapOf(*renderer, highLayer(0.5f, CloudType::Cirrus, 9500.0f), 46.5, 6.5, kSize, kExtentM, true);
    ASSERT_GT(variance(t), 1e-4) << "the map must hold cirrus streaks";
    const CorrelationPeak p = largestCorrelation(t, kSize, kExtentM / kSize, 10000.0, 40000.0);
    std::printf("cirrus autocorrelation beyond 10 km: largest %.3f at (%.1f, %.1f) km\n", p.rho, p.eastM / 1000.0,
                p.northM / 1000.0);
    EXPECT_LT(p.rho, 0.3) << "cirrus rows: autocorrelation peak at a lag of (" << p.eastM / 1000.0 << ", "
                          << p.northM / 1000.0 << ") km east, north";
}

// The cirrus warp is computed: read from an 8-bit texture, as it was, lavapipe returned it in 8-bit steps
// (56 m), so the fibres broke along lines ~100 m apart. Over a 1.5 km map of 12 m texels, the largest step
// between neighbouring texels is under 11 times the mean step (the 8-bit warp: 17-27; computed: 7).
TEST_F(CloudShapes, CirrusHasNoSteps)
{
    constexpr uint32_t kSize = 128;
    for (const double latDeg : {45.2, 46.5, 47.1})
    {
        const std::vector<float> t = shadowMapOf(*renderer, highLayer(0.5f, CloudType::Cirrus, 9500.0f), latDeg,
                                                 latDeg - 39.5, kSize, 1500.0, true);
        ASSERT_GT(variance(t), 1e-4) << "the map must hold cirrus";
        double sum = 0, largest = 0;
        size_t count = 0;
        for (uint32_t y = 0; y + 1 < kSize; ++y)
            for (uint32_t x = 0; x + 1 < kSize; ++x)
            {
                const size_t i = size_t(y) * kSize + x;
                for (const size_t j : {i + 1, i + kSize})
                {
                    const double step = std::fabs(double(t[j]) - double(t[i]));
                    sum += step;
                    largest = std::max(largest, step);
                    ++count;
                }
            }
        const double ratio = largest / (sum / double(count));
        std::printf("cirrus at %.1f N: largest step %.1f times the mean\n", latDeg, ratio);
        EXPECT_LT(ratio, 11.0) << "cirrus at " << latDeg << " N breaks in steps";
    }
}
