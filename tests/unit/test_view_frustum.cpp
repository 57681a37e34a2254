// SPDX-License-Identifier: MIT
// Off-centre frusta (skyservice/render/view_frustum.h) in the frame's uniforms: the rays that
// shaders/clouds/view_ray.glsl makes of them reach the frustum's edges, and the previous camera's
// projection (reconstruct.comp.glsl projectPrevious, fed by reprojectionParams) takes each pixel's
// ray back to its pixel; a changed frustum drops the history; bad angles are named. In a turn, the
// columns the previous frame did not see (findNewColumns, marched in full) are those whose rays that
// projection takes off the previous image.
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/reprojection.h"
#include "skyservice/render/view_frustum.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace sky;

namespace
{

glm::dvec3 xyz(const vec3& v) { return glm::dvec3(v.x, v.y, v.z); }

FrameParams frameFor(const CameraFrame& cam, const ViewRequest& request)
{
    static const SunMoon sm{};
    static const WeatherWindow window;
    static const WindowSummary summary;
    static const QualitySettings quality;
    FrameInputs in;
    in.camera = &cam;
    in.sunMoon = &sm;
    in.window = &window;
    in.summary = &summary;
    in.request = &request;
    in.quality = &quality;
    return makeFrameParams(in);
}

// viewRayDirection of view_ray.glsl, in double on the float uniforms.
glm::dvec3 viewRay(const FrameParams& f, double xPx, double yPx)
{
    const double nx = xPx / f.image.widthPx * 2.0 - 1.0, ny = yPx / f.image.heightPx * 2.0 - 1.0;
    return glm::normalize(xyz(f.camera.centreRayEnu) + nx * double(f.camera.halfWidthTan) * xyz(f.camera.rightEnu) -
                          ny * double(f.camera.halfHeightTan) * xyz(f.camera.upEnu));
}

// projectPrevious of reconstruct.comp.glsl: pixel coordinates of direction `v` in the previous image.
glm::dvec2 projectPrevious(const FrameParams& f, const glm::dvec3& v)
{
    const PreviousCameraParams& p = f.reprojection.previous;
    const double z = glm::dot(v, xyz(p.forwardEnu));
    const glm::dvec2 ndc(glm::dot(v, xyz(p.rightEnu)) / (z * double(p.halfWidthTan)),
                         -glm::dot(v, xyz(p.upEnu)) / (z * double(p.halfHeightTan)));
    return (ndc + 1.0) * 0.5 * glm::dvec2(f.image.widthPx, f.image.heightPx);
}

double tanDeg(double deg) { return std::tan(deg * M_PI / 180.0); }

ViewRequest offCentre()
{
    ViewRequest v;
    v.pose = EyePose{45.0, 7.0, 2000.0, 30.0, 5.0, 10.0};
    v.width = 96;
    v.height = 48;
    v.frustum = Frustum{true, 40.0, -10.0, 12.0, 18.0};  // wholly left of the axis: 40 to 10 degrees left of it
    return v;
}

}  // namespace

TEST(ViewFrustum, EdgeRaysLieAtTheHalfAngles)
{
    const ViewRequest request = offCentre();
    const CameraFrame cam = computeCameraFrame(request.pose);
    const FrameParams f = frameFor(cam, request);
    // Tangents of a ray along the camera's own axes.
    auto tangents = [&](const glm::dvec3& d) {
        const double z = glm::dot(d, cam.forwardEnu);
        return glm::dvec2(glm::dot(d, cam.rightEnu) / z, glm::dot(d, cam.upEnu) / z);
    };
    const double w = request.width, h = request.height;
    EXPECT_NEAR(tangents(viewRay(f, 0.0, h / 2)).x, -tanDeg(40.0), 1e-6) << "left edge";
    EXPECT_NEAR(tangents(viewRay(f, w, h / 2)).x, tanDeg(-10.0), 1e-6) << "right edge";
    EXPECT_NEAR(tangents(viewRay(f, w / 2, 0.0)).y, tanDeg(12.0), 1e-6) << "upper edge";
    EXPECT_NEAR(tangents(viewRay(f, w / 2, h)).y, -tanDeg(18.0), 1e-6) << "lower edge";
    // The world jitter's texel is a pixel's height at the axis.
    EXPECT_NEAR(f.march.jitterTexelRad, (tanDeg(12.0) + tanDeg(18.0)) / h, 1e-7);
}

