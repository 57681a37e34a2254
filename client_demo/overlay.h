// SPDX-License-Identifier: MIT
// The small text overlay (position, UTC, fps) drawn into the composited image with the project's 5x7
// bitmap font (skyservice/output/bitmap_font.h, no Vulkan in it).
#pragma once

#include "client_demo/flight_model.h"

#include "skyservice/output/image_files.h"

#include <string>
#include <vector>

namespace demo
{

/// What the overlay shows.
struct OverlayInfo
{
    Aircraft aircraft;        ///< where the pilot is (may be ahead of the frame's view by a frame or two)
    double simTimeUnixS = 0;  ///< UTC of the frame shown
    double fps = 0;           ///< frames shown per second (0 = not measured: headless)
    uint64_t frameId = 0;     ///< the service's frame id
    std::string transport;    ///< "shm" or "vulkan"
};

/// The overlay's lines of text.
std::vector<std::string> overlayLines(const OverlayInfo& info);

/**
 * Draws the lines at the top-left corner on a darkened band (scale 2 from 960 pixels wide, else 1).
 **********************************************************************/
void drawOverlay(sky::ImageRgba8& image, const OverlayInfo& info);

}  // namespace demo
