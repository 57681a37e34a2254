// SPDX-License-Identifier: MIT
// From the CIGI host's state to the view the daemon renders: the ownship's pose (altitude above mean
// sea level, attitude) plus the view's offset from it (View Control) become the eye (ellipsoid height,
// heading/pitch/roll), and the view's View Definition becomes the frustum.
//
// Axes: CIGI poses entities in north-east-down with yaw, pitch, roll applied in that order (ICD 3.3,
// Entity Control); a view's offsets are in the entity's body axes (X forward, Y right, Z down) and its
// angles are relative to the entity's attitude. EyePose uses the same angles (heading clockwise from
// north, pitch nose up, roll right wing down), so the eye's attitude is the product of the two rotations.
#pragma once

#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/render/render_types.h"

#include <string>

namespace sky
{

/// The eye of `view` (null: on the ownship, no offset). `geoid` turns the altitude above mean sea level
/// into an ellipsoid height (not loaded: taken as 0 undulation). False + error when the ownship was never
/// posed or the resulting pose is outside what the renderer accepts (validateEyePose).
bool cigiEyePose(const cigi::OwnshipPose& ownship, const cigi::ViewState* view, const cigi::GeoidGrid& geoid,
                 EyePose& out, std::string& error);

/// The asymmetric frustum of a View Definition: CIGI's signed half-angles (left and bottom negative when
/// the edge is left of / below the view axis) as Frustum's angles from the axis to each edge. `fovYDeg`
/// gets the vertical extent (top - bottom) for a renderer that draws a symmetric view. False + error when
/// an angle is outside (-85, 85) degrees or the view is narrower than 1 degree.
bool cigiFrustum(const cigi::ViewState& view, Frustum& out, double& fovYDeg, std::string& error);

} // namespace sky
