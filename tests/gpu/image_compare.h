// SPDX-License-Identifier: MIT
// Image comparisons of the reprojection tests: PSNR of the cloud image and of the display
// image, over the whole frame or a band of columns, and one full render resampled into another view.
//
// Cloud-image PSNR is over the four channels of RenderResult::cloudRgbaHalf (premultiplied linear
// radiance rgb and alpha) with the peak = the largest channel value of the reference; display PSNR
// is over the tone-mapped sRGB bytes (rgb and the constant alpha), peak 255.
#pragma once

#include "skyservice/render/renderer.h"

#include <string>
#include <vector>

namespace sky::testscenes
{

/// Columns [x0, x1) of the image (all columns by default), in rows [y0, y1) (all rows by default): a band
/// of columns, or of rows when the columns are left at their default.
struct ColumnBand
{
    uint32_t x0 = 0;
    uint32_t x1 = 0xffffffffu;
    uint32_t y0 = 0;
    uint32_t y1 = 0xffffffffu;
};

double psnrCloud(const RenderResult& test, const RenderResult& reference, ColumnBand band = {});

/// The reference's own radiance scale: the 99th percentile, over its pixels of alpha >= 0.5, of the
/// largest rgb channel (premultiplied). psnrCloud's peak is mostly alpha's 1, so a light twice as bright
/// doubles the error against a fixed peak with nothing rendered worse; this scale follows the light. 1 when no pixel is that opaque.
double radianceScale(const RenderResult& reference);
/// Cloud-image PSNR independent of the picture's brightness: rgb differences over `rgbScale` (by default
/// radianceScale(reference)), alpha differences over 1 (its range), peak 1.
double psnrCloudScaled(const RenderResult& test, const RenderResult& reference, ColumnBand band = {},
                       double rgbScale = 0.0);
double psnrDisplay(const RenderResult& test, const RenderResult& reference, ColumnBand band = {});
/// Mean absolute difference of the cloud image over `band`, divided by the reference's peak.
double meanAbsCloudError(const RenderResult& test, const RenderResult& reference, ColumnBand band = {});

/// Cloud image of `source` (rendered for `sourceView`) resampled bilinearly at the pixel rays of
/// `targetView` (same eye position; only the orientation may differ). Pixels whose ray falls outside
/// the source image are flagged in `valid`.
struct Resampled
{
    std::vector<float> cloudRgba;  ///< 4 floats per target pixel
    std::vector<uint8_t> valid;    ///< 1 where the ray lands inside the source image
};
Resampled resampleCloud(const RenderResult& source, const ViewRequest& sourceView, const ViewRequest& targetView);
/// PSNR of a resampled cloud image against a render of the target view, over valid pixels.
double psnrResampled(const Resampled& test, const RenderResult& reference);

/// Writes the display image as a PNG, each pixel as a `scale` x `scale` square (for looking at a
/// 128x72 frame by eye; tests do not read it back).
void writeDisplayPng(const RenderResult& r, const std::string& path, uint32_t scale = 4);

}  // namespace sky::testscenes
