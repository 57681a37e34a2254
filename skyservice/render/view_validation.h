// SPDX-License-Identifier: MIT
// The rules a view must meet before the renderer draws it: the eye pose (earth/geodesy.h validateEyePose),
// the image size and the projection (a vertical field of view, or an off-centre frustum: view_frustum.h).
// One function, called once where a view enters: the service's set_view (after the protocol has parsed
// each field), its configuration, the render command's options, and renderView for callers that draw
// directly (tests, sky-bench, the showcase). submitView, the service's frame path, draws views the
// service validated where they entered and does not check them again.
#pragma once

#include "skyservice/render/render_types.h"
#include "skyservice/render/view_limits.h"

#include <cstdint>
#include <string>

namespace sky
{

/// Image sides the renderer draws, in pixels.
constexpr uint32_t kMinViewSizePx = 8;
constexpr uint32_t kMaxViewSizePx = 8192;

/// True when the renderer may draw `view` (the ranges of view_limits.h among its rules); otherwise false
/// and `error` says what is wrong, in one line.
bool validateView(const ViewRequest& view, std::string& error);

}  // namespace sky
