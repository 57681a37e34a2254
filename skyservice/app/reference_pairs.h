// SPDX-License-Identifier: MIT
// Views next to the reference (`./sky run` shows four of the look views next to the reference path tracer):
// a view rendered in real time and path-traced (skyservice/render/reference_renderer.h) at a small size, the two
// side by side on a captioned sheet with each one's median cloud luminance (skyservice/output/cloud_luminance.h).
// `skyservice showcase` writes OUT/look-reference-pairs.png; sky-reference-looks draws its sheet with it too.
#pragma once

#include "skyservice/app/look_views.h"
#include "skyservice/output/image_files.h"
#include "skyservice/render/reference_renderer.h"

#include <string>
#include <vector>

namespace sky
{

/// One view both ways, at the same size.
struct ReferencePair
{
    std::string title;  ///< the view, a few words (lookTitle)
    RenderResult realTime, reference;
    ReferenceStats stats;  ///< the reference's
};

/// The look views of the showcase's pairs (look_views.h names): from below, among, from above, at sunset.
extern const char* const kReferencePairViews[4];

/// The part of the view's caption before ':' (all of it when there is none): a title for a small tile.
std::string lookTitle(const LookView& view);

/// Renders `view` in real time and path-traced, both with the model of `quality` and the renderer's weather.
SkyStatus renderReferencePair(Renderer& r, ReferenceRenderer& ref, const ViewRequest& view,
                              const QualitySettings& quality, const ReferenceSettings& settings, ReferencePair& pair);

/// A row per pair, real time | reference, enlarged (nearest neighbour) to about 400 pixels wide so that the
/// captions fit: the title and median cloud luminance under the real-time tile, the samples per pixel and the
/// reference's median under the other. Empty (0 x 0) without pairs.
ImageRgba8 makeReferencePairSheet(const std::vector<ReferencePair>& pairs, uint32_t samplesPerPixel);

/// What `skyservice showcase` does: the kReferencePairViews at width x height, each with the built-in weather at
/// its time, both ways, into the sheet at `pngPath`; prints a line per view (medians, the reference's seconds).
/// The reference renderer is created and destroyed here. Fails with the first error (a view, the file).
SkyStatus writeLookReferencePairs(Renderer& r, const QualitySettings& quality, uint32_t width, uint32_t height,
                                  uint32_t samplesPerPixel, const std::string& pngPath);

}  // namespace sky
