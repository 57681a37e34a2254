// SPDX-License-Identifier: MIT
// Cloud shape tests (issue 22, "Shapes that match the sky") on the available Vulkan device (lavapipe in
// CI), validation on, small images:
// - no cloud below the layer base: from under every base, looking down, alpha is zero on every pixel,
//   also where layers of very different bases meet clear cells (their interpolation in the weather
//   window once made bases that no cell has);
// - no repetition in the shadow map: over the built-in cumulus field, the autocorrelation of the 150 km
//   map has no peak above 0.3 at any lag beyond 5 km (the 8 km noise tile once showed at 0.5 and more).
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
    setWeather(*renderer, makeBuiltinWeather(0));
    constexpr uint32_t kSize = 256;
    constexpr double kExtentM = 150000.0;
    ViewRequest v;
    // Inside the cumulus field, away from the cumulonimbus; the sun at noon for short shadows.
    v.pose = {kBuiltinCumulusLatDeg - 0.3, kBuiltinCumulusLonDeg + 1.0, 500.0, 0.0, 10.0, 0.0};
    v.width = 16;
    v.height = 8;
    v.unixTimeS = parseTime("2026-06-21T11:30:00Z");
    v.shadowMap = true;
    v.shadowMapSize = kSize;
    v.shadowMapExtentM = kExtentM;
    QualitySettings q = testQuality();
    q.maxViewSteps = 16;
    q.shadowSteps = 24;
    q.highCloud = false;  // the cirrus veil is a 2D layer with its own test of rows (none here)
    RenderResult r = renderOk(v, q);
    ASSERT_EQ(r.shadowTransmittance.size(), size_t(kSize) * kSize);
    const std::vector<float>& t = r.shadowTransmittance;
    double mean = 0;
    for (float x : t)
        mean += double(x);
    mean /= double(t.size());
    double variance = 0;
    for (float x : t)
        variance += (double(x) - mean) * (double(x) - mean);
    variance /= double(t.size());
    ASSERT_GT(variance, 0.01) << "the map must hold cloud shadows and gaps";

    const double texelM = kExtentM / kSize;
    const int maxLag = int(33000.0 / texelM);
    double worst = -1;
    int worstX = 0, worstY = 0;
    for (int dy = 0; dy <= maxLag; ++dy)
        for (int dx = -maxLag; dx <= maxLag; ++dx)
        {
            if (std::hypot(dx, dy) * texelM <= 5000.0 || (dy == 0 && dx < 0))
                continue;
            double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
            size_t count = 0;
            for (int y = 0; y + dy < int(kSize); ++y)
                for (int x = std::max(0, -dx); x < int(kSize) && x + dx < int(kSize); ++x)
                {
                    const double a = t[size_t(y) * kSize + size_t(x)];
                    const double b = t[size_t(y + dy) * kSize + size_t(x + dx)];
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
            const double rho = cov / std::sqrt(std::max(sa * sb, 1e-12));
            if (rho > worst)
            {
                worst = rho;
                worstX = dx;
                worstY = dy;
            }
        }
    EXPECT_LT(worst, 0.3) << "autocorrelation peak at a lag of (" << worstX * texelM / 1000.0 << ", "
                          << -worstY * texelM / 1000.0 << ") km east, north";
    std::printf("shadow map autocorrelation beyond 5 km: largest %.3f at (%.1f, %.1f) km\n", worst,
                worstX * texelM / 1000.0, -worstY * texelM / 1000.0);
}
