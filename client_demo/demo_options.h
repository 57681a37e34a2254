// SPDX-License-Identifier: MIT
// client_demo's command line (README.md lists every option).
#pragma once

#include "client_demo/compositor.h"
#include "client_demo/flight_model.h"
#include "client_demo/skyclient_source.h"

#include <string>

namespace demo
{

/// Everything the command line sets.
struct DemoOptions
{
    std::string socketPath;       ///< the service's control socket
    Transport transport = Transport::Auto;
    bool headless = false;        ///< capture to files instead of opening a window
    unsigned frames = 0;          ///< frames to capture or show; 0 = headless 8, window until closed
    std::string outDir = "out/demo";  ///< headless: where frame-NNNN.png and .json go
    std::string screenshotPath;   ///< window: write the last presented image here (PNG)
    unsigned width = 640;         ///< rendered frame size (pixels); also the window's first size
    unsigned height = 360;
    ViewAngles angles;            ///< the frustum (--fov or --frustum)
    Aircraft aircraft;            ///< where the flight starts
    std::string timeIso;          ///< "" = keep the service's time
    double rate = 0.0;            ///< simulated s per real s, sent with --time
    double stepS = 1.0;           ///< headless: simulated flight seconds between frames
    bool ground = true;           ///< composite the demo ground
    CompositeMode composite = CompositeMode::Layers;  ///< layers (shared memory only) or the display frame
    int frameTimeoutMs = 120000;  ///< longest wait for one frame (lavapipe at high quality is slow)
};

/**
 * Parses argv. Prints help or the error itself.
 *
 * @return -1 to go on, else the exit code (0 after --help, 2 for a bad command line).
 **********************************************************************/
int parseDemoOptions(int argc, char** argv, DemoOptions& options);

/// The compositing the options ask for: the mode, and the demo's mountain ahead of the flight's start.
CompositeOptions compositeOptionsOf(const DemoOptions& options);

/// The service's default socket: $XDG_RUNTIME_DIR/skyservice.sock, else /tmp/skyservice-<uid>.sock.
std::string defaultSocketPath();

}  // namespace demo
