// SPDX-License-Identifier: MIT
// --headless: a scripted flight through the service, each frame composited and written to
// DIR/frame-NNNN.png with a JSON sidecar (view, time, frame id), atomically. No window, no GLFW.
#pragma once

#include "client_demo/demo_options.h"

namespace demo
{

/// Runs the capture; returns the exit code (0 ok, 1 failure, with the reason on stderr).
int runHeadless(const DemoOptions& options);

}  // namespace demo
