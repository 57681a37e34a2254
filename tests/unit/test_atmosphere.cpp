// SPDX-License-Identifier: MIT
// The atmosphere and phase-function shader math, compiled as C++ (docs/style.md §8), and the CPU reference.
#include "skyservice/sky/atmosphere.h"
#include "skyservice/sky/atmosphere_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

namespace
{
namespace glsl
{
using namespace glm;
using sampler2D = sky::CpuSampler2D;
vec4 texture(const sampler2D& s, vec2 uv)
{
    return s.sample(uv);
}
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/phase.glsl"
#include "shaders/lib/atmosphere_sampling.glsl"
#pragma GCC diagnostic pop
}  // namespace glsl

using sky::AtmosphereReference;

constexpr double kBottomM = 6360000.0;

// Integral over the sphere of f(cos theta), with theta = pi x^2 so that forward peaks (width ~1 - g)
// get fine steps: 2 pi sin(theta) dtheta, dtheta = 2 pi x dx, midpoint rule in x.
double integrateOverSphere(const std::function<double(double)>& f, int n = 200000)
{
    double sum = 0;
    for (int i = 0; i < n; ++i)
    {
        double x = (i + 0.5) / n;
        double theta = M_PI * x * x;
        sum += f(std::cos(theta)) * 2.0 * M_PI * std::sin(theta) * 2.0 * M_PI * x / n;
    }
    return sum;
}

const AtmosphereReference& earth()
{
    static const AtmosphereReference a = sky::createAtmosphereReference(sky::makeEarthAtmosphere(kBottomM));
    return a;
}

SkyViewPushConstants lights(float camRM, float sunElevationDeg, float sunAzimuthDeg)
{
    SkyViewPushConstants c{};
    float e = glm::radians(sunElevationDeg);
    float a = glm::radians(sunAzimuthDeg);
    c.sunDirection = glm::vec4(std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e), camRM);
    c.sunIrradiance = earth().params.solarIrradiance;
    c.moonDirection = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);  // below the ground: no moonlight
    c.moonIrradiance = glm::vec4(0.0f);
    return c;
}

glm::vec3 dirFromElevAz(float elevationDeg, float azimuthDeg)
{
    return glsl::enuDirectionFromAngles(glm::radians(90.0f - elevationDeg), glm::radians(azimuthDeg));
}

