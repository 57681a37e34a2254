// SPDX-License-Identifier: MIT
// The aerial-perspective LUT (shaders/atmosphere/aerial_perspective_lut.comp.glsl) that the composite
// reads for the haze in front of clouds: texels read back from lavapipe (validation on) against the ray
// integral on the CPU (400 steps on the CPU LUTs, skyservice/sky/atmosphere_reference.h), at sunset
// (the reddest, most direction-dependent haze) and at noon, for directions above and below the horizon,
// near the sun and away from it, and distances from 1 km to 700 km.
#include "shaders/shared/atmosphere_params.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/atmosphere_reference.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

using namespace sky;
using namespace sky::testscenes;

namespace
{

struct HorizonRows
{
    double sky = 0, ground = 0;
    double contrast() const { return std::fabs(ground - sky) / sky; }
};

class AerialLut : public GpuFixture
{
protected:
    /// Mean linear green of the horizon sky (1-3 degrees above the horizon) and of the ground 1-4 degrees
    /// below it, seen level from `altM` at noon (32 x 18 pixels, 1.1 degrees a row); fog from the ground.
    static HorizonRows horizonRows(double altM, double visibilityM, double fogTopM = 0, double fogVisibilityM = 0)
    {
        ViewRequest v = lookUp(45.0, 7.0, altM, 0.0, "2026-06-21T12:00:00Z");
        v.width = 32;
        v.height = 18;
        v.fovYDeg = 20.0;  // the horizon between rows 8 and 9
        v.visibilityM = visibilityM;
        v.fogTopM = fogTopM;
        v.fogVisibilityM = fogVisibilityM;
        RenderResult r;
        SkyStatus status = renderView(*renderer, v, testQuality(), r);
        EXPECT_TRUE(status.ok()) << status.message;
        EXPECT_EQ(r.linearRgbaHalf.size(), size_t(v.width) * v.height * 4);
        auto rowsGreen = [&](uint32_t first, uint32_t last) {
            double sum = 0;
            for (uint32_t y = first; y <= last; ++y)
                for (uint32_t x = 0; x < v.width; ++x)
                    sum += double(glm::unpackHalf1x16(r.linearRgbaHalf[(size_t(y) * v.width + x) * 4 + 1]));
            return sum / double((last - first + 1) * v.width);
        };
        HorizonRows h;
        h.sky = rowsGreen(6, 7);
        h.ground = rowsGreen(10, 12);
        EXPECT_GT(h.sky, 0.0);
        return h;
    }

    static std::vector<glm::vec3> readLut(const Image& image)
    {
        std::vector<uint8_t> bytes;
        SkyStatus s = readbackImage(renderer->ctx, renderer->memory, image, bytes);
        EXPECT_TRUE(s.ok()) << s.message;
        std::vector<uint16_t> halves(bytes.size() / 2);
        std::memcpy(halves.data(), bytes.data(), halves.size() * 2);
        std::vector<glm::vec3> texels(halves.size() / 4);
        for (size_t i = 0; i < texels.size(); ++i)
            texels[i] = glm::vec3(glm::unpackHalf1x16(halves[4 * i]), glm::unpackHalf1x16(halves[4 * i + 1]),
                                  glm::unpackHalf1x16(halves[4 * i + 2]));
        return texels;
    }
};

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

}  // namespace

