// SPDX-License-Identifier: MIT
// The real-time lighting against the reference path tracer on the look views (look_views.h; built-in cumulus,
// base 1200 m, 44.3 N 7.5 E, midsummer noon): from below at 500 m looking up 10 deg, and from above at
// 4000 m looking down 15 deg. The reference is rendered here at a small size and few samples per pixel;
// the statistics are means (tests/gpu/look_stats.h), which few samples leave unbiased where the median of a
// path-traced image creeps up with the samples. Unbiased is not enough under the bases: there most paths carry
// almost nothing and a few carry much, so a sum of few samples mostly falls short. The reference's underside/
// top ratio of means from below was 0.281 at 8 samples, 0.316 at 16, 0.376 at 32 and 0.407 at 64; the
// view from below takes 32 (a lavapipe test's limit). sky-reference-looks prints the medians at more samples.
#include "skyservice/app/look_views.h"
#include "skyservice/render/reference_renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/look_stats.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace sky;

namespace
{

struct Pair
{
    testscenes::LookStats realTime, reference;
};

class ReferenceLooks : public ::testing::Test
{
protected:
    static void SetUpTestSuite()
    {
        renderer_ = new Renderer();
        RendererOptions options;
        options.context.quiet = true;
        status_ = createRenderer(*renderer_, options);
        if (status_.ok())
            status_ = createReferenceRenderer(*renderer_, reference_);
        if (status_.ok())
            setWeather(*renderer_, makeBuiltinWeather(0));
    }
    static void TearDownTestSuite()
    {
        destroyReferenceRenderer(*renderer_, reference_);
        destroyRenderer(*renderer_);
        delete renderer_;
    }

    static Pair render(double altM, double pitchDeg, uint32_t samplesPerPixel)
    {
        ViewRequest view = testscenes::lookUp(44.3, 7.5, altM, pitchDeg, "2026-06-21T12:00:00Z");
        view.width = 48;
        view.height = 27;
        const QualitySettings quality = testscenes::testQuality();
        ReferenceSettings settings;
        settings.samplesPerPixel = samplesPerPixel;
        RenderResult realTime, path;
        SkyStatus s = renderView(*renderer_, view, quality, realTime);
        EXPECT_TRUE(s.ok()) << s.message;
        s = renderReference(*renderer_, reference_, view, quality, settings, path);
        EXPECT_TRUE(s.ok()) << s.message;
        EXPECT_EQ(reference_.last.pathsTruncated, 0u);
        Pair p{testscenes::measureLook(view, realTime), testscenes::measureLook(view, path)};
        std::printf("cloud pixels %zu / %zu; mean luminance %.4f / %.4f (real time / reference); underside/top of "
                    "means %.3f / %.3f; medians %.4f / %.4f\n",
                    p.realTime.cloudPixels, p.reference.cloudPixels, p.realTime.meanLuminance,
                    p.reference.meanLuminance, p.realTime.undersideOverTopOfMeans, p.reference.undersideOverTopOfMeans,
                    p.realTime.medianLuminance, p.reference.medianLuminance);
        return p;
    }

    // The look sheet's cumulus from above (skyservice/app/look_views.h) at a small size, path-traced.
    static SkyStatus renderAbove(const ReferenceSettings& settings, uint32_t width, uint32_t height)
    {
        const ViewRequest view = lookViewRequest(*findLookView(lookViews(), "look-cumulus-above"), width, height);
        RenderResult path;
        return renderReference(*renderer_, reference_, view, testscenes::testQuality(), settings, path);
    }

