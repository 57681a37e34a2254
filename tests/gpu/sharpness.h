// SPDX-License-Identifier: MIT
// Sharpness of a display image (the requirement: under a 60 deg/s turn the display keeps its detail; compare
// sharpness, not only PSNR): PSNR forgives a uniformly blurred frame that keeps the mean right, while the
// eye sees lost detail at once. The measure is the mean absolute difference of the display luma between
// horizontal and vertical neighbours, optionally over a band of columns: blur lowers it, grain raises it.
#pragma once

#include "skyservice/render/renderer.h"
#include "tests/gpu/image_compare.h"

namespace sky::testscenes
{

/// Mean |luma(x+1,y) - luma(x,y)| + |luma(x,y+1) - luma(x,y)| over the pixels of `band` whose right and lower
/// neighbours exist, in 8-bit sRGB luma steps (Rec. 709 weights on the display bytes).
double displaySharpness(const RenderResult& image, ColumnBand band = {});

/// displaySharpness of `test` over that of `reference` (1 when both are flat).
double sharpnessRatio(const RenderResult& test, const RenderResult& reference, ColumnBand band = {});

}  // namespace sky::testscenes
