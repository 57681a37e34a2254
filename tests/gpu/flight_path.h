// SPDX-License-Identifier: MIT
// A scripted flight for the reprojection gates: the eye moves in 60 Hz frame steps, every
// frame is rendered reprojected and, once the history is warm, compared with a full-resolution render
// of the same pose.
#pragma once

#include "skyservice/render/renderer.h"

#include <string>

namespace sky::testscenes
{

/// How the eye moves: horizontally along its heading at `speedMS`, turning at `turnDegPerS`, climbing at
/// `climbMS`; the view's pitch stays as it is.
struct Motion
{
    double speedMS = 0;      ///< ground speed along the heading (m/s)
    double turnDegPerS = 0;  ///< heading rate (degrees per second; + turns right)
    double climbMS = 0;      ///< vertical speed (m/s; + up)
    double pitchDegPerS = 0; ///< pitch rate (degrees per second; + nose up)
};

/// One 60 Hz step of `motion` (dt = 1/60 s): position through the local radii of curvature.
void stepPose(ViewRequest& view, const Motion& motion);

struct FlightStats
{
    double worstCloudDb = 1e9;        ///< lowest cloud-image PSNR of the measured frames
    double worstDisplayDb = 1e9;      ///< lowest display PSNR
    double worstEdgeCloudDb = 1e9;    ///< lowest cloud-image PSNR in the 8-pixel edge bands
    double worstEdgeMeanAbs = 0;      ///< highest mean absolute cloud error in those bands (share of the peak)
    double worstEdgeDeficitDb = -1e9; ///< largest (whole-frame cloud PSNR - edge-band cloud PSNR) of a frame
    double worstReferenceDb = 1e9;    ///< lowest PSNR of a reference against the previous one resampled to it
    double lowestSharpness = 1e9;     ///< lowest display sharpness ratio to the full render (sharpness.h)
    double lowestEdgeSharpness = 1e9; ///< the same in the edge bands
    int historyDrops = 0;             ///< measured frames that did not use history
    int frames = 0;
    uint32_t lastBlockPx = 0;         ///< march block of the last frame (RenderResult::marchBlockPx)
    std::string lastBlockReason;      ///< and its reason
    uint32_t minBlockPx = 4, maxBlockPx = 1;  ///< finest and coarsest march block of the measured frames
    int fullBlockFramesNotExact = 0;  ///< block-1 frames whose cloud image differs from the full render
};

/// Which lines count as "the screen edges" of a flight: the 8 columns on the side the view turns toward,
/// or both sides when it does not turn (flying forward brings new content in at every edge); when the
/// pitch changes, the 8 rows at the border the nose moves toward instead.
constexpr uint32_t kEdgeBandPx = 8;

/**
 * Flies `warmFrames` reprojected frames (not measured: the history fills), then `measuredFrames`
 * reprojected frames each followed by a full render of the same pose. Prints one line per measured
 * frame prefixed by `name`, with the reference's own consistency: the previous reference resampled to
 * this frame's rays (rotation only, bilinear) against this reference, the floor that sub-pixel cloud
 * detail sets for any reprojection at this size. When `pngPath` (ending in ".png") is not empty, the
 * last reprojected frame is written there and its full render beside it ("...-full.png"), 4x enlarged.
 */
FlightStats flySegment(Renderer& r, ViewRequest& view, const Motion& motion, int warmFrames, int measuredFrames,
                       const std::string& name, const std::string& pngPath = "");

}  // namespace sky::testscenes
