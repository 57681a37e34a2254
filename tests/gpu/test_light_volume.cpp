// SPDX-License-Identifier: MIT
// The light volume (shaders/shared/light_volume.h): the far cone samples precomputed around the eye give
// the clouds the march gives them with every cone sample marched, the volume is placed on whole texels
// of the window plane, and it is absent where it would hold nothing.
#include "shaders/shared/light_volume.h"
#include "skyservice/render/light_volume.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class LightVolume : public GpuFixture
{
protected:
    RenderResult render(const WeatherSnapshot& weather, const ViewRequest& view, double texelM)
    {
        setWeather(*renderer, weather);
        QualitySettings q = testQuality();  // 4 cone samples: 2 live, 2 + the long one in the volume
        q.lightVolumeTexelM = texelM;
        return renderOk(view, q);
    }
    void expectMatchesMarchedCone(const WeatherSnapshot& weather, const ViewRequest& view, uint32_t minOpaquePixels,
                                  double minPsnrDb, const char* label);
};

// Max difference of two cloud images (premultiplied radiance and alpha, half floats).
double maxCloudDifference(const RenderResult& a, const RenderResult& b)
{
    double worst = 0.0;
    for (size_t i = 0; i < a.cloudRgbaHalf.size(); ++i)
        worst = std::max(worst, std::abs(double(glm::unpackHalf1x16(a.cloudRgbaHalf[i])) -
                                         double(glm::unpackHalf1x16(b.cloudRgbaHalf[i]))));
    return worst;
}

}  // namespace

// Renders `view` with every cone sample marched and with the light volume (160 m texels), and checks
// that the volume was read (the images differ) and that they agree to `minPsnrDb` (cloud image, on the
// marched image's own radiance scale: psnrCloudScaled, so that a brighter light does not read as a worse
// volume).
//
// The limits keep the margins the earlier limits had under the earlier light (octave contribution 0.5, no
// diffuse remainder, sky ambient 0.35 at the base, full ground bounce) on these cloud shapes, carried over
// to the radiance scale, on which a brighter light does not read as a worse volume (the measured figures: BENCHMARKS.md, "Test figures").
void LightVolume::expectMatchesMarchedCone(const WeatherSnapshot& weather, const ViewRequest& view,
                                           uint32_t minOpaquePixels, double minPsnrDb, const char* label)
{
    RenderResult marched = render(weather, view, 0.0);
    RenderResult fromVolume = render(weather, view, 160.0);
    ASSERT_GT(cloudStats(marched).opaquePixels, minOpaquePixels);
    double psnr = psnrCloudScaled(fromVolume, marched);
    double worst = maxCloudDifference(fromVolume, marched);
    std::printf("light volume vs marched cone, %s: PSNR %.2f dB on the radiance scale %.3f (%.2f dB against the "
                "largest channel), max difference %.4f\n",
                label, psnr, radianceScale(marched), psnrCloud(fromVolume, marched), worst);
    EXPECT_GT(worst, 0.0) << "the volume was not read";
    EXPECT_GE(psnr, minPsnrDb);
}

// Scattered cumulus 1-5 km from an eye below them, sun at 35 degrees. The diffuse remainder's k
// (light_cone.glsl) makes the diffusion factor that the volume interpolates over its 160 m texels fall
// faster, so the limit is 0.5 dB under the earlier one; a volume holding optical depth instead of
// transmittance fails it (too dark where texels straddle a cloud edge) (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(LightVolume, CloudsSeenFromBelowMatchTheMarchedCone)
{
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 35.0, "2026-06-21T12:00:00Z");
    v.width = 160;
    v.height = 90;
    v.unixTimeS = timeOfSunElevation(45.0, 7.0, "2026-06-21T12:00:00Z", 35.0);
    expectMatchesMarchedCone(uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2800.0f), v, 500u, 31.0, "from below");
}

