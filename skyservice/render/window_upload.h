// SPDX-License-Identifier: MIT
// The weather window on the GPU for the eye's lattice cell (weather/window_lattice.h), and the prefetch
// of the next cell's window on the worker thread (window_provider.h).
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

// Puts the window of the eye's lattice node on the GPU (made on a worker thread ahead of time when the
// eye flew toward it, else now), and starts the window of the node the eye is heading for. A new window is
// copied into the images on the frame queue, ordered on the GPU between the frames before and after it
// (window_copy.h): the CPU does not wait, and the frame that enters a cell draws that cell's window, as
// a one-shot render of its view does.
SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality);

}  // namespace sky
