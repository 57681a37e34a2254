// SPDX-License-Identifier: MIT
// The per-frame uniforms (skyservice/render/frame_setup.cpp): clouds must be fixed to the earth (and
// drift only with the wind), whatever the eye does: the noise lookup position of a fixed point must not
// depend on where the eye is.
#include "skyservice/render/frame_setup.h"

#include <GeographicLib/Geocentric.hpp>
#include <cmath>
#include <gtest/gtest.h>

using namespace sky;

namespace
{

// Noise-space position (metres, modulo the offset period) of the ECEF point `pointEcef` seen from `pose`.
glm::dvec3 noisePosition(const EyePose& pose, const glm::dvec3& pointEcef, double animationS, const glm::dmat3& drift)
{
    CameraFrame cam = computeCameraFrame(pose);
    SunMoon sm{};
    WeatherWindow window;
    window.halfExtentM = 800000.0;
    WindowSummary summary;
    summary.layers[0].minBaseM = 1000.0f;
    summary.layers[0].maxTopM = 3000.0f;
    summary.layers[0].meanWindEnuMS = glm::dvec2(7.0, -3.0);
    ViewRequest request;
    request.pose = pose;
    QualitySettings quality;
    FrameInputs in;
    in.camera = &cam;
    in.sunMoon = &sm;
    in.window = &window;
    in.summary = &summary;
    in.request = &request;
    in.quality = &quality;
    in.animationTimeS = animationS;
    in.driftEnuToEcef = drift;
    FrameParams f = makeFrameParams(in);
    // What the shader does: rotate the eye-relative ENU offset into earth-fixed axes, add the offset.
    glm::dvec3 enu = glm::transpose(cam.enuToEcef) * (pointEcef - cam.eyeEcefM);
    glm::dvec3 rotated(glm::dot(glm::dvec3(f.enuToEcef.row0), enu), glm::dot(glm::dvec3(f.enuToEcef.row1), enu),
                       glm::dot(glm::dvec3(f.enuToEcef.row2), enu));
    glm::dvec3 p = rotated + glm::dvec3(f.layers[0].noiseOffsetM);
    double m = noiseOffsetModulusM(quality);
    return glm::dvec3(std::fmod(p.x + 10 * m, m), std::fmod(p.y + 10 * m, m), std::fmod(p.z + 10 * m, m));
}

double wrappedDistance(const glm::dvec3& a, const glm::dvec3& b, double m)
{
    glm::dvec3 d = glm::abs(a - b);
    d = glm::min(d, glm::dvec3(m) - d);
    return glm::length(d);
}

}  // namespace

// Regression: the wind drift was turned into earth-fixed axes at the eye, so with hours of drift a 5 m
// move of the eye slid the clouds by kilometres (found by the reprojection tests).
TEST(FrameSetup, CloudsStayFixedToTheEarthWhenTheEyeMoves)
{
    const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
    double x, y, z;
    earth.Forward(45.2, 7.3, 2000.0, x, y, z);
    glm::dvec3 point(x, y, z);
    const glm::dmat3 drift = computeCameraFrame(EyePose{45.0, 7.0, 0.0, 0.0, 0.0, 0.0}).enuToEcef;
    const double m = noiseOffsetModulusM(QualitySettings{});
    for (double animation : {0.0, 3.0 * 3600.0, 1.7e9})
    {
        glm::dvec3 a = noisePosition({45.0, 7.0, 1500.0, 0.0, 0.0, 0.0}, point, animation, drift);
        glm::dvec3 b = noisePosition({45.0, 7.0001, 1500.0, 30.0, 5.0, 0.0}, point, animation, drift);    // 8 m east
        glm::dvec3 c = noisePosition({45.6, 8.2, 11000.0, 200.0, -3.0, 10.0}, point, animation, drift);  // 100 km away
        // Float32 offsets and rotation rows: ~0.5 m at these distances is the budget.
        EXPECT_LT(wrappedDistance(a, b, m), 0.5) << "animation " << animation;
        EXPECT_LT(wrappedDistance(a, c, m), 1.0) << "animation " << animation;
    }
    // And the wind does move them: one hour of 7.6 m/s is ~27 km of drift (modulo the period).
    glm::dvec3 now = noisePosition({45.0, 7.0, 1500.0, 0.0, 0.0, 0.0}, point, 0.0, drift);
    glm::dvec3 later = noisePosition({45.0, 7.0, 1500.0, 0.0, 0.0, 0.0}, point, 60.0, drift);
    EXPECT_NEAR(wrappedDistance(now, later, m), 60.0 * std::hypot(7.0, 3.0), 1.0);
}