TEST(ViewFrustum, ThePreviousCameraProjectsEachRayBackToItsPixel)
{
    const ViewRequest request = offCentre();
    const CameraFrame cam = computeCameraFrame(request.pose);
    FrameParams f = frameFor(cam, request);
    ReprojectionHistory history;
    history.valid = true;
    history.lastView = request;
    history.lastCamera = cam;
    std::string why;
    ASSERT_TRUE(historyUsable(history, request, cam, why)) << why;
    f.reprojection = reprojectionParams(history, request, cam, true);
    double worst = 0.0;
    for (double y : {0.5, 11.5, 24.0, 47.5})
        for (double x : {0.5, 30.25, 48.0, 95.5})
            worst = std::max(worst, glm::length(projectPrevious(f, viewRay(f, x, y)) - glm::dvec2(x, y)));
    EXPECT_LT(worst, 1e-3) << "pixels";
    // Without the shifted right axis the centre would land tens of pixels off: the check can fail.
    FrameParams centred = f;
    centred.reprojection.previous.rightEnu = glm::vec3(cam.rightEnu);
    EXPECT_GT(glm::length(projectPrevious(centred, viewRay(f, 48.0, 24.0)) - glm::dvec2(48.0, 24.0)), 10.0);
}

TEST(ViewFrustum, AChangedFrustumDropsTheHistory)
{
    const ViewRequest request = offCentre();
    const CameraFrame cam = computeCameraFrame(request.pose);
    ReprojectionHistory history;
    history.valid = true;
    history.lastView = request;
    history.lastCamera = cam;
    std::string why;
    ViewRequest changed = request;
    changed.frustum.downDeg += 0.5;
    EXPECT_FALSE(historyUsable(history, changed, cam, why));
    EXPECT_NE(why.find("field of view"), std::string::npos) << why;
    ViewRequest symmetric = request;
    symmetric.frustum.asymmetric = false;
    EXPECT_FALSE(historyUsable(history, symmetric, cam, why));
    ViewRequest otherFov = request;
    otherFov.fovYDeg += 10.0;  // ignored while the frustum is asymmetric
    EXPECT_TRUE(historyUsable(history, otherFov, cam, why)) << why;
}

TEST(ViewFrustum, BadAnglesAreNamed)
{
    std::string error;
    EXPECT_TRUE(validateFrustum(Frustum{true, 40.0, -10.0, 12.0, 18.0}, error));
    EXPECT_TRUE(validateFrustum(Frustum{false, 0, 0, 0, 0}, error)) << "a symmetric view has no angles";
    EXPECT_FALSE(validateFrustum(Frustum{true, 85.0, 0.0, 10.0, 10.0}, error));
    EXPECT_NE(error.find("left"), std::string::npos) << error;
    EXPECT_FALSE(validateFrustum(Frustum{true, 10.0, 10.0, 10.0, std::nan("")}, error));
    EXPECT_NE(error.find("down"), std::string::npos) << error;
    EXPECT_FALSE(validateFrustum(Frustum{true, 10.0, -9.5, 10.0, 10.0}, error));
    EXPECT_NE(error.find("left + right"), std::string::npos) << error;
    EXPECT_FALSE(validateFrustum(Frustum{true, 10.0, 10.0, -30.0, 30.5}, error));
    EXPECT_NE(error.find("up + down"), std::string::npos) << error;
}

namespace
{

// The history of one reprojected frame of `request` (block 4), as the renderer keeps it.
ReprojectionHistory historyOf(const ViewRequest& request)
{
    ReprojectionHistory history;
    history.valid = true;
    history.lastView = request;
    history.lastCamera = computeCameraFrame(request.pose);
    history.block.blockPx = 4;
    return history;
}

// The lines `view` marches in full after `history`'s frame, and with `f` the frame parameters that carry them.
NewLines newLinesAfter(const ReprojectionHistory& history, const ViewRequest& view, FrameParams* f = nullptr)
{
    const CameraFrame cam = computeCameraFrame(view.pose);
    ReprojectionHistory h = history;
    h.newLines = findNewLines(h, view, cam);
    if (f)
    {
        *f = frameFor(cam, view);
        f->reprojection = reprojectionParams(h, view, cam, true);
    }
    return h.newLines;
}

}  // namespace

