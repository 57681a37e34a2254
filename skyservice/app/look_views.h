// SPDX-License-Identifier: MIT
// The look views: where pilots look at the built-in clouds (skyservice/sky/builtin_weather.h), to
// judge their shapes and light at a glance. `skyservice showcase` renders them into the look sheet and four of
// them next to the reference path tracer (skyservice/app/reference_pairs.h); sky-reference-looks measures them.
#pragma once

#include "skyservice/render/render_types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sky
{

struct LookView
{
    std::string name;     ///< file name without extension (out/NAME.png), unique
    std::string caption;  ///< what, where, when (about 40 characters fit a 320-pixel tile)
    EyePose pose;
    double fovYDeg = 60.0;  ///< vertical field of view (degrees)
    int64_t unixTimeS = 0;  ///< UTC (s since 1970); the built-in weather at that time
};

/// The look views, in the look sheet's order.
std::vector<LookView> lookViews();

/// The look view called `name`; nullptr when there is none.
const LookView* findLookView(const std::vector<LookView>& views, const std::string& name);

/// A request for `view` at width x height pixels (everything else at ViewRequest's defaults).
ViewRequest lookViewRequest(const LookView& view, uint32_t width, uint32_t height);

/// Degrees of longitude spanned by `metres` east-west at latitude `latDeg` (degrees), on a sphere: to place
/// eyes some kilometres from the built-in clouds (0.3 % off the ellipsoid's, which is enough there).
double lonOffsetDeg(double metres, double latDeg);

}  // namespace sky