bool finiteNonNegative(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

TEST(Phase, AllIntegrateToOneOverTheSphere)
{
    const std::pair<const char*, std::function<double(double)>> phases[] = {
        {"HG 0.8", [](double nu) { return glsl::phaseHenyeyGreenstein(0.8f, float(nu)); }},
        {"HG -0.3", [](double nu) { return glsl::phaseHenyeyGreenstein(-0.3f, float(nu)); }},
        {"HG 0", [](double nu) { return glsl::phaseHenyeyGreenstein(0.0f, float(nu)); }},
        {"two-lobe", [](double nu) { return glsl::phaseTwoLobeHG(0.8f, -0.3f, 0.7f, float(nu)); }},
        {"Draine", [](double nu) { return glsl::phaseDraine(0.5f, 1.0f, float(nu)); }},
        {"HG+Draine 2um", [](double nu) { return glsl::phaseHgDraine(2.0f, float(nu)); }},
        {"HG+Draine 5um", [](double nu) { return glsl::phaseHgDraine(5.0f, float(nu)); }},
        {"HG+Draine 20um", [](double nu) { return glsl::phaseHgDraine(20.0f, float(nu)); }},
        {"HG+Draine 50um", [](double nu) { return glsl::phaseHgDraine(50.0f, float(nu)); }},
        {"Rayleigh", [](double nu) { return glsl::rayleighPhase(float(nu)); }},
        {"Cornette-Shanks 0.8", [](double nu) { return glsl::miePhaseCornetteShanks(0.8f, float(nu)); }},
        {"isotropic", [](double) { return glsl::phaseIsotropic(); }},
    };
    for (const auto& [name, f] : phases)
        EXPECT_NEAR(integrateOverSphere(f), 1.0, 2e-3) << name;
}

TEST(Phase, MeanCosines)
{
    auto meanCosine = [](const std::function<double(double)>& f) {
        return integrateOverSphere([&](double nu) { return f(nu) * nu; });
    };
    EXPECT_NEAR(meanCosine([](double nu) { return glsl::phaseHenyeyGreenstein(0.8f, float(nu)); }), 0.8, 2e-3);
    // Two lobes: w g1 + (1 - w) g2 = 0.7 * 0.8 + 0.3 * -0.3 = 0.47.
    EXPECT_NEAR(meanCosine([](double nu) { return glsl::phaseTwoLobeHG(0.8f, -0.3f, 0.7f, float(nu)); }), 0.47, 2e-3);
    // Cloud droplets of 20 um scatter strongly forward (Mie: g ~ 0.85) with a backward lobe.
    double g20 = meanCosine([](double nu) { return glsl::phaseHgDraine(20.0f, float(nu)); });
    EXPECT_GT(g20, 0.75);
    EXPECT_LT(g20, 0.95);
    EXPECT_GT(glsl::phaseHgDraine(20.0f, 1.0f), 1000.0f * glsl::phaseHgDraine(20.0f, 0.0f));
}

TEST(AtmosphereGeometry, VerticalDistanceToTopIsExact)
{
    AtmosphereParams p = sky::makeEarthAtmosphere(kBottomM);
    // top = 6460 km, r = 6400 km: exactly 60 km; float has 0.004 m resolution there.
    EXPECT_FLOAT_EQ(glsl::distanceToTopBoundary(p, 6.4e6f, 1.0f), 60000.0f);
    EXPECT_FLOAT_EQ(glsl::distanceToBottomBoundary(p, 6.4e6f, -1.0f), 40000.0f);
    EXPECT_FALSE(glsl::rayIntersectsGround(p, 6.4e6f, 0.0f));
    EXPECT_TRUE(glsl::rayIntersectsGround(p, 6.4e6f, -0.2f));
}

TEST(AtmosphereGeometry, GrazingDistancesMatchDouble)
{
    AtmosphereParams p = sky::makeEarthAtmosphere(kBottomM);
    const double top = kBottomM + 100000.0;
    const struct
    {
        double altitudeM;
        double mu;
    } rays[] = {{0.0, 0.0},   {1.0, 0.001},  {10.0, -0.0001}, {2.0, 0.5},   {20000.0, -0.02}, {1.0, 0.9999},
                {10.0, -0.01}, {1000.0, -0.1}, {2.0, -0.5},     {100.0, -0.9}, {9000.0, -0.06}};
    int groundRays = 0;
    for (const auto& ray : rays)
    {
        double r = kBottomM + ray.altitudeM;
        double toTop = -r * ray.mu + std::sqrt(r * r * (ray.mu * ray.mu - 1.0) + top * top);
        float got = glsl::distanceToTopBoundary(p, float(r), float(ray.mu));
        // The textbook float form -r mu + sqrt(r^2 (mu^2 - 1) + top^2) errs by 0.15-1.4 m on these rays;
        // rays through the earth (ground hits) end thousands of km away where a float ulp is 0.5 m.
        EXPECT_NEAR(got, toTop, std::max(0.1, toTop * 1.2e-7)) << ray.altitudeM << " " << ray.mu;
        double disc = r * r * (ray.mu * ray.mu - 1.0) + kBottomM * kBottomM;
        if (ray.mu < 0.0 && disc >= 0.0)
        {
            double toGround = -r * ray.mu - std::sqrt(disc);
            EXPECT_TRUE(glsl::rayIntersectsGround(p, float(r), float(ray.mu))) << ray.altitudeM << " " << ray.mu;
            EXPECT_NEAR(glsl::distanceToBottomBoundary(p, float(r), float(ray.mu)), toGround, toGround * 1e-6 + 0.01)
                << ray.altitudeM << " " << ray.mu;
            ++groundRays;
        }
    }
    EXPECT_EQ(groundRays, 5);
    // A point 1 m above the ground, 5 km along a horizontal ray, is at 1 m + 5000^2 / 2R.
    EXPECT_NEAR(glsl::altitudeAlongRay(p, float(kBottomM + 1.0), 0.0f, 5000.0f), 1.0 + 25e6 / (2 * kBottomM), 0.01);
}

// Straight up, the optical depth of the exponential profiles is sigma H (1 - exp(-100 km / H)) and the
// ozone tent contributes sigma * half width.
TEST(AtmosphereTransmittance, VerticalMatchesAnalyticOpticalDepth)
{
    const AtmosphereParams& p = earth().params;
    auto analytic = [&](int c) {
        double rayleigh = double(p.rayleighScattering[c]) * 8000.0 * (1.0 - std::exp(-100.0 / 8.0));
        double mie = double(p.mieExtinction[c]) * 1200.0 * (1.0 - std::exp(-100.0 / 1.2));
        double ozone = double(p.ozoneAbsorption[c]) * 15000.0;
        return std::exp(-(rayleigh + mie + ozone));
    };
    glm::vec3 quadrature = glsl::transmittanceToTop(p, float(kBottomM), 1.0f, ATMOSPHERE_TRANSMITTANCE_STEPS);
    glm::vec3 lut = sky::sampleTransmittanceCpu(earth(), float(kBottomM), 1.0f);
    for (int c = 0; c < 3; ++c)
    {
        EXPECT_NEAR(double(quadrature[c]) / analytic(c), 1.0, 0.002) << c;
        EXPECT_NEAR(double(lut[c]) / analytic(c), 1.0, 0.01) << c;
    }
}

// The 40-step quadrature of the LUT against 20000 steps, up to the horizon.
TEST(AtmosphereTransmittance, FortyStepsAreEnoughUpToTheHorizon)
{
    const AtmosphereParams& p = earth().params;
    for (float altitude : {0.0f, 1000.0f, 10000.0f})
        for (float mu : {1.0f, 0.3f, 0.05f, 0.0f})
        {
            float r = float(kBottomM) + altitude;
            glm::vec3 coarse = glsl::transmittanceToTop(p, r, mu, ATMOSPHERE_TRANSMITTANCE_STEPS);
            glm::vec3 fine = glsl::transmittanceToTop(p, r, mu, 20000);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(coarse[c], fine[c], 0.002f + 0.01f * fine[c]) << altitude << " " << mu << " " << c;
        }
}

TEST(AtmosphereTransmittance, SunsetIsRedderThanNoon)
{
    float r = float(kBottomM) + 100.0f;
    glm::vec3 noon = sky::sampleTransmittanceCpu(earth(), r, std::sin(glm::radians(60.0f)));
    glm::vec3 sunset = sky::sampleTransmittanceCpu(earth(), r, std::sin(glm::radians(2.0f)));
    EXPECT_GT(sunset.x / sunset.z, 5.0f * (noon.x / noon.z));
    EXPECT_GT(noon.z, 0.6f);  // a clear noon sky dims blue sunlight by about a quarter
    EXPECT_LT(sunset.z, 0.1f);
}

TEST(AtmosphereLut, TransmittanceUvRoundTrips)
{
    const AtmosphereParams& p = earth().params;
    for (float altitude : {0.0f, 10.0f, 1000.0f, 30000.0f, 99000.0f})
        for (float mu : {1.0f, 0.5f, 0.1f, 0.0f, -0.05f})
        {
            float r = float(kBottomM) + altitude;
            if (glsl::rayIntersectsGround(p, r, mu))
                continue;
            glm::vec2 uv = glsl::transmittanceLutUv(p, r, mu);
            float r2;
            float mu2;
            glsl::transmittanceLutRMu(p, uv, r2, mu2);
            EXPECT_NEAR(r2, r, 1.0f) << altitude << " " << mu;
            EXPECT_NEAR(mu2, mu, 2e-3f) << altitude << " " << mu;
        }
}

TEST(AtmosphereLut, MultiscatterAndSkyViewUvRoundTrip)
{
    const AtmosphereParams& p = earth().params;
    for (float muS : {-1.0f, -0.3f, 0.0f, 0.7f, 1.0f})
        for (float altitude : {1.0f, 5000.0f, 99000.0f})
        {
            float r = float(kBottomM) + altitude;
            float r2;
            float muS2;
            glsl::multiscatterLutRMuS(p, glsl::multiscatterLutUv(p, r, muS), r2, muS2);
            EXPECT_NEAR(r2, r, 1.0f);
            EXPECT_NEAR(muS2, muS, 1e-5f);
        }
    for (float altitude : {2.0f, 10000.0f, 200000.0f})
    {
        float r = float(kBottomM) + altitude;
        for (float zenithDeg : {0.5f, 45.0f, 89.0f, 90.0f, 90.5f, 120.0f, 179.0f})
            for (float azimuthDeg : {0.0f, 10.0f, 90.0f, 359.0f})
            {
                float zenith = glm::radians(zenithDeg);
                float azimuth = glm::radians(azimuthDeg);
                float zenith2;
                float azimuth2;
                glsl::skyViewLutDirection(p, r, glsl::skyViewLutUv(p, r, zenith, azimuth), zenith2, azimuth2);
                EXPECT_NEAR(zenith2, zenith, 2e-4f) << altitude << " " << zenithDeg;
                EXPECT_NEAR(std::remainder(azimuth2 - azimuth, 2.0f * float(M_PI)), 0.0f, 1e-5f);
            }
        // Rows crowd at the horizon: one row spans far less zenith angle there than at the zenith.
        float zHorizon = glsl::skyViewHorizonZenith(p, r);
        float row = 1.0f / SKY_VIEW_LUT_HEIGHT;
        float zA, zB, aA;
        glsl::skyViewLutDirection(p, r, glm::vec2(0.0f, 0.5f - row), zA, aA);
        glsl::skyViewLutDirection(p, r, glm::vec2(0.0f, 0.5f), zB, aA);
        EXPECT_NEAR(zB, zHorizon, 1e-4f);
        EXPECT_LT(zB - zA, 0.002f);
    }
}

TEST(AtmosphereSky, ZenithIsBluerThanHorizonAtNoon)
{
    SkyViewPushConstants c = lights(float(kBottomM) + 100.0f, 60.0f, 180.0f);
    glm::vec3 zenith = sky::skyRadianceLut(earth(), c, glm::vec3(0.0f, 0.0f, 1.0f));
    glm::vec3 horizon = sky::skyRadianceLut(earth(), c, dirFromElevAz(1.0f, 0.0f));
    EXPECT_GT(zenith.z / zenith.x, 1.5f * horizon.z / horizon.x);
    EXPECT_GT(zenith.z, zenith.x);
    // Clear-sky zenith radiance at 440 nm for a 60-degree sun: of order 0.05-0.1 W m^-2 sr^-1 nm^-1.
    EXPECT_GT(zenith.z, 0.02f);
    EXPECT_LT(zenith.z, 0.2f);
}

TEST(AtmosphereSky, NightHasNoNaNAndNoNegativeValues)
{
    SkyViewPushConstants c = lights(float(kBottomM) + 500.0f, -30.0f, 90.0f);
    c.moonDirection = glm::vec4(dirFromElevAz(40.0f, 200.0f), 0.0f);
    c.moonIrradiance = earth().params.solarIrradiance * float(sky::moonIrradianceRelativeToSun(0.0));
    for (float elevation : {90.0f, 30.0f, 1.0f, 0.0f, -0.5f, -10.0f, -90.0f})
        for (float azimuth : {0.0f, 90.0f, 200.0f})
        {
            glm::vec3 v = sky::skyRadianceLut(earth(), c, dirFromElevAz(elevation, azimuth));
            EXPECT_TRUE(finiteNonNegative(v)) << elevation << " " << azimuth;
            c.flags.x = SKY_VIEW_FLAG_GROUND;
            EXPECT_TRUE(finiteNonNegative(sky::skyRadianceLut(earth(), c, dirFromElevAz(elevation, azimuth))));
            c.flags.x = 0;
        }
    // The moonlit sky is dim but there, brightest near the moon.
    glm::vec3 nearMoon = sky::skyRadianceLut(earth(), c, dirFromElevAz(38.0f, 200.0f));
    glm::vec3 farFromMoon = sky::skyRadianceLut(earth(), c, dirFromElevAz(38.0f, 20.0f));
    EXPECT_GT(nearMoon.z, farFromMoon.z);
    EXPECT_GT(nearMoon.z, 0.0f);
    // Without the moon the sun 30 degrees down leaves the sky nearly black.
    c.moonIrradiance = glm::vec4(0.0f);
    glm::vec3 dark = sky::skyRadianceLut(earth(), c, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_LT(dark.z, 1e-6f);
    for (const glm::vec4& t : earth().multiscatter.texels)
        EXPECT_TRUE(finiteNonNegative(glm::vec3(t)));
    for (const glm::vec4& t : earth().transmittance.texels)
        EXPECT_TRUE(finiteNonNegative(glm::vec3(t)) && t.x <= 1.0f);
}

// The LUT-based integrator (what the GPU runs) against the brute-force reference.
TEST(AtmosphereSky, IntegratorMatchesBruteForceReference)
{
    const float sunElevations[] = {45.0f, 5.0f};
    const glm::vec2 views[] = {{90.0f, 0.0f}, {30.0f, 180.0f}, {5.0f, 0.0f}, {2.0f, 170.0f}, {-5.0f, 90.0f}};
    for (float sunElevation : sunElevations)
    {
        SkyViewPushConstants c = lights(float(kBottomM) + 200.0f, sunElevation, 180.0f);
        for (glm::vec2 view : views)
        {
            glm::vec3 dir = dirFromElevAz(view.x, view.y);
            glm::vec3 lut = sky::skyRadianceLut(earth(), c, dir);
            glm::vec3 reference = sky::referenceSkyRadiance(earth(), c, dir, 2000);
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(lut[ch], reference[ch], 0.05f * reference[ch] + 1e-5f)
                    << "sun " << sunElevation << " view " << view.x << "," << view.y << " channel " << ch;
        }
    }
}

TEST(AtmosphereSky, SkyViewLutSamplingMatchesDirectIntegration)
{
    float camRM = float(kBottomM) + 1000.0f;
    SkyViewPushConstants c = lights(camRM, 10.0f, 100.0f);
    sky::CpuTexture2D lut = sky::computeSkyViewLut(earth(), c);
    for (glm::vec2 view : {glm::vec2(60.0f, 33.0f), glm::vec2(20.0f, 100.0f), glm::vec2(3.0f, 359.5f),
                           glm::vec2(0.5f, 0.2f), glm::vec2(-3.0f, 250.0f), glm::vec2(90.0f, 0.0f)})
    {
        glm::vec3 dir = dirFromElevAz(view.x, view.y);
        glm::vec3 sampled = sky::sampleSkyViewCpu(earth(), lut, dir, camRM);
        glm::vec3 direct = sky::skyRadianceLut(earth(), c, dir);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(sampled[ch], direct[ch], 0.05f * direct[ch] + 1e-5f) << view.x << "," << view.y;
    }
}

TEST(AtmosphereSky, AerialPerspectiveFadesToTheSky)
{
    SkyViewPushConstants c = lights(float(kBottomM) + 1000.0f, 30.0f, 90.0f);
    glm::vec3 cam(0.0f, 0.0f, c.sunDirection.w);
    glm::vec3 dir = dirFromElevAz(-0.2f, 270.0f);  // a slightly downward ray towards the hazy horizon
    glm::vec3 inscatter;
    glm::vec3 transmittance;
    sky::aerialPerspectiveCpu(earth(), c, cam, dir, 0.0f, inscatter, transmittance);
    EXPECT_EQ(transmittance, glm::vec3(1.0f));
    EXPECT_EQ(inscatter, glm::vec3(0.0f));
    float previous = 1.0f;
    for (float distance : {1000.0f, 10000.0f, 50000.0f, 100000.0f})
    {
        sky::aerialPerspectiveCpu(earth(), c, cam, dir, distance, inscatter, transmittance);
        EXPECT_LT(transmittance.z, previous);
        EXPECT_LT(transmittance.z, transmittance.x);  // blue is lost first
        EXPECT_TRUE(finiteNonNegative(inscatter));
        previous = transmittance.z;
    }
    // Out to the ground the 10-step march gives what the sky-view integrator gives.
    sky::aerialPerspectiveCpu(earth(), c, cam, dir, 1e7f, inscatter, transmittance);
    glm::vec3 sky = sky::skyRadianceLut(earth(), c, dir);
    for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(inscatter[ch], sky[ch], 0.1f * sky[ch]);
}

TEST(AtmosphereSky, SunDiskIntegratesToTheIrradiance)
{
    const AtmosphereParams& p = earth().params;
    float camRM = p.radii.y + 1000.0f;  // above the atmosphere: transmittance 1
    glm::vec3 sunDir = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
    glm::vec3 irradiance(1.0f, 2.0f, 3.0f);
    glm::vec3 u = glm::normalize(glm::cross(sunDir, glm::vec3(0.0f, 0.0f, 1.0f)));
    glm::vec3 v = glm::cross(sunDir, u);
    double sum = 0;
    const int n = 200;
    float halfWidth = p.radii.z * 1.05f;
    float cell = 2.0f * halfWidth / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
        {
            float x = -halfWidth + (float(i) + 0.5f) * cell;
            float y = -halfWidth + (float(j) + 0.5f) * cell;
            glm::vec3 dir = glm::normalize(sunDir + x * u + y * v);
            sum += double(glsl::sunDiskRadiance(earth().transmittance.sampler(), p, dir, camRM, sunDir, irradiance).y) *
                   double(cell) * double(cell);
        }
    EXPECT_NEAR(sum, 2.0, 0.03);
    // Limb darkening: the centre is brighter than near the edge.
    glm::vec3 centre = glsl::sunDiskRadiance(earth().transmittance.sampler(), p, sunDir, camRM, sunDir, irradiance);
    glm::vec3 edge = glsl::sunDiskRadiance(earth().transmittance.sampler(), p,
                                           glm::normalize(sunDir + 0.95f * p.radii.z * u), camRM, sunDir, irradiance);
    EXPECT_GT(centre.y, 1.5f * edge.y);
}

// The lit part of the moon's disk carries the moon irradiance whatever the phase.
TEST(AtmosphereSky, MoonDiskIntegratesToTheIrradiance)
{
    const AtmosphereParams& p = earth().params;
    float camRM = p.radii.y + 1000.0f;
    glm::vec3 moonDir = glm::normalize(glm::vec3(-0.2f, 0.5f, 0.7f));
    glm::vec3 u = glm::normalize(glm::cross(moonDir, glm::vec3(0.0f, 0.0f, 1.0f)));
    glm::vec3 v = glm::cross(moonDir, u);
    auto integrate = [&](glm::vec3 sunDir, double& litArea) {
        double sum = 0;
        litArea = 0;
        const int n = 200;
        float halfWidth = p.radii.w * 1.05f;
        float cell = 2.0f * halfWidth / n;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
            {
                glm::vec3 dir = glm::normalize(moonDir + (-halfWidth + (float(i) + 0.5f) * cell) * u +
                                               (-halfWidth + (float(j) + 0.5f) * cell) * v);
                float y = glsl::moonDiskRadiance(earth().transmittance.sampler(), p, dir, camRM, moonDir, sunDir,
                                                 glm::vec3(1.0f)).y;
                sum += double(y) * double(cell) * double(cell);
                litArea += y > 0.0f ? double(cell) * double(cell) : 0.0;
            }
        return sum;
    };
    double diskArea = M_PI * double(p.radii.w) * double(p.radii.w);
    double lit = 0;
    EXPECT_NEAR(integrate(-moonDir, lit), 1.0, 0.02);  // full
    EXPECT_NEAR(lit / diskArea, 1.0, 0.02);
    EXPECT_NEAR(integrate(u, lit), 1.0, 0.03);  // first or last quarter: half the disk lit
    EXPECT_NEAR(lit / diskArea, 0.5, 0.02);
}

TEST(AtmosphereLights, MoonIrradianceFollowsPhase)
{
    // Full moon about -12.7 mag against the sun's -26.74: 2.5e-6.
    EXPECT_NEAR(sky::moonIrradianceRelativeToSun(0.0), 2.46e-6, 0.05e-6);
    EXPECT_LT(sky::moonIrradianceRelativeToSun(90.0), 0.2 * sky::moonIrradianceRelativeToSun(0.0));
    EXPECT_NEAR(sky::moonAngularRadiusRad(384400e3), 0.00452, 0.00002);
}

}  // namespace

// A visibility sets the aerosol at the ground so that Rayleigh + Mie at 550 nm is 3 / visibility (5 %
// contrast left over that distance), grey, keeping the model's albedo, scale height and phase; beyond
// what clean air allows there is no aerosol at all.
TEST(AtmosphereHaze, VisibilitySetsTheGroundExtinction)
{
    const AtmosphereParams clear = sky::makeEarthAtmosphere(kBottomM);
    for (double visibilityM : {2000.0, 40000.0})
    {
        AtmosphereParams p = clear;
        sky::setHazeVisibility(p, visibilityM);
        EXPECT_NEAR(double(p.rayleighScattering.y + p.mieExtinction.y) * visibilityM, sky::kVisibilityOpticalDepth,
                    1e-5)
            << visibilityM;
        EXPECT_EQ(p.mieExtinction.x, p.mieExtinction.z);
        EXPECT_NEAR(p.mieScattering.y / p.mieExtinction.y, clear.mieScattering.y / clear.mieExtinction.y, 1e-6);
        EXPECT_EQ(p.mieScattering.w, clear.mieScattering.w);  // scale height
        EXPECT_EQ(p.mieExtinction.w, clear.mieExtinction.w);  // phase asymmetry
        EXPECT_EQ(std::memcmp(&p.rayleighScattering, &clear.rayleighScattering, sizeof(vec4)), 0);
    }
    AtmosphereParams p = clear;
    sky::setHazeVisibility(p, 400000.0);
    EXPECT_EQ(p.mieExtinction.y, 0.0f);
    // The clear atmosphere's own aerosol is a visibility of 150-200 km.
    const double clearVisibilityM =
        sky::kVisibilityOpticalDepth / double(clear.rayleighScattering.y + clear.mieExtinction.y);
    EXPECT_GT(clearVisibilityM, 150000.0);
    EXPECT_LT(clearVisibilityM, 200000.0);
}

// Ground fog is a band of uniform extinction 3 / visibility (setGroundFog), ramping at its edges over a
// tenth of its depth; none outside it, none when its visibility is 0.
TEST(AtmosphereHaze, GroundFogIsABandOfExtinction)
{
    AtmosphereParams p = sky::makeEarthAtmosphere(kBottomM);
    const glm::vec3 clear = glsl::extinctionAt(p, 150.0f);
    sky::setGroundFog(p, 0.0, 300.0, 500.0);
    EXPECT_NEAR(glsl::groundFogExtinction(p, 150.0f), 3.0f / 500.0f, 1e-7f);
    EXPECT_NEAR(glsl::extinctionAt(p, 150.0f).y - clear.y, 3.0f / 500.0f, 1e-7f);
    EXPECT_NEAR(glsl::mieScatteringAt(p, 150.0f).y - clear.y * 0.0f, 3.0f / 500.0f, 2e-5f);
    EXPECT_GT(glsl::groundFogExtinction(p, 305.0f), 0.0f);  // the upper edge's ramp
    EXPECT_EQ(glsl::groundFogExtinction(p, 321.0f), 0.0f);
    EXPECT_EQ(glsl::groundFogExtinction(p, 2000.0f), 0.0f);
    sky::setGroundFog(p, 0.0, 300.0, 0.0);
    EXPECT_EQ(glsl::groundFogExtinction(p, 150.0f), 0.0f);
    EXPECT_EQ(glsl::extinctionAt(p, 150.0f), clear);
}
