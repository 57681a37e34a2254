// SPDX-License-Identifier: MIT
// client_demo: a client of the sky service that flies over its frames (README.md).
//   client_demo [--socket PATH]                      a window (keys in window.h)
//   client_demo --headless --frames N --out DIR      a scripted flight captured to PNG + JSON files
// Exit codes: 0 ok, 1 runtime failure (no service, no frame, no window), 2 bad command line.
#include "client_demo/demo_options.h"
#include "client_demo/headless_run.h"

#ifdef DEMO_HAVE_WINDOW
#include "client_demo/windowed_run.h"
#endif

#include <csignal>
#include <cstdio>

int main(int argc, char** argv)
{
    demo::DemoOptions options;
    if (int code = demo::parseDemoOptions(argc, argv, options); code >= 0)
        return code;
    // A service that goes away mid-write must end in an error reply, not a SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    if (options.headless)
        return demo::runHeadless(options);
#ifdef DEMO_HAVE_WINDOW
    return demo::runWindowed(options);
#else
    std::fprintf(stderr, "client_demo: built without GLFW: only --headless is available\n");
    return 2;
#endif
}
