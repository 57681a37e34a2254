// SPDX-License-Identifier: MIT
// The weather window on the GPU for the eye's lattice cell (earth/window_lattice.h), and the prefetch
// of the next cell's window on the worker thread (window_provider.h).
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

// Puts the window of the eye's lattice node on the GPU (made on a worker thread ahead of time when the
// eye flew toward it, else now), and starts the window of the node the eye is heading for.
SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality);

}  // namespace sky
