// SPDX-License-Identifier: MIT
// Compositing on the CPU, two ways. `display`: the service's finished frame full screen, the demo's flat
// ground below the horizon darkened by the cloud shadow map, blended with the frame where the frame shows
// ground. `layers` (layer_compositor.h): the demo's terrain with relief put in front of or behind the clouds
// by depth, from the service's linear sky, clouds and depth layers, then the demo's own tone mapping.
//
// Why the CPU: at demo sizes (640x360 .. 1280x720) a per-pixel loop takes a few milliseconds, the frame
// arrives in host memory on the shared-memory transport anyway, and the same code then serves the window,
// the headless capture (which has no Vulkan device at all) and the unit test, so what the test checks is
// exactly what the window shows. The window only uploads and scales the result (presenter.h).
#pragma once

#include "client_demo/frame_source.h"
#include "client_demo/ground_shading.h"
#include "client_demo/terrain.h"

#include "skyservice/output/image_files.h"

namespace demo
{

/// How a frame is composited.
enum class CompositeMode
{
    Layers,   ///< terrain with relief by depth from the sky/clouds/depth layers (frames without them: Display)
    Display,  ///< flat ground blended over the finished display frame
};

/// Tuning of the ground (defaults are what the demo uses).
struct CompositeOptions
{
    bool ground = true;               ///< draw the demo ground at all
    CompositeMode mode = CompositeMode::Layers;
    double groundOpacity = 0.85;      ///< display: weight of the demo ground right below the eye (0..1)
    double groundFadeM = 30000.0;     ///< display: distance over which the ground fades into the frame's haze (m, 1/e)
    DemoTerrain terrain;              ///< layers: the heightfield (no peaks: flat ground)
    double hazeM = 30000.0;           ///< layers: distance at which the terrain is 1/e terrain, 1 - 1/e sky (m)
};

/// What compositeFrame did (for the headless sidecar and the tests).
struct CompositeStats
{
    CompositeMode mode = CompositeMode::Display;  ///< the path taken
    uint64_t terrainPixels = 0;            ///< layers: pixels whose ray met the terrain
    uint64_t terrainInFrontPixels = 0;     ///< ... of which the terrain lies in front of a cloud (alpha > 0)
    uint64_t terrainBehindCloudPixels = 0; ///< ... of which the terrain lies behind a cloud (alpha > 0)
};

/**
 * Composites one frame: by layers (compositeLayers, layer_compositor.h) when options.mode is Layers and the
 * frame carries them, else the display path below.
 *
 * The frame below the horizon shows the service's own ground (its atmosphere's ground albedo seen through
 * the haze, and any clouds below the eye). The demo's terrain is blended over it with a weight that
 * falls off with distance as exp(-d / groundFadeM), so the horizon keeps the frame's aerial perspective,
 * and that drops where the frame is much brighter than its average ground (clouds below the eye stay).
 *
 * @param[in] frame the service's frame (rgba of width*height).
 * @param[in] options ground settings.
 * @param[out] out the composited image, the frame's size.
 **********************************************************************/
void compositeFrame(const LatestFrame& frame, const CompositeOptions& options, sky::ImageRgba8& out,
                    CompositeStats* stats = nullptr);

/**
 * The key light of a frame for shading the ground: from its shadow map's metadata when it has one,
 * otherwise a mid-morning sun (the frame carries no sun position without a shadow map).
 **********************************************************************/
GroundLight groundLightOf(const LatestFrame& frame);

}  // namespace demo
