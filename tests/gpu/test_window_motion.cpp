// SPDX-License-Identifier: MIT
// The weather window for a moving eye (skyservice/weather/window_lattice.h, weather/window_provider.h), on
// the GPU (lavapipe, validation on, small images, test quality):
//  - an eye that crosses the edge of a lattice cell (its window is re-centred 2.2 km away) sees its
//    clouds where it saw them a few metres before: the shaders place the eye on the window correctly;
//  - a flight makes every window after the first on the worker thread, ahead of the eye, and the frames
//    it renders are byte for byte those of one-shot renders at the same poses (no dependence on timing).
#include "skyservice/render/renderer.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class WindowMotion : public GpuFixture
{
protected:
    RenderResult render(const ViewRequest& view)
    {
        RenderResult result;
        SkyStatus s = renderView(*renderer, view, testQuality(), result);
        EXPECT_TRUE(s.ok()) << s.message;
        return result;
    }
};

// Looking north-east at one cumulus cell ~7.9 km away from inside the layer's altitude range: a window
// placed 2.2 km wrong would move the cell by ~10 degrees on the screen.
ViewRequest cellView(double eyeLatDeg)
{
    ViewRequest v = lookUp(eyeLatDeg, 7.0, 2000.0, 0.0, "2026-06-21T12:00:00Z");
    v.pose.headingDeg = 45.0;
    v.fovYDeg = 40.0;
    v.width = 96;
    v.height = 54;
    return v;
}

}  // namespace

TEST_F(WindowMotion, CrossingACellEdgeMovesNoCloud)
{
    // 45.01 deg is the edge between lattice rows 2250 and 2251 (0.02 deg apart).
    setWeather(*renderer, isolatedCell(45.06, 7.07, 1500.0, CloudType::Cumulus, 1500.0f, 2600.0f));
    const double lats[3] = {45.0097, 45.0099, 45.0101};  // 22 m apart; the last is in the next cell
    CloudCentroid c[3];
    for (int i = 0; i < 3; ++i)
    {
        RenderResult r = render(cellView(lats[i]));
        c[i] = cloudCentroid(r, 0.3f);
        ASSERT_GT(c[i].pixels, 20u) << "the cell is not in view from " << lats[i];
    }
    WindowCentre a = windowCentreForEye(lats[1], 7.0), b = windowCentreForEye(lats[2], 7.0);
    ASSERT_FALSE(a == b);
    double sameCellPx = std::hypot(c[1].xPx - c[0].xPx, c[1].yPx - c[0].yPx);
    double acrossPx = std::hypot(c[2].xPx - c[1].xPx, c[2].yPx - c[1].yPx);
    std::printf("cell centroid moves %.3f px within a cell, %.3f px across the edge (22 m each)\n", sameCellPx,
                acrossPx);
    // 22 m toward a cloud 7.9 km away moves it by < 0.2 px. Across the edge the window is resampled on
    // texels (~1 km) shifted by a fraction of a texel, which moves the outline of the 1.5 km cell a
    // little: measured 0.64 px (~60 m at 7.9 km; 0.39 px for a 3 km cell). A 54-row image at 40 degrees
    // has 1.35 px per degree: a window misplaced by its 2.2 km re-centring would move the cell > 10 px.
    EXPECT_LT(sameCellPx, 0.5);
    EXPECT_LT(acrossPx, 1.5);
}

TEST_F(WindowMotion, FlightMakesItsWindowsAheadOfTheEyeAndTheFramesDoNotDependOnIt)
{
    setWeather(*renderer, isolatedCell(45.06, 7.07, 1500.0, CloudType::Cumulus, 1500.0f, 2600.0f));
    const WindowPrefetch& p = renderer->weather.prefetch;
    const uint64_t madeBefore = p.madeOnFrame, usedBefore = p.used;
    // North at 300 m per frame (250 m/s at ~1 frame per 1.2 s; the window logic only sees the motion per
    // frame) for 30 frames: 9 km, four cell edges.
    ViewRequest v = cellView(44.99);
    v.width = 48;
    v.height = 27;
    const double stepDeg = 300.0 / 111132.0;  // metres per degree of latitude at 45 N (Torge)
    RenderResult last;
    ViewRequest lastView;
    int edges = 0;
    for (int k = 0; k < 30; ++k)
    {
        ViewRequest f = v;
        f.pose.latDeg = v.pose.latDeg + k * stepDeg;
        if (k > 0 && !(windowCentreForEye(f.pose.latDeg, 7.0) == windowCentreForEye(lastView.pose.latDeg, 7.0)))
            ++edges;
        last = render(f);
        lastView = f;
    }
    std::printf("%d cell edges crossed; windows made on the frame path %llu, on the worker thread and used %llu\n",
                edges, (unsigned long long)(p.madeOnFrame - madeBefore), (unsigned long long)(p.used - usedBefore));
    EXPECT_GE(edges, 3);
    EXPECT_EQ(p.madeOnFrame - madeBefore, 1u);  // the first frame only (the eye arrived from elsewhere)
    EXPECT_EQ(p.used - usedBefore, uint64_t(edges));

    // The window a frame used during the flight was made on the worker; the same pose rendered after a
    // jump far away makes it on the frame path: the bytes are the same.
    render(cellView(10.0));
    RenderResult again = render(lastView);
    EXPECT_EQ(again.displayRgba8, last.displayRgba8);
    EXPECT_EQ(again.cloudRgbaHalf, last.cloudRgbaHalf);
}