TEST_F(AerialLut, TexelsMatchTheRayIntegral)
{
    setWeather(*renderer, WeatherSnapshot{});
    for (const char* time : {"2026-06-21T19:15:00Z", "2026-06-21T12:00:00Z"})
    {
        ViewRequest v = lookUp(45.0, 7.0, 2600.0, 1.0, time);
        v.width = 32;
        v.height = 18;
        renderOk(v, testQuality());
        // The inputs of the LUTs this frame used (kept by the renderer for its reuse check).
        const AtmosphereReference cpu = createAtmosphereReference(renderer->atmosphere.skyViewAtmosphere);
        const SkyViewPushConstants c = renderer->atmosphere.skyViewPush;
        std::vector<glm::vec3> inscatter = readLut(renderer->atmosphere.aerialInscatterLut);
        std::vector<glm::vec3> transmittance = readLut(renderer->atmosphere.aerialTransmittanceLut);
        ASSERT_EQ(inscatter.size(), size_t(AERIAL_LUT_WIDTH) * AERIAL_LUT_HEIGHT * AERIAL_LUT_SLICES);

        float worstInscatter = 0, worstTransmittance = 0;
        int checked = 0;
        for (int x = 0; x < AERIAL_LUT_WIDTH; x += 11)
            for (int y : {0, 8, 16, 20, 21, 22, 23, 30, AERIAL_LUT_HEIGHT - 1})
                for (int slice : {0, 2, 7, 15, AERIAL_LUT_SLICES - 1})
                {
                    glm::vec3 refIn, refT;
                    aerialLutTexelCpu(cpu, c, x, y, slice, 400, refIn, refT);
                    size_t i = (size_t(slice) * AERIAL_LUT_HEIGHT + size_t(y)) * AERIAL_LUT_WIDTH + size_t(x);
                    // In-scattering relative to the brightest channel of the reference (it spans decades
                    // between 1 km and 1000 km), with a floor for the dimmest texels near the eye.
                    float scale = std::max(maxComponent(refIn), 1e-3f * maxComponent(glm::vec3(c.sunIrradiance)));
                    float eIn = maxComponent(glm::abs(inscatter[i] - refIn)) / scale;
                    float eT = maxComponent(glm::abs(transmittance[i] - refT));
                    worstInscatter = std::max(worstInscatter, eIn);
                    worstTransmittance = std::max(worstTransmittance, eT);
                    EXPECT_LT(eIn, 0.015f) << time << " texel " << x << "," << y << " slice " << slice;
                    EXPECT_LT(eT, 0.003f) << time << " texel " << x << "," << y << " slice " << slice;
                    ++checked;
                }
        std::printf("%s: %d texels, worst in-scattering error %.4f of the reference, transmittance %.4f\n", time,
                    checked, double(worstInscatter), double(worstTransmittance));
    }
}

// Far slices hold more haze than near ones (more air), and less transmittance: the slices are in order.
TEST_F(AerialLut, HazeGrowsWithDistance)
{
    setWeather(*renderer, WeatherSnapshot{});
    ViewRequest v = lookUp(45.0, 7.0, 1000.0, 0.0, "2026-06-21T12:00:00Z");
    v.width = 32;
    v.height = 18;
    renderOk(v, testQuality());
    std::vector<glm::vec3> inscatter = readLut(renderer->atmosphere.aerialInscatterLut);
    std::vector<glm::vec3> transmittance = readLut(renderer->atmosphere.aerialTransmittanceLut);
    const int y = AERIAL_LUT_HEIGHT / 2 - 2;  // just above the horizon: the longest paths through the air
    for (int x = 0; x < AERIAL_LUT_WIDTH; x += 7)
        for (int k = 1; k < AERIAL_LUT_SLICES; ++k)
        {
            size_t near = (size_t(k - 1) * AERIAL_LUT_HEIGHT + size_t(y)) * AERIAL_LUT_WIDTH + size_t(x);
            size_t far = near + size_t(AERIAL_LUT_WIDTH) * AERIAL_LUT_HEIGHT;
            EXPECT_GE(inscatter[far].g, inscatter[near].g) << x << " slice " << k;
            EXPECT_LE(transmittance[far].g, transmittance[near].g) << x << " slice " << k;
        }
}

