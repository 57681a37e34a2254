// SPDX-License-Identifier: MIT
#include "skyservice/render/reprojection.h"

#include "skyservice/render/view_frustum.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace sky
{
namespace
{

// Ordered-dither (Bayer) matrices of size 4 and 2 (Bayer 1973): entry k is visited on frame k mod n^2.
constexpr uint32_t kBayer4[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
constexpr uint32_t kBayer2[2][2] = {{0, 2}, {3, 1}};

}  // namespace

glm::uvec2 reprojectionPhase(uint32_t frameIndex, uint32_t blockPx)
{
    if (blockPx == 2)
    {
        uint32_t k = frameIndex % 4u;
        for (uint32_t y = 0; y < 2; ++y)
            for (uint32_t x = 0; x < 2; ++x)
                if (kBayer2[y][x] == k)
                    return {x, y};
    }
    if (blockPx != 4)
        return {0, 0};  // block 1: every pixel
    uint32_t k = frameIndex % 16u;
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x)
            if (kBayer4[y][x] == k)
                return {x, y};
    return {0, 0};  // unreachable: the matrix holds 0..15
}

MarchBlock chooseMarchBlock(const WeatherWindow& window, double eyeAltitudeM, const glm::dvec2& eyeOnWindowM,
                            uint32_t insideBlockPx)
{
    MarchBlock best;
    bool bestInside = false;
    if (window.sizeTexels == 0 || window.texels.empty())
        return best;
    // Texels whose true position lies within the radius of the eye (the warp makes the texels near the
    // centre ~1 km), and always the four around the eye (a window without warp has texels larger than
    // the radius). The eye's texel: its warped plane position in texel units.
    const int64_t n = int64_t(window.sizeTexels);
    const glm::dvec2 q = windowWarpM(eyeOnWindowM, window.halfExtentM, window.warpRadiusM) / window.texelSizeM +
                         0.5 * double(n) - 0.5;
    const int64_t ci = int64_t(std::floor(q.x)), cj = int64_t(std::floor(q.y));  // the texel centre below-left
    const int64_t reach = 8;  // texels searched on each side of the eye; more than 2 km at any warp
    char text[160];
    for (uint32_t k = 0; k < MAX_CLOUD_LAYERS; ++k)
    {
        float coverage = 0.0f;
        double base = 1e30, top = -1e30;
        for (int64_t j = std::max<int64_t>(0, cj - reach); j < std::min(n, cj + reach + 1); ++j)
            for (int64_t i = std::max<int64_t>(0, ci - reach); i < std::min(n, ci + reach + 1); ++i)
            {
                bool aroundEye = (i == ci || i == ci + 1) && (j == cj || j == cj + 1);
                const glm::dvec2 p = window.texelPositionM(uint32_t(i), uint32_t(j));
                if (!aroundEye && glm::length(p - eyeOnWindowM) > kNearCloudRadiusM)
                    continue;
                const glm::vec4& t = window.at(2 * k, uint32_t(i), uint32_t(j));
                if (!(t.x > kNearCloudMinCoverage))
                    continue;
                coverage = std::max(coverage, t.x);
                base = std::min(base, double(t.y));
                top = std::max(top, double(t.z));
            }
        if (coverage <= 0.0f)
            continue;
        uint32_t block = 4;
        const bool inside = eyeAltitudeM >= base && eyeAltitudeM <= top;
        const bool overcast = coverage >= kOvercastCoverage;
        if (inside)
            block = overcast ? std::clamp(insideBlockPx, 1u, 2u) : 1u;
        else if (eyeAltitudeM >= base - kNearCloudM && eyeAltitudeM <= top + kNearCloudM)
            block = 2;
        // The smallest block wins; at the same block, being inside a layer names the reason.
        const bool better = block < best.blockPx || (block == best.blockPx && block < 4 && inside && !bestInside);
        if (!better)
            continue;
        bestInside = inside;
        std::snprintf(text, sizeof text, "eye %s cloud layer %u (%.0f-%.0f m, coverage %.2f)",
                      inside ? (overcast ? "inside overcast" : "inside") : "near", k, base, top, double(coverage));
        best.blockPx = block;
        best.reason = text;
    }
    return best;
}

bool historyUsable(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera,
                   std::string& why)
{
    const ViewRequest& last = history.lastView;
    if (!history.valid)
        why = "no history";
    else if (!sameProjection(last, view))
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

namespace
{

// The previous camera's axes in the current ENU frame, in double (docs/datums.md): ENU(prev) -> ECEF ->
// ENU(now). An off-centre frustum: the tangent x of a direction is measured from the image centre,
// x - centreX = dot(v, right - centreX * forward) / dot(v, forward), so the shifted axes project with
// the centred formula (reconstruct.comp.glsl projectPrevious). A centred one keeps the axes untouched.
struct PreviousAxes
{
    glm::dvec3 right, up, forward;
};

PreviousAxes previousAxes(const ReprojectionHistory& history, const ViewTangents& t, const CameraFrame& camera)
{
    const CameraFrame& prev = history.lastCamera;
    const glm::dmat3 prevToNow = glm::transpose(camera.enuToEcef) * prev.enuToEcef;
    glm::dvec3 right = prev.rightEnu, up = prev.upEnu;
    if (t.centreX != 0.0 || t.centreY != 0.0)
    {
        right -= t.centreX * prev.forwardEnu;
        up -= t.centreY * prev.forwardEnu;
    }
    return {prevToNow * right, prevToNow * up, prevToNow * prev.forwardEnu};
}

}  // namespace

namespace
{

// The band of lines at the border of an image `size` lines long that `seen` (a line number -> whether
// the previous frame saw it) says are new: from the side with more of them, at most `most`.
template <typename Seen>
LineBand newBand(uint32_t size, uint32_t most, Seen seen)
{
    most = std::min(most, size);
    uint32_t low = 0, high = 0;
    while (low < most && !seen(low))
        ++low;
    while (high < most && !seen(size - 1 - high))
        ++high;
    if (high >= low && high > 0)
        return {size - high, high};
    if (low > 0)
        return {0, low};
    return {};
}

}  // namespace

NewLines findNewLines(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera)
{
    NewLines none;
    if (history.block.blockPx <= 1 || view.width == 0 || view.height == 0)
        return none;
    // History is kept only for the same projection (historyUsable), so the previous frustum is this one.
    const ViewTangents t = viewTangents(view);
    const PreviousAxes prev = previousAxes(history, t, camera);
    const glm::dvec3 centreRay = camera.forwardEnu + t.centreX * camera.rightEnu + t.centreY * camera.upEnu;
    const double w = view.width, h = view.height;
    // As the reconstruct pass: the ray of pixel position (x, y) projected into the previous image (pixels);
    // false when it lies behind the previous camera.
    auto project = [&](double x, double y, glm::dvec2& q) {
        const double nx = x / w * 2.0 - 1.0, ny = y / h * 2.0 - 1.0;
        const glm::dvec3 d = centreRay + nx * t.halfWidth * camera.rightEnu - ny * t.halfHeight * camera.upEnu;
        const double z = glm::dot(d, prev.forward);
        if (z <= 0.0)
            return false;
        q = glm::dvec2((glm::dot(d, prev.right) / (z * t.halfWidth) + 1.0) * 0.5 * w,
                       (-glm::dot(d, prev.up) / (z * t.halfHeight) + 1.0) * 0.5 * h);
        return true;
    };
    NewLines lines;
    lines.columns = newBand(view.width, maxNewColumns(view.width), [&](uint32_t x) {
        glm::dvec2 q;
        for (double y : {0.5, 0.5 * h, h - 0.5})
            if (!project(x + 0.5, y, q) || q.x < 0.0 || q.x >= w)
                return false;
        return true;
    });
    lines.rows = newBand(view.height, maxNewRows(view.height), [&](uint32_t y) {
        glm::dvec2 q;
        for (double x : {0.5, 0.5 * w, w - 0.5})
            if (!project(x, y + 0.5, q) || q.y < 0.0 || q.y >= h)
                return false;
        return true;
    });
    return lines;
}

ReprojectionParams reprojectionParams(const ReprojectionHistory& history, const ViewRequest& view,
                                      const CameraFrame& camera, bool useHistory)
{
    ReprojectionParams r;
    std::memset(&r, 0, sizeof r);  // the unused members too: the light volume compares frames bytewise
    r.blockPx = history.block.blockPx;
    const glm::uvec2 phase = reprojectionPhase(history.frameIndex, r.blockPx);
    r.phasePx = uvec2(phase.x, phase.y);
    r.historyValid = useHistory ? 1u : 0u;
    if (!useHistory)
        return r;
    const ViewTangents t = viewTangents(view);
    const PreviousAxes prev = previousAxes(history, t, camera);
    const glm::dmat3 ecefToEnu = glm::transpose(camera.enuToEcef);
    r.previous.rightEnu = vec3(prev.right);
    r.previous.halfWidthTan = float(t.halfWidth);
    r.previous.upEnu = vec3(prev.up);
    r.previous.halfHeightTan = float(t.halfHeight);
    r.previous.forwardEnu = vec3(prev.forward);
    r.previous.eyeEnuM = vec3(ecefToEnu * (history.lastCamera.eyeEcefM - camera.eyeEcefM));
    const NewLines& lines = history.newLines;
    r.newLines.firstColumn = lines.columns.first;
    r.newLines.columnCount = lines.columns.count;
    r.newLines.firstRow = lines.rows.first;
    r.newLines.rowCount = lines.rows.count;
    return r;
}

}  // namespace sky
