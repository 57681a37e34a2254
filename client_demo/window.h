// SPDX-License-Identifier: MIT
// The demo's GLFW window (docs/style.md §15: the only window in the project): creation, its Vulkan surface, and the
// pilot's keys and mouse turned into a FlightInput.
//
// Keys: A/D or Left/Right turn, W/S or Up/Down pitch (W = nose up), Q/E slower/faster, R/F or
// PageUp/PageDown climb/descend, T time of day +1 h, G ground on/off, Esc quit. Left mouse drag: look
// (heading and pitch).
#pragma once

#include "client_demo/flight_model.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace demo
{

/// One-shot events since the last readInput (held keys are polled, presses are counted).
struct WindowEvents
{
    int timeJumpHours = 0;   ///< T presses
    bool toggleGround = false;
    bool quit = false;       ///< Esc or the close button
};

/// The window and what its callbacks collected.
struct DemoWindow
{
    GLFWwindow* window = nullptr;
    WindowEvents pending;          ///< filled by the key callback
    double dragX = 0.0;            ///< mouse movement with the left button held since the last read (pixels)
    double dragY = 0.0;
    double lastCursorX = 0.0;
    double lastCursorY = 0.0;
    bool dragging = false;
};

/**
 * Initialises GLFW (once) and opens a resizable window without a client API (Vulkan presents into it).
 *
 * @return false (error says why: no display, no Vulkan loader for GLFW) when it cannot.
 **********************************************************************/
bool createDemoWindow(DemoWindow& window, uint32_t width, uint32_t height, const std::string& title, std::string& error);

/// Closes the window and terminates GLFW.
void destroyDemoWindow(DemoWindow& window);

/// The instance extensions GLFW needs for a surface on this platform.
std::vector<const char*> windowInstanceExtensions();

/// Creates the window's surface (VK_NULL_HANDLE on failure).
VkSurfaceKHR createWindowSurface(DemoWindow& window, VkInstance instance);

/// The framebuffer size now (pixels; 0 while minimised).
void framebufferSize(const DemoWindow& window, uint32_t& width, uint32_t& height);

/**
 * Polls events and turns held keys and the mouse drag into this frame's input.
 *
 * @param[out] events one-shot events since the last call.
 **********************************************************************/
FlightInput readInput(DemoWindow& window, WindowEvents& events);

}  // namespace demo
