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
#include <cstdio>
#include <cstring>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class AerialLut : public GpuFixture
{
protected:
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
