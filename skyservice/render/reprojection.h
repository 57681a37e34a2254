// SPDX-License-Identifier: MIT
// Temporal reprojection of the cloud image (docs/model.md): the CPU side.
//
// Each reprojected frame marches one pixel of every 4x4 block, at the block position that
// reprojectionPhase(frameIndex) names (a Bayer order: 16 consecutive frames cover all 16 positions).
// shaders/clouds/reconstruct.comp.glsl builds the full image from those fresh pixels and the previous
// frame's image. This file keeps what the renderer remembers between frames, decides when that history
// must be dropped, and computes the reprojection part of FrameParams in double precision (docs/datums.md):
// the previous camera's axes and eye position are expressed in the current eye's ENU frame before
// they are rounded to float, so the GPU never sees an earth-centred coordinate.
#pragma once

#include "shaders/shared/frame_params.h"
#include "skyservice/weather/weather_window.h"
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

/// The eye marches one pixel of every 2x2 block instead of 4x4 when it is closer than this (m, vertically)
/// to the base or top of a cloud layer with cloud around it: clouds that near move by several pixels per
/// frame and uncover what history never saw (our choice: at 250 m/s a cloud 300 m away moves ~0.8
/// degrees per 60 Hz frame).
constexpr double kNearCloudM = 300.0;
/// ... and every pixel (block 1) when it is between a layer's base and top: in a broken or scattered
/// layer the eye flies between clouds whose edges are metres to a few km away (a quarter of the pixels
/// per frame dithered them at 150 m/s in ./sky run's demo).
/// Inside an overcast layer (coverage around the eye at least this) the view is fog a few tens of metres
/// deep, whose radiance comes from the first ~100 m of cloud: there RenderTuning::insideCloudBlockPx
/// (2 by default, a quarter of the pixels) applies.
constexpr float kOvercastCoverage = 0.8f;
/// "Around the eye" is this far horizontally (m): the weather window's texels near the eye are ~1 km.
constexpr double kNearCloudRadiusM = 2000.0;
/// Coverage below this counts as clear air for that decision.
constexpr float kNearCloudMinCoverage = 0.02f;

/// How many pixels a reprojected frame marches, and why.
struct MarchBlock
{
    uint32_t blockPx = 4;  ///< 4: one pixel of every 4x4 block; 2: of every 2x2; 1: every pixel
    std::string reason;    ///< why not 4 ("" when 4)
};

/// Lines (columns or rows) at one side of the image.
struct LineBand
{
    uint32_t first = 0;  ///< first column (row)
    uint32_t count = 0;  ///< how many (0: none)
};

/// The lines at the image borders whose rays the previous frame did not see (followed to infinity): in a
/// turn, the columns at the side the view turns toward; in a pitch change, the rows at the top or bottom;
/// both in a banked turn. The march marches every pixel of them, not one of each block, so they enter
/// the history as marched and not interpolated from one pixel in B^2 (a fast turn would otherwise bring
/// all its new content in blurred, for up to B^2 frames). A roll brings in the corners, which neither
/// covers: they keep the interpolated fill.
struct NewLines
{
    LineBand columns;
    LineBand rows;
};

/// At most 1/16 of the width is marched that way (8 columns of 128, 240 of 3840: a turn of about 5 degrees
/// per frame at 90 degrees of field of view), and 1/32 of the height (34 rows of 1080: a pitch change of
/// about 2 degrees per frame at 60 degrees, 120 deg/s at 60 Hz; the fresh images hold room for them, 2 MB
/// at 1080p); beyond it the rest keeps the fill.
constexpr uint32_t kNewColumnsMaxShare = 16;
constexpr uint32_t kNewRowsMaxShare = 32;
inline uint32_t maxNewColumns(uint32_t widthPx) { return (widthPx + kNewColumnsMaxShare - 1) / kNewColumnsMaxShare; }
inline uint32_t maxNewRows(uint32_t heightPx) { return (heightPx + kNewRowsMaxShare - 1) / kNewRowsMaxShare; }

/// What the renderer remembers of the last reprojected frame.
struct ReprojectionHistory
{
    bool valid = false;          ///< the history images hold the last reprojected frame of `lastView`
    uint32_t frameIndex = 0;     ///< reprojected frames since the renderer was created (picks the phase)
    uint32_t current = 0;        ///< which of the two history images the last frame wrote
    uint64_t drops = 0;          ///< dropHistory calls (weather swaps, jumps): a small staged step makes none
    ViewRequest lastView;        ///< the view of the last reprojected frame
    CameraFrame lastCamera;      ///< its camera, in double
    std::string lastDropReason;  ///< why the last reprojected frame did not use history ("" if it did)
    MarchBlock block;            ///< the march block of the frame being (or last) rendered
    NewLines newLines;           ///< the lines that frame marches in full (none without history)
};

/// Position (x, y in 0..blockPx-1) of the marched pixel inside every block on frame `frameIndex`: the
/// Bayer matrix of that size read in order, so that any blockPx^2 consecutive frames march every
/// position once and consecutive frames are far apart inside the block. blockPx is 4, 2 or 1.
glm::uvec2 reprojectionPhase(uint32_t frameIndex, uint32_t blockPx = 4);

/**
 * The march block for an eye at `eyeAltitudeM` (m above the ellipsoid) in `window`: inside a volumetric
 * layer (between its base and top, coverage above kNearCloudMinCoverage within kNearCloudRadiusM) 1, or
 * `insideBlockPx` (2 or 1) where that coverage reaches kOvercastCoverage; 2 within kNearCloudM of such a
 * layer, else 4. `eyeOnWindowM` is where the eye lies
 * on the window plane (m; weather/window_lattice.h: windows are centred on a lattice node near the eye).
 */
MarchBlock chooseMarchBlock(const WeatherWindow& window, double eyeAltitudeM,
                            const glm::dvec2& eyeOnWindowM = glm::dvec2(0.0), uint32_t insideBlockPx = 2);

/// Whether the last frame can be reprojected into `view`. If not, `why` names the reason (first frame,
/// size or field of view change, eye moved, turned, or time jumped beyond the limits above).
bool historyUsable(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera,
                   std::string& why);

/// The lines of `view` (on `camera`) that the last frame in `history` did not see. Columns: on the side
/// with more of them, counted from the image border inward while a column's rays at its top, middle and
/// bottom all or partly fall off the previous image (left or right of it, or behind); rows the same
/// with a row's rays at its left, middle and right falling off above or below. At most maxNewColumns and
/// maxNewRows; none when the march block is 1 (every pixel is marched anyway).
NewLines findNewLines(const ReprojectionHistory& history, const ViewRequest& view, const CameraFrame& camera);

/// The reprojection part of a reprojected frame's uniforms on `camera`: the block size
/// history.block.blockPx and its phase, the previous camera (zero when useHistory is false: the
/// reconstruct pass then ignores the history images) and history.newLines.
ReprojectionParams reprojectionParams(const ReprojectionHistory& history, const ViewRequest& view,
                                      const CameraFrame& camera, bool useHistory);

}  // namespace sky
