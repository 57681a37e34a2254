// SPDX-License-Identifier: MIT
#include "skyservice/output/contact_sheet.h"

#include "skyservice/output/bitmap_font.h"

#include <algorithm>

namespace sky
{

namespace
{

// Fit a caption into maxWidthPx by cutting it and appending "...".
std::string fitCaption(const std::string& caption, uint32_t maxWidthPx, uint32_t scale)
{
    if (textWidthPixels(caption, scale) <= maxWidthPx)
        return caption;
    std::string cut = caption;
    while (!cut.empty() && textWidthPixels(cut + "...", scale) > maxWidthPx)
        cut.pop_back();
    return cut.empty() ? std::string() : cut + "...";
}

// Straight-alpha "over" onto the opaque background.
void blendTile(ImageRgba8& sheet, const ImageRgba8& tile, uint32_t left, uint32_t top)
{
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x)
        {
            const uint8_t* src = tile.pixel(x, y);
            uint8_t* dst = sheet.pixel(left + x, top + y);
            const uint32_t alpha = src[3];
            for (int k = 0; k < 3; ++k)
                dst[k] = uint8_t((uint32_t(src[k]) * alpha + uint32_t(dst[k]) * (255u - alpha) + 127u) / 255u);
            dst[3] = 255;
        }
}

}  // namespace

ImageRgba8 makeContactSheet(const std::vector<ImageRgba8>& images, const std::vector<std::string>& captions,
                            uint32_t columns)
{
    ImageRgba8 sheet;
    if (images.empty())
        return sheet;
    columns = std::clamp(columns, 1u, uint32_t(images.size()));
    const uint32_t rows = uint32_t((images.size() + columns - 1) / columns);
    uint32_t tileWidth = 1;
    uint32_t tileHeight = 1;
    for (const ImageRgba8& image : images)
    {
        tileWidth = std::max(tileWidth, image.width);
        tileHeight = std::max(tileHeight, image.height);
    }
    const uint32_t scale = tileWidth >= 480 ? 2 : 1;
    const uint32_t captionHeight = kGlyphHeight * scale + 2 * (2 * scale);
    const uint32_t cellHeight = tileHeight + captionHeight;
    sheet.width = columns * tileWidth + (columns + 1) * kContactSheetMarginPx;
    sheet.height = rows * cellHeight + (rows + 1) * kContactSheetMarginPx;
    sheet.pixels.assign(size_t(sheet.width) * sheet.height * 4, kContactSheetBackground);
    for (size_t p = 3; p < sheet.pixels.size(); p += 4)
        sheet.pixels[p] = 255;

    const std::array<uint8_t, 4> textColour = {235, 235, 235, 255};
    for (size_t n = 0; n < images.size(); ++n)
    {
        const ImageRgba8& image = images[n];
        const uint32_t column = uint32_t(n % columns);
        const uint32_t row = uint32_t(n / columns);
        const uint32_t cellLeft = kContactSheetMarginPx + column * (tileWidth + kContactSheetMarginPx);
        const uint32_t cellTop = kContactSheetMarginPx + row * (cellHeight + kContactSheetMarginPx);
        if (image.pixels.size() == size_t(image.width) * image.height * 4)
            blendTile(sheet, image, cellLeft + (tileWidth - image.width) / 2, cellTop + (tileHeight - image.height) / 2);
        if (n < captions.size())
        {
            const std::string text = fitCaption(captions[n], tileWidth, scale);
            drawText(sheet, int64_t(cellLeft), int64_t(cellTop + tileHeight + 2 * scale), text, scale, textColour);
        }
    }
    return sheet;
}

ImageRgba8 enlargeImage(const ImageRgba8& image, uint32_t factor)
{
    factor = std::max(factor, 1u);
    ImageRgba8 out;
    out.width = image.width * factor;
    out.height = image.height * factor;
    out.pixels.resize(size_t(out.width) * out.height * 4);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x)
            std::copy_n(image.pixel(x / factor, y / factor), 4, out.pixel(x, y));
    return out;
}

}  // namespace sky