// A right turn of one degree brings new columns in at the right border, a left turn at the left one; the
// band ends where the previous image begins (the projection above: the first column inside it has all
// three rays on the previous image, the band's last one not); a large turn is capped, no turn or a block
// of 1 marches none; the band reaches the shader in frame.reprojection.newLines.
TEST(ViewFrustum, ATurnMarchesTheColumnsThePreviousFrameDidNotSee)
{
    for (bool asymmetric : {false, true})
    {
        ViewRequest request = offCentre();
        request.frustum.asymmetric = asymmetric;
        request.fovYDeg = 40.0;
        ReprojectionHistory history = historyOf(request);
        auto turned = [&](double deg, FrameParams* f = nullptr) {
            ViewRequest v = request;
            v.pose.headingDeg += deg;
            return newLinesAfter(history, v, f).columns;
        };
        FrameParams f;
        const LineBand right = turned(1.0, &f);
        ASSERT_GT(right.count, 0u) << asymmetric;
        EXPECT_EQ(right.first + right.count, request.width);
        EXPECT_EQ(f.reprojection.newLines.firstColumn, right.first);
        EXPECT_EQ(f.reprojection.newLines.columnCount, right.count);
        auto inside = [&](double x) {
            bool all = true;
            for (double y : {0.5, 24.0, 47.5})
            {
                const double q = projectPrevious(f, viewRay(f, x, y)).x;
                all = all && q >= 0.0 && q < request.width;
            }
            return all;
        };
        EXPECT_TRUE(inside(right.first - 0.5)) << "the column before the band was seen";
        EXPECT_FALSE(inside(right.first + 0.5)) << "the band's first column was not";
        const LineBand left = turned(-1.0);
        EXPECT_EQ(left.first, 0u);
        EXPECT_GT(left.count, 0u);
        EXPECT_EQ(turned(0.0).count, 0u);
        EXPECT_EQ(turned(20.0).count, maxNewColumns(request.width));
        history.block.blockPx = 1;
        EXPECT_EQ(turned(1.0).count, 0u);
    }
}

// A pitch change brings new rows in: nose up at the top, nose down at the bottom; the band ends where the
// previous image begins (the first row inside it has its left, middle and right rays on the previous
// image, the band's last one not); a large change is capped; the band reaches the shader in frame.reprojection.newLines.
TEST(ViewFrustum, APitchChangeMarchesTheRowsThePreviousFrameDidNotSee)
{
    for (bool asymmetric : {false, true})
    {
        ViewRequest request = offCentre();
        request.frustum.asymmetric = asymmetric;
        request.fovYDeg = 40.0;
        const ReprojectionHistory history = historyOf(request);
        auto pitched = [&](double deg, FrameParams* f = nullptr) {
            ViewRequest v = request;
            v.pose.pitchDeg += deg;
            return newLinesAfter(history, v, f).rows;
        };
        FrameParams f;
        const LineBand up = pitched(1.0, &f);
        ASSERT_GT(up.count, 0u) << asymmetric;
        EXPECT_EQ(up.first, 0u);
        EXPECT_EQ(f.reprojection.newLines.firstRow, up.first);
        EXPECT_EQ(f.reprojection.newLines.rowCount, up.count);
        auto inside = [&](double y) {
            bool all = true;
            for (double x : {0.5, 48.0, 95.5})
            {
                const double q = projectPrevious(f, viewRay(f, x, y)).y;
                all = all && q >= 0.0 && q < request.height;
            }
            return all;
        };
        EXPECT_TRUE(inside(up.count + 0.5)) << "the row after the band was seen";
        EXPECT_FALSE(inside(up.count - 0.5)) << "the band's last row was not";
        const LineBand down = pitched(-1.0);
        EXPECT_EQ(down.first + down.count, request.height);
        EXPECT_GT(down.count, 0u);
        EXPECT_EQ(pitched(0.0).count, 0u);
        EXPECT_EQ(pitched(20.0).count, maxNewRows(request.height));
    }
}
