// SPDX-License-Identifier: MIT
// World-space march jitter (issue 5, shaders/lib/world_jitter.glsl): the start offset of a view ray
// is a function of its earth-fixed direction, not of its screen pixel.
//
// On the CPU: the texel function itself. On the GPU (lavapipe, validation on, 128x72, test quality):
// a view and the same view rolled by 180 degrees march exactly the same rays in the opposite screen
// order, so with world-space jitter their cloud images agree pixel for pixel (a screen-space jitter
// gives each ray another offset there), and a full render turned by 0.3 degrees (0.37 pixel) agrees
// with the first one resampled to its rays.
#include "shaders/shared/bindings.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
namespace glsl
{
using namespace glm;
#include "shaders/lib/world_jitter.glsl"
}  // namespace glsl
#pragma GCC diagnostic pop

#include <cmath>
#include <cstdio>
#include <set>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class WorldJitter : public GpuFixture
{
protected:
    void SetUp() override { setWeather(*renderer, reprojectionWeather()); }
};

// The image turned by 180 degrees in the plane (pixel (x, y) -> (w-1-x, h-1-y)).
RenderResult rotated180(const RenderResult& r)
{
    RenderResult out = r;
    size_t n = size_t(r.width) * r.height;
    for (size_t p = 0; p < n; ++p)
    {
        size_t q = n - 1 - p;
        for (size_t c = 0; c < 4; ++c)
        {
            out.cloudRgbaHalf[p * 4 + c] = r.cloudRgbaHalf[q * 4 + c];
            out.displayRgba8[p * 4 + c] = r.displayRgba8[q * 4 + c];
        }
        out.cloudDepthM[p] = r.cloudDepthM[q];
    }
    return out;
}

}  // namespace

TEST(WorldJitterCpu, NeighbouringDirectionsReadNeighbouringTexels)
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

TEST_F(WorldJitter, SameRaysInTheOppositeScreenOrderGiveTheSameClouds)
{
    ViewRequest a = reprojectionView();
    ViewRequest b = a;
    b.pose.rollDeg = 180.0;  // the same pixel rays, screen turned upside down
    RenderResult ra = renderOk(a, testQuality());
    RenderResult rb = rotated180(renderOk(b, testQuality()));
    ASSERT_GT(cloudStats(ra).cloudPixels, 200u);
    double pc = psnrCloud(rb, ra), pd = psnrDisplay(rb, ra);
    std::printf("roll 0 vs roll 180 (turned back): cloud PSNR %.1f dB, display PSNR %.1f dB\n", pc, pd);
    EXPECT_GE(pc, 45.0);
}

TEST_F(WorldJitter, FullRenderTurnedBySubPixelAgreesWithTheFirstResampled)
{
    ViewRequest a = reprojectionView();
    ViewRequest b = a;
    b.pose.headingDeg += 0.3;  // 0.37 pixel at the centre of a 128x72, 60-degree image
    RenderResult ra = renderOk(a, testQuality());
    RenderResult rb = renderOk(b, testQuality());
    double direct = psnrCloud(rb, ra);
    double resampled = psnrResampled(resampleCloud(ra, a, b), rb);
    std::printf("full vs full 0.3 deg apart: cloud PSNR direct %.1f dB, A resampled to B's rays %.1f dB\n", direct,
                resampled);
    EXPECT_GE(resampled, 25.0);
}