// An eye in level flight turns its ENU axes a little every frame; the LUTs are built for sun and moon
// directions rounded to 2^-14 (atmosphere_passes.cpp), so one 60 Hz frame at 250 m/s keeps them (the
// same inputs, bit for bit) while 20 km moves the sun far enough to rebuild them.
TEST_F(AerialLut, LevelFlightKeepsTheLutsForManyFrames)
{
    setWeather(*renderer, WeatherSnapshot{});
    ViewRequest v = lookUp(45.0, 7.0, 3000.0, 5.0, "2026-06-21T09:00:00Z");
    v.width = 32;
    v.height = 18;
    auto pushAfter = [&](double northM) {
        ViewRequest moved = v;
        moved.pose.latDeg += northM / 111132.0;
        renderOk(moved, testQuality());
        return renderer->atmosphere.skyViewPush;
    };
    SkyViewPushConstants start = pushAfter(0.0);
    int rebuilds = 0;
    for (int frame = 1; frame <= 30; ++frame)
    {
        SkyViewPushConstants now = pushAfter(frame * 250.0 / 60.0);
        rebuilds += std::memcmp(&now, &start, sizeof now) != 0 ? 1 : 0;
        start = now;
    }
    EXPECT_LE(rebuilds, 3) << "of 30 frames at 250 m/s";
    SkyViewPushConstants far = pushAfter(20000.0);
    EXPECT_NE(std::memcmp(&far, &start, sizeof far), 0) << "20 km on";
}

// ViewRequest::visibilityM sets the haze (setHazeVisibility): seen from 300 m, the ground 4-15 km away
// (1-4 degrees below the horizon) keeps a contrast against the horizon sky at 40 km of visibility and all
// but loses it at 2 km (3 / 2 km of extinction leaves 0.2 % of it over 4 km). The transmittance LUT is
// rebuilt for the new haze.
TEST_F(AerialLut, VisibilityHazesTheDistantGround)
{
    setWeather(*renderer, WeatherSnapshot{});
    const double clear = horizonRows(300.0, 40000.0).contrast();
    const AtmosphereParams clearAir = renderer->atmosphere.skyViewAtmosphere;
    const double hazy = horizonRows(300.0, 2000.0).contrast();
    EXPECT_GT(renderer->atmosphere.skyViewAtmosphere.mieExtinction.y, 10.0f * clearAir.mieExtinction.y);
    EXPECT_GT(clear, 0.1) << "the ground does not stand out from the sky at 40 km";
    EXPECT_LT(hazy, 0.3 * clear) << "2 km of visibility did not haze the ground (contrast " << hazy << " vs "
                                 << clear << " at 40 km)";
    std::printf("ground contrast against the horizon sky: %.3f at 40 km, %.3f at 2 km\n", clear, hazy);
}

// Ground fog (ViewRequest::fog*, setGroundFog) is a band: from 150 m inside 300 m of fog with 300 m of
// visibility the ground and the horizon sky are the same fog; from 1000 m, above it, the sky the eye sees
// over the horizon never crosses the fog and stays as it was, while below the horizon the fog's top hides
// the ground. (Seen from above, away from the sun, the fog's top is darker than the ground it hides: the
// atmosphere model's multiple scattering, Hillaire's isotropic approximation on 32 altitude rows, does not
// make a thick band of fog as bright as a cloud's top.)
TEST_F(AerialLut, GroundFogIsABandOfExtinction)
{
    setWeather(*renderer, WeatherSnapshot{});
    const double clearInside = horizonRows(150.0, 40000.0).contrast();
    const double foggyInside = horizonRows(150.0, 40000.0, 300.0, 300.0).contrast();
    EXPECT_LT(foggyInside, 0.3 * clearInside) << "inside the fog the ground still stands out";
    const HorizonRows clearAbove = horizonRows(1000.0, 40000.0);
    const HorizonRows foggyAbove = horizonRows(1000.0, 40000.0, 300.0, 300.0);
    EXPECT_NEAR(foggyAbove.sky / clearAbove.sky, 1.0, 0.1) << "the fog reached above its top";
    EXPECT_GT(std::fabs(foggyAbove.ground / clearAbove.ground - 1.0), 0.2) << "the fog's top does not hide the ground";
    std::printf("fog: contrast inside %.3f (clear %.3f); from above: sky %.4f (clear %.4f), below the horizon "
                "%.4f (clear %.4f)\n",
                foggyInside, clearInside, foggyAbove.sky, clearAbove.sky, foggyAbove.ground, clearAbove.ground);
}
