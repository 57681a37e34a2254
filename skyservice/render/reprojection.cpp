// SPDX-License-Identifier: MIT
#include "skyservice/render/reprojection.h"

#include <cmath>

namespace sky
{
namespace
{

// Ordered-dither (Bayer) matrix of size 4 (Bayer 1973): entry k is visited on frame k mod 16.
constexpr uint32_t kBayer4[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};

vec4 v4(const glm::dvec3& v, double w) { return vec4(float(v.x), float(v.y), float(v.z), float(w)); }

}  // namespace

glm::uvec2 reprojectionPhase(uint32_t frameIndex)
{
    uint32_t k = frameIndex % 16u;
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x)
            if (kBayer4[y][x] == k)
                return {x, y};
    return {0, 0};  // unreachable: the matrix holds 0..15
}

bool historyUsable(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera,
                   std::string& why)
{
    const ViewRequest& last = history.lastView;
    if (!history.valid)
        why = "no history";
    else if (last.width != view.width || last.height != view.height || last.fovYDeg != view.fovYDeg)
        why = "image size or field of view changed";
    else if (glm::length(camera.eyeEcefM - history.lastCamera.eyeEcefM) > kReprojectionMaxMoveM)
        why = "eye moved more than the limit";
    else if (glm::dot(camera.enuToEcef * camera.forwardEnu,
                      history.lastCamera.enuToEcef * history.lastCamera.forwardEnu) <
             std::cos(kReprojectionMaxTurnDeg * M_PI / 180.0))
        why = "view turned more than the limit";
    else if (std::llabs(view.unixTimeS - last.unixTimeS) > int64_t(kReprojectionMaxTimeJumpS))
        why = "time jumped more than the limit";
    else
        return true;
    return false;
}

void fillReprojectionParams(FrameParams& frame, const ReprojectionHistory& history, const ViewRequest& view,
                            const CameraFrame& camera, bool useHistory)
{
    glm::uvec2 phase = reprojectionPhase(history.frameIndex);
    frame.reprojection = uvec4(4u, phase.x, phase.y, useHistory ? 1u : 0u);
    frame.previousRight = vec4(0.0f);
    frame.previousUp = vec4(0.0f);
    frame.previousForward = vec4(0.0f);
    frame.previousEye = vec4(0.0f);
    if (!useHistory)
        return;
    // Previous axes and eye in the current ENU frame, in double (DESIGN §4): ENU(prev) -> ECEF -> ENU(now).
    const CameraFrame& prev = history.lastCamera;
    glm::dmat3 ecefToEnu = glm::transpose(camera.enuToEcef);
    glm::dmat3 prevToNow = ecefToEnu * prev.enuToEcef;
    double tanHalf = std::tan(history.lastView.fovYDeg * M_PI / 360.0);
    double aspect = double(view.width) / double(view.height);
    frame.previousRight = v4(prevToNow * prev.rightEnu, tanHalf * aspect);
    frame.previousUp = v4(prevToNow * prev.upEnu, tanHalf);
    frame.previousForward = v4(prevToNow * prev.forwardEnu, 0.0);
    frame.previousEye = v4(ecefToEnu * (prev.eyeEcefM - camera.eyeEcefM), 0.0);
}

}  // namespace sky
