// SPDX-License-Identifier: MIT
// Statistics of the cloud pixels of a render, to compare the real-time lighting with the reference path
// tracer (sky-reference-looks, tests/gpu/test_reference_looks.cpp). Over the cloud pixels and their luminance
// (skyservice/output/cloud_luminance.h):
//  - median: the median luminance;
//  - underside/top: the median luminance of the cloud pixels whose first-collision altitude (eye altitude +
//    depth along the ray, on the sphere) lies in the lowest fifth of those pixels' altitudes, over that of the
//    highest fifth. From below that compares the bases with the sunlit towers; a stand-in for the underside /
//    sunlit-side ratio that needs no cloud segmentation.
#pragma once

#include "skyservice/render/renderer.h"

#include <cstddef>
#include <string>

namespace sky::testscenes
{

struct LookStats
{
    size_t cloudPixels = 0;
    double medianLuminance = 0;
    double meanLuminance = 0;  ///< unbiased at few samples per pixel, where the median of a path-traced image is not
    double undersideOverTop = 0;
    double undersideLuminance = 0;  ///< median of the lowest fifth
    double topLuminance = 0;        ///< median of the highest fifth
    /// The same ratio of the fifths' mean luminances: unbiased at few samples per pixel.
    double undersideOverTopOfMeans = 0;
};

LookStats measureLook(const ViewRequest& view, const RenderResult& r);

/// The cloud image, depth and display image of a render (what measureLook reads) to and from a small binary file: the
/// reference takes minutes on lavapipe and depends only on the view, the model and the samples.
bool saveCloudLayers(const std::string& path, const RenderResult& r);
bool loadCloudLayers(const std::string& path, RenderResult& r);

}  // namespace sky::testscenes
