// SPDX-License-Identifier: MIT
// The luminance of the clouds of a render, to compare two renders of one view (the real-time march against
// the reference path tracer: skyservice/app/reference_pairs.h, sky-reference-looks). Over the cloud pixels
// (alpha > 0.5 in the render's own cloud image), the luminance of the cloud radiance / alpha with Rec. 709
// weights, pre-exposed like the EXR files: both renders of a view share the scale, views do not.
#pragma once

#include "skyservice/render/render_types.h"

#include <cstddef>
#include <vector>

namespace sky
{

struct CloudPixel
{
    size_t index;      ///< y * width + x
    double luminance;  ///< of radiance / alpha (pre-exposed)
};

/// The cloud pixels of `r` (its cloud image must have been read back), in row order; none when it was not.
std::vector<CloudPixel> cloudPixels(const RenderResult& r);

/// The median of `values` (the upper one of an even count); 0 when empty.
double medianOf(std::vector<double> values);

/// The median luminance of the cloud pixels of `r`; 0 when it has none.
double medianCloudLuminance(const RenderResult& r);

}  // namespace sky
