// SPDX-License-Identifier: MIT
// A tiny built-in 5x7 bitmap font (printable ASCII 32..126, drawn for this project) for captions on
// contact sheets and debug images, so that no font file or font library is needed.
#pragma once

#include "skyservice/output/image_files.h"

#include <array>
#include <cstdint>
#include <string_view>

namespace sky
{

inline constexpr uint32_t kGlyphWidth = 5;    ///< glyph cell width (pixels at scale 1)
inline constexpr uint32_t kGlyphHeight = 7;   ///< glyph cell height (pixels at scale 1)
inline constexpr uint32_t kGlyphAdvance = 6;  ///< horizontal distance between characters (pixels at scale 1)

/**
 * @param[in] c a character; anything outside printable ASCII 32..126 gives the glyph of '?'.
 * @return its 7 rows, top first; bit 4 is the leftmost pixel, bit 0 the rightmost.
 **********************************************************************/
const std::array<uint8_t, kGlyphHeight>& glyphRows(char c);

/**
 * @param[in] text one line of text.
 * @param[in] scale pixel size of one font pixel (>= 1).
 * @return the width the text takes when drawn (pixels), 0 for empty text.
 **********************************************************************/
uint32_t textWidthPixels(std::string_view text, uint32_t scale);

/**
 * Draw one line of text, clipped to the image.
 *
 * @param[in,out] image the image to draw on.
 * @param[in] x, y top-left corner of the first glyph (pixels; may be negative or off the image).
 * @param[in] text one line of text.
 * @param[in] scale pixel size of one font pixel (>= 1).
 * @param[in] rgba colour of the text (straight RGBA, 8 bit); it replaces the pixels it covers.
 **********************************************************************/
void drawText(ImageRgba8& image, int64_t x, int64_t y, std::string_view text, uint32_t scale,
              const std::array<uint8_t, 4>& rgba);

}  // namespace sky
