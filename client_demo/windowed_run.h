// SPDX-License-Identifier: MIT
// The window: fly with keys and mouse, the service renders each new view, the demo composites its frames
// over the ground and shows them with an overlay. --frames N stops after N service frames were shown,
// --screenshot FILE writes the last presented image.
#pragma once

#include "client_demo/demo_options.h"

namespace demo
{

/// Runs until the window closes (or --frames); returns the exit code (0 ok, 1 failure on stderr).
int runWindowed(const DemoOptions& options);

}  // namespace demo
