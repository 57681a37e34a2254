// SPDX-License-Identifier: MIT
// Contact sheet: several rendered views tiled on one image, each captioned with the built-in bitmap
// font (skyservice/output/bitmap_font.h), for reviewing a showcase run at a glance.
#pragma once

#include "skyservice/output/image_files.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sky
{

/// Layout constants of a contact sheet (pixels).
inline constexpr uint32_t kContactSheetMarginPx = 8;         ///< around and between tiles
inline constexpr uint8_t kContactSheetBackground = 24;       ///< grey level behind the tiles

/**
 * Tile images on a grid with a caption under each.
 *
 * @param[in] images the tiles, in reading order; they may differ in size (each cell is as large as
 *   the largest, a smaller image is centred in its cell). Alpha is blended over the dark background.
 * @param[in] captions one line per image (missing entries mean no caption); text wider than the tile
 *   is cut and ends in "..."; characters outside printable ASCII draw as '?'.
 * @param[in] columns tiles per row (0 is taken as 1; more than images.size() is reduced).
 * @return the sheet, opaque; an empty image (0 x 0) when images is empty.
 *
 * The caption font is scaled by 2 when tiles are at least 480 pixels wide.
 **********************************************************************/
ImageRgba8 makeContactSheet(const std::vector<ImageRgba8>& images, const std::vector<std::string>& captions,
                            uint32_t columns);

/// `image` enlarged `factor` times (0 is taken as 1) by repeating its pixels, so that a small render reads on a
/// sheet as what it is: a few pixels, not a blur.
ImageRgba8 enlargeImage(const ImageRgba8& image, uint32_t factor);

}  // namespace sky