    static Renderer* renderer_;
    static ReferenceRenderer reference_;
    static SkyStatus status_;
};

Renderer* ReferenceLooks::renderer_ = nullptr;
ReferenceRenderer ReferenceLooks::reference_;
SkyStatus ReferenceLooks::status_;

// From below the undersides are dark grey and the sunlit towers bright: the real-time ratio of the lowest
// fifth of the cloud pixels to the highest stays near the reference's (~0.2; before the ambient and
// octave-tail changes of cloud_lighting.glsl it was ~1: undersides as bright as the towers), and so does
// the brightness of the clouds.
TEST_F(ReferenceLooks, UnderCumulusAtNoonMatchesThePathTracedReference)
{
    ASSERT_TRUE(status_.ok()) << status_.message;
    const Pair p = render(500.0, 10.0, 32u);
    ASSERT_GT(p.reference.cloudPixels, 100u);
    ASSERT_GT(p.realTime.cloudPixels, 100u);
    EXPECT_NEAR(p.realTime.meanLuminance / p.reference.meanLuminance, 1.0, 0.25);
    EXPECT_NEAR(p.realTime.undersideOverTopOfMeans / p.reference.undersideOverTopOfMeans, 1.0, 0.35);
    EXPECT_LT(p.realTime.undersideOverTopOfMeans, 0.5);
}

// From above the sunlit tops and sides: as bright as the reference's (the octaves alone were 2-3x too dark).
TEST_F(ReferenceLooks, CumulusFromAboveMatchesThePathTracedReference)
{
    ASSERT_TRUE(status_.ok()) << status_.message;
    const Pair p = render(4000.0, -15.0, 4u);
    ASSERT_GT(p.reference.cloudPixels, 100u);
    ASSERT_GT(p.realTime.cloudPixels, 100u);
    EXPECT_NEAR(p.realTime.meanLuminance / p.reference.meanLuminance, 1.0, 0.25);
    EXPECT_NEAR(p.realTime.undersideOverTopOfMeans / p.reference.undersideOverTopOfMeans, 1.0, 0.35);
}

// Sunset behind cumulus (the look sheet's view: 800 m, towards a sun 3 degrees up): the light reaching the
// clouds has crossed tens of kilometres of the field, which the light cone (~4 km) does not see; the far
// shadow (shaders/clouds/far_shadow.glsl) stands for it. Without it the real-time clouds were ~6x as bright
// as the reference's, their bases golden (mean 0.46 vs 0.10 here; with it 0.083).
TEST_F(ReferenceLooks, SunsetBehindCumulusIsAsDarkAsThePathTracedReference)
{
    ASSERT_TRUE(status_.ok()) << status_.message;
    const LookView& look = *findLookView(lookViews(), "look-sunset-cumulus");
    const ViewRequest view = lookViewRequest(look, 64, 36);
    setWeather(*renderer_, makeBuiltinWeather(look.unixTimeS));
    const QualitySettings quality = testscenes::testQuality();
    ReferenceSettings settings;
    settings.samplesPerPixel = 8;
    RenderResult realTime, path;
    SkyStatus s = renderView(*renderer_, view, quality, realTime);
    ASSERT_TRUE(s.ok()) << s.message;
    s = renderReference(*renderer_, reference_, view, quality, settings, path);
    setWeather(*renderer_, makeBuiltinWeather(0));
    ASSERT_TRUE(s.ok()) << s.message;
    const testscenes::LookStats rt = testscenes::measureLook(view, realTime);
    const testscenes::LookStats ref = testscenes::measureLook(view, path);
    std::printf("sunset: cloud pixels %zu / %zu; mean luminance %.4f / %.4f (real time / reference)\n", rt.cloudPixels,
                ref.cloudPixels, rt.meanLuminance, ref.meanLuminance);
    ASSERT_GT(ref.cloudPixels, 100u);
    ASSERT_GT(rt.cloudPixels, 100u);
    EXPECT_NEAR(rt.meanLuminance / ref.meanLuminance, 1.0, 0.35);
}

// Regression: from above, a stretch step of a path beyond 262 km (where t + 1 cm rounds to t) could stand
// still and find the same stretch again forever, and a ray leaving a cloud through its base was given a stretch
// through the earth to the distance limit (reference_media.glsl minimumAdvance, shell.glsl). The view finishes
// below its dispatch bound with every sample traced, in ~2100 steps a path (lavapipe, 64x36, 2 samples).
TEST_F(ReferenceLooks, CumulusFromAboveFinishesWithBoundedWork)
{
    ASSERT_TRUE(status_.ok()) << status_.message;
    ReferenceSettings settings;
    settings.samplesPerPixel = 2;
    const SkyStatus s = renderAbove(settings, 64, 36);
    ASSERT_TRUE(s.ok()) << s.message;
    const ReferenceStats& st = reference_.last;
    std::printf("dispatches %u of %u; paths %llu, cut %llu; steps %llu (%.0f a path); stretches skipped %llu\n",
                st.dispatches, st.maxDispatches, (unsigned long long)st.paths, (unsigned long long)st.pathsCut,
                (unsigned long long)st.steps, double(st.steps) / double(std::max<uint64_t>(st.paths, 1)),
                (unsigned long long)st.stretchesSkipped);
    EXPECT_EQ(st.pathsCut, 0u);
    EXPECT_EQ(st.paths, 64u * 36u * 2u);
    EXPECT_LT(st.dispatches, st.maxDispatches / 2);
    EXPECT_LT(double(st.steps) / double(st.paths), 10000.0);
    EXPECT_GT(st.stretchesSkipped, 0u);
}

// The dispatch bound ends a render that has not finished, with the samples done so far, and counts the rest.
TEST_F(ReferenceLooks, DispatchBoundEndsTheRenderAndCountsTheSamplesCut)
{
    ASSERT_TRUE(status_.ok()) << status_.message;
    ReferenceSettings settings;
    settings.samplesPerPixel = 8;
    settings.maxDispatches = 1;
    const SkyStatus s = renderAbove(settings, 32, 18);
    ASSERT_TRUE(s.ok()) << s.message;
    const ReferenceStats& st = reference_.last;
    EXPECT_EQ(st.dispatches, 1u);
    EXPECT_GT(st.pathsCut, 0u);
    EXPECT_GT(st.paths, 0u);
    EXPECT_EQ(st.paths + st.pathsCut, 32u * 18u * 8u);
}

}  // namespace
