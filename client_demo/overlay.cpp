// SPDX-License-Identifier: MIT
#include "client_demo/overlay.h"

#include "client_demo/utc_time.h"

#include "skyservice/output/bitmap_font.h"

#include <algorithm>
#include <cstdio>

namespace demo
{

std::vector<std::string> overlayLines(const OverlayInfo& info)
{
    const Aircraft& a = info.aircraft;
    char line[160];
    std::vector<std::string> lines;
    std::snprintf(line, sizeof line, "LAT %.4f LON %.4f ALT %.0f M", a.latDeg, a.lonDeg, a.altitudeM);
    lines.emplace_back(line);
    std::snprintf(line, sizeof line, "HDG %.0f PITCH %.0f SPD %.0f M/S", a.headingDeg, a.pitchDeg, a.speedMps);
    lines.emplace_back(line);
    lines.push_back(formatUtc(info.simTimeUnixS) + " UTC");
    if (info.fps > 0.0)
        std::snprintf(line, sizeof line, "%.1f FPS  FRAME %llu  %s", info.fps, (unsigned long long)info.frameId,
                      info.transport.c_str());
    else
        std::snprintf(line, sizeof line, "FRAME %llu  %s", (unsigned long long)info.frameId, info.transport.c_str());
    lines.emplace_back(line);
    return lines;
}

void drawOverlay(sky::ImageRgba8& image, const OverlayInfo& info)
{
    if (image.width == 0 || image.height == 0)
        return;
    const uint32_t scale = image.width >= 960 ? 2 : 1;
    const std::vector<std::string> lines = overlayLines(info);
    const uint32_t lineHeight = (sky::kGlyphHeight + 3) * scale;
    uint32_t bandWidth = 0;
    for (const std::string& l : lines)
        bandWidth = std::max(bandWidth, sky::textWidthPixels(l, scale));
    bandWidth = std::min(image.width, bandWidth + 8 * scale);
    const uint32_t bandHeight = std::min(image.height, uint32_t(lines.size()) * lineHeight + 6 * scale);
    // Halve the brightness behind the text so it reads on bright cloud and dark night alike.
    for (uint32_t y = 0; y < bandHeight; ++y)
        for (uint32_t x = 0; x < bandWidth; ++x)
        {
            uint8_t* p = image.pixel(x, y);
            for (int k = 0; k < 3; ++k)
                p[k] = uint8_t(p[k] / 2);
        }
    for (size_t i = 0; i < lines.size(); ++i)
        sky::drawText(image, 4 * scale, int64_t(4 * scale + i * lineHeight), lines[i], scale, {255, 255, 255, 255});
}

}  // namespace demo