// A deck seen from above (an eye at 4000 m over a stratocumulus deck 2-3 km below): the long sample of
// the top layer's cone climbs out of the shell, the volume's top levels must agree (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(LightVolume, DeckSeenFromAboveMatchesTheMarchedCone)
{
    expectMatchesMarchedCone(deckBelowWeather(), deckFromAboveView(), 2000u, 34.7, "from above");
}

// The far cascade (320 m texels, light_volume.h) lights what lies 7.7-15.4 km from the eye: a deck 8-12 km
// below an eye at 10 km, seen 10 degrees down, against every cone sample marched, and against the volume
// without its cascade (which the view must read: the images differ). Without the cascade the picture is
// the marched cone's exactly (all of the deck lies beyond the first 7.7 km). The light tuned to the
// reference is further from the marched cone whatever the texel, more than its brightness explains, so
// the limit is not the one kept from the earlier light (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(LightVolume, FarCascadeMatchesTheMarchedCone)
{
    ViewRequest v = lookUp(45.0, 7.0, 10000.0, -10.0, "2026-06-21T12:00:00Z");
    v.width = 160;
    v.height = 90;
    v.unixTimeS = timeOfSunElevation(45.0, 7.0, "2026-06-21T12:00:00Z", 30.0);
    WeatherSnapshot w = deckBelowWeather();
    setWeather(*renderer, w);
    // Every cone marched in full: beyond 15 km from the eye (most of this deck) a march without the volume
    // takes earlier cones' far samples (RenderTuning::coneTailReuseM), which the cascade holds here.
    RenderTuning everyCone;
    everyCone.coneTailReuseM = 0.0;
    QualitySettings q = testQuality();
    q.lightVolumeTexelM = 0.0;
    RenderResult marched = renderTuned(v, q, everyCone);
    q.lightVolumeTexelM = 160.0;
    RenderResult cascade = renderTuned(v, q, everyCone);
    RenderTuning nearVolumeOnly = everyCone;
    nearVolumeOnly.lightVolumeFarCascade = false;
    RenderResult nearOnly = renderTuned(v, q, nearVolumeOnly);
    ASSERT_GT(cloudStats(marched).opaquePixels, 2000u);
    double psnr = psnrCloudScaled(cascade, marched);
    std::printf("light volume with its far cascade vs marched cone, deck 8-12 km away: PSNR %.2f dB on the "
                "radiance scale %.3f (%.2f dB against the largest channel; without the cascade %.2f dB)\n",
                psnr, radianceScale(marched), psnrCloud(cascade, marched), psnrCloudScaled(nearOnly, marched));
    EXPECT_GT(maxCloudDifference(cascade, nearOnly), 0.0) << "the cascade was not read";
    EXPECT_GE(psnr, 42.3);
}

// The volume is kept while a frame's inputs are those it was built from, and built again when they
// change: a still second frame gives the first frame's bytes, and a view 2 km away, then the first view
// again, give the bytes of renders from a freshly built volume (one kept from the view before would
// light them wrongly).
TEST_F(LightVolume, KeptOnlyWhileItsInputsHold)
{
    WeatherSnapshot w = uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2800.0f);
    setWeather(*renderer, w);
    QualitySettings q = testQuality();
    ViewRequest a = lookUp(45.0, 7.0, 200.0, 35.0, "2026-06-21T15:00:00Z");
    a.width = 96;
    a.height = 54;
    ViewRequest b = a;
    b.pose.lonDeg += 0.025;  // ~2 km east: another corner, other texels
    auto fresh = [&](const ViewRequest& v) {
        renderer->lightVolume.key.valid = false;
        return renderOk(v, q);
    };
    RenderResult first = fresh(a);
    ASSERT_GT(cloudStats(first).opaquePixels, 100u);
    EXPECT_EQ(renderOk(a, q).cloudRgbaHalf, first.cloudRgbaHalf) << "still view";
    RenderResult other = renderOk(b, q);
    EXPECT_NE(other.cloudRgbaHalf, first.cloudRgbaHalf);
    RenderResult again = renderOk(a, q);
    EXPECT_EQ(other.cloudRgbaHalf, fresh(b).cloudRgbaHalf) << "moved view";
    EXPECT_EQ(again.cloudRgbaHalf, first.cloudRgbaHalf) << "back to the first view";
}

