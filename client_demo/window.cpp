// SPDX-License-Identifier: MIT
#include "client_demo/window.h"

// GLFW_INCLUDE_NONE (set by CMake): no OpenGL headers. vulkan.h (from window.h) comes first so that GLFW
// declares its Vulkan functions.
#include <GLFW/glfw3.h>

namespace demo
{
namespace
{

// Rates of the controls (chosen to feel like a light aircraft at the defaults).
constexpr double kTurnDegPerS = 30.0;
constexpr double kPitchDegPerS = 20.0;
constexpr double kSpeedMpsPerS = 50.0;
constexpr double kClimbMps = 150.0;
constexpr double kMouseDegPerPixel = 0.15;

DemoWindow& owner(GLFWwindow* w) { return *static_cast<DemoWindow*>(glfwGetWindowUserPointer(w)); }

void onKey(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/)
{
    if (action != GLFW_PRESS)
        return;
    WindowEvents& e = owner(w).pending;
    if (key == GLFW_KEY_T)
        ++e.timeJumpHours;
    else if (key == GLFW_KEY_G)
        e.toggleGround = !e.toggleGround;
    else if (key == GLFW_KEY_ESCAPE)
        e.quit = true;
}

void onMouseButton(GLFWwindow* w, int button, int action, int /*mods*/)
{
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    DemoWindow& d = owner(w);
    d.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &d.lastCursorX, &d.lastCursorY);
}

void onCursor(GLFWwindow* w, double x, double y)
{
    DemoWindow& d = owner(w);
    if (d.dragging)
    {
        d.dragX += x - d.lastCursorX;
        d.dragY += y - d.lastCursorY;
    }
    d.lastCursorX = x;
    d.lastCursorY = y;
}

bool held(GLFWwindow* w, int a, int b) { return glfwGetKey(w, a) == GLFW_PRESS || glfwGetKey(w, b) == GLFW_PRESS; }

}  // namespace

bool createDemoWindow(DemoWindow& d, uint32_t width, uint32_t height, const std::string& title, std::string& error)
{
    if (glfwInit() != GLFW_TRUE)
    {
        const char* why = nullptr;
        glfwGetError(&why);
        error = std::string("GLFW cannot start (no display?): ") + (why ? why : "unknown");
        return false;
    }
    if (glfwVulkanSupported() != GLFW_TRUE)
    {
        error = "GLFW finds no Vulkan loader";
        glfwTerminate();
        return false;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    d.window = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (d.window == nullptr)
    {
        const char* why = nullptr;
        glfwGetError(&why);
        error = std::string("cannot open a window: ") + (why ? why : "unknown");
        glfwTerminate();
        return false;
    }
    glfwSetWindowUserPointer(d.window, &d);
    glfwSetKeyCallback(d.window, onKey);
    glfwSetMouseButtonCallback(d.window, onMouseButton);
    glfwSetCursorPosCallback(d.window, onCursor);
    return true;
}

void destroyDemoWindow(DemoWindow& d)
{
    if (d.window != nullptr)
    {
        glfwDestroyWindow(d.window);
        glfwTerminate();
    }
    d = DemoWindow{};
}

std::vector<const char*> windowInstanceExtensions()
{
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    return names ? std::vector<const char*>(names, names + count) : std::vector<const char*>{};
}

VkSurfaceKHR createWindowSurface(DemoWindow& d, VkInstance instance)
{
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(instance, d.window, nullptr, &surface) != VK_SUCCESS)
        return VK_NULL_HANDLE;
    return surface;
}

void framebufferSize(const DemoWindow& d, uint32_t& width, uint32_t& height)
{
    int w = 0;
    int h = 0;
    glfwGetFramebufferSize(d.window, &w, &h);
    width = uint32_t(w > 0 ? w : 0);
    height = uint32_t(h > 0 ? h : 0);
}

FlightInput readInput(DemoWindow& d, WindowEvents& events)
{
    glfwPollEvents();
    GLFWwindow* w = d.window;
    FlightInput in;
    in.turnDegPerS = kTurnDegPerS * ((held(w, GLFW_KEY_D, GLFW_KEY_RIGHT) ? 1 : 0) - (held(w, GLFW_KEY_A, GLFW_KEY_LEFT) ? 1 : 0));
    in.pitchDegPerS = kPitchDegPerS * ((held(w, GLFW_KEY_W, GLFW_KEY_UP) ? 1 : 0) - (held(w, GLFW_KEY_S, GLFW_KEY_DOWN) ? 1 : 0));
    in.speedMpsPerS = kSpeedMpsPerS * ((held(w, GLFW_KEY_E, GLFW_KEY_E) ? 1 : 0) - (held(w, GLFW_KEY_Q, GLFW_KEY_Q) ? 1 : 0));
    in.climbMps = kClimbMps * ((held(w, GLFW_KEY_R, GLFW_KEY_PAGE_UP) ? 1 : 0) - (held(w, GLFW_KEY_F, GLFW_KEY_PAGE_DOWN) ? 1 : 0));
    in.mouseHeadingDeg = d.dragX * kMouseDegPerPixel;
    in.mousePitchDeg = -d.dragY * kMouseDegPerPixel;
    d.dragX = d.dragY = 0.0;
    events = d.pending;
    events.quit = events.quit || glfwWindowShouldClose(w) == GLFW_TRUE;
    d.pending = WindowEvents{};
    return in;
}

}  // namespace demo
