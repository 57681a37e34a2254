// SPDX-License-Identifier: MIT
// Radial warp of the weather window (skyservice/weather/weather_window.h, windowWarpM, is the same formula
// in double): q = p (E + r0) / (|p| + r0). Fine texels near the eye, coarse toward the horizon.

// Window-plane position q (metres) of the point at map position p (metres east/north of the eye).
vec2 windowWarp(vec2 p, float halfExtentM, float warpRadiusM)
{
    if (warpRadiusM <= 0.0f)
        return p;
    return p * ((halfExtentM + warpRadiusM) / (length(p) + warpRadiusM));
}