// The corner sits on whole texels of the window plane around the eye, whatever the eye's offset.
TEST(LightVolumePlacement, CornerIsOnWholeTexelsAroundTheEye)
{
    QualitySettings q;
    q.lightVolumeTexelM = 160.0;
    q.lightVolumeMinRays = 0;
    for (float offset : {0.0f, 79.9f, 80.1f, -1234.5f, 5000.0f})
    {
        const vec2 eyeOnPlaneM(offset, -0.5f * offset);
        const LightVolumeParams v = placeLightVolume(q, RenderTuning{}, eyeOnPlaneM, true, 0);
        ASSERT_EQ(v.nearCascade.texelM, 160.0f);
        ASSERT_EQ(v.farCascade.texelM, 160.0f * LIGHT_VOLUME_FAR_SCALE) << "the far cascade: 320 m texels";
        for (const LightVolumeCascadeParams& placement : {v.nearCascade, v.farCascade})
            for (int axis = 0; axis < 2; ++axis)
            {
                const double texelM = double(placement.texelM);
                double corner = double(placement.cornerM[axis]);
                double eye = double(eyeOnPlaneM[axis]);
                EXPECT_NEAR(corner / texelM, std::round(corner / texelM), 1e-6) << offset;
                // The eye lies in one of the two middle texels: the volume reaches 7.6-7.7 km to every
                // side (its cascade 15.2-15.4 km).
                double fromCorner = (eye - corner) / texelM;
                EXPECT_GE(fromCorner, 0.5 * LIGHT_VOLUME_SIZE) << offset;
                EXPECT_LT(fromCorner, 0.5 * LIGHT_VOLUME_SIZE + 1.0) << offset;
            }
    }
}

// No volume when there is nothing to hold (no volumetric cloud, every cone sample detailed), when it is
// turned off, and when the frame marches too few rays for its build to pay (1920x1080 reprojected marches
// 130 320 rays, 640x360 reprojected 14 400).
TEST(LightVolumePlacement, AbsentWhenItWouldHoldNothing)
{
    QualitySettings q;
    const vec2 eye(0.0f);
    const uint64_t rays = marchedRays(1920u, 1080u, 4u);
    auto texelM = [&](const QualitySettings& quality, const RenderTuning& tuning, bool cloud, uint64_t n) {
        const LightVolumeParams v = placeLightVolume(quality, tuning, eye, cloud, n);
        return glm::vec2(v.nearCascade.texelM, v.farCascade.texelM);
    };
    EXPECT_GT(texelM(q, RenderTuning{}, true, rays).x, 0.0f) << "defaults: a volume";
    EXPECT_EQ(texelM(q, RenderTuning{}, false, rays).x, 0.0f) << "no volumetric cloud";
    QualitySettings allDetailed = q;
    allDetailed.fullConeSamples = allDetailed.lightSamples;
    EXPECT_EQ(texelM(allDetailed, RenderTuning{}, true, rays).x, 0.0f) << "every cone sample live";
    QualitySettings off = q;
    off.lightVolumeTexelM = 0.0;
    EXPECT_EQ(texelM(off, RenderTuning{}, true, rays).x, 0.0f) << "turned off";
    EXPECT_EQ(texelM(off, RenderTuning{}, true, rays).y, 0.0f) << "no cascade without the volume";
    RenderTuning noCascade;
    noCascade.lightVolumeFarCascade = false;
    EXPECT_GT(texelM(q, noCascade, true, rays).x, 0.0f);
    EXPECT_EQ(texelM(q, noCascade, true, rays).y, 0.0f) << "cascade turned off";
    EXPECT_EQ(texelM(q, RenderTuning{}, true, marchedRays(640u, 360u, 4u)).x, 0.0f) << "640x360 reprojected: 14 400 rays";
    EXPECT_GT(texelM(q, RenderTuning{}, true, marchedRays(640u, 360u, 1u)).x, 0.0f) << "640x360 full: 230 400 rays";
}
