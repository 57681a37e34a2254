// SPDX-License-Identifier: MIT
// The weather window on the GPU for the eye's lattice cell (weather/window_lattice.h), and the prefetch
// of the next cell's window on the worker thread (window_provider.h).
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

// Puts the window of the eye's lattice node on the GPU (made on a worker thread ahead of time when the
// eye flew toward it, else now), and starts the window of the node the eye is heading for. A new window is
// copied into the back images (window_copy.h) without waiting; frames go on drawing the current one until
// the copy's fence has signalled (a frame or two after a flight crosses into a new cell). Only a frame
// with no usable window (the first, a new weather, a jump or new window settings) waits for the copy.
SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality);

}  // namespace sky
