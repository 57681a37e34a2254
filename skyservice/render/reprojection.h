// SPDX-License-Identifier: MIT
// Temporal reprojection of the cloud image (DESIGN §3, issue 5): the CPU side.
//
// Each reprojected frame marches one pixel of every 4x4 block, at the block position that
// reprojectionPhase(frameIndex) names (a Bayer order: 16 consecutive frames cover all 16 positions).
// shaders/clouds/reconstruct.comp.glsl builds the full image from those fresh pixels and the previous
// frame's image. This file keeps what the renderer remembers between frames, decides when that history
// must be dropped, and fills the reprojection terms of FrameParams in double precision (DESIGN §4):
// the previous camera's axes and eye position are expressed in the current eye's ENU frame before
// they are rounded to float, so the GPU never sees an earth-centred coordinate.
#pragma once

#include "shaders/shared/frame_params.h"
#include "skyservice/render/render_types.h"

#include <glm/glm.hpp>
#include <string>

namespace sky
{

/// History is dropped when the eye moves farther than this between two frames (m): 5 km is 20 frames
/// at 250 m/s and 60 Hz; beyond it the previous frame is more likely a teleport than a flight.
constexpr double kReprojectionMaxMoveM = 5000.0;
/// ... or when the view axis turns more than this (degrees): at 60 degrees of field of view, 30 degrees
/// leaves half the screen without history, where reprojection saves nothing.
constexpr double kReprojectionMaxTurnDeg = 30.0;
/// ... or when the view time jumps more than this (s): wind drift and sun move the clouds.
constexpr double kReprojectionMaxTimeJumpS = 60.0;

/// What the renderer remembers of the last reprojected frame.
struct ReprojectionHistory
{
    bool valid = false;          ///< the history images hold the last reprojected frame of `lastView`
    uint32_t frameIndex = 0;     ///< reprojected frames since the renderer was created (picks the phase)
    uint32_t current = 0;        ///< which of the two history images the last frame wrote
    ViewRequest lastView;        ///< the view of the last reprojected frame
    CameraFrame lastCamera;      ///< its camera, in double
    std::string lastDropReason;  ///< why the last reprojected frame did not use history ("" if it did)
};

/// Position (x, y in 0..3) of the marched pixel inside every 4x4 block on frame `frameIndex`: the 4x4
/// Bayer matrix read in order, so that any 16 consecutive frames march every position once and
/// consecutive frames are far apart inside the block.
glm::uvec2 reprojectionPhase(uint32_t frameIndex);

/// Whether the last frame can be reprojected into `view`. If not, `why` names the reason (first frame,
/// size or field of view change, eye moved, turned, or time jumped beyond the limits above).
bool historyUsable(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera,
                   std::string& why);

/// Fills frame.reprojection, frame.previousRight/Up/Forward and frame.previousEye for a reprojected
/// frame on `camera` (useHistory false: the reconstruct pass ignores the history images).
void fillReprojectionParams(FrameParams& frame, const ReprojectionHistory& history, const ViewRequest& view,
                            const CameraFrame& camera, bool useHistory);

}  // namespace sky
