// SPDX-License-Identifier: MIT
// Column bounds of the weather window: for each window texel, the lowest cloud base and the highest cloud
// top that any density lookup in that texel's cell can see, with a min/max pyramid over 2x2 texels. The
// march's search skips a stretch of ray whose altitudes lie above every top or below every base of the
// columns it crosses (shaders/clouds/empty_space.glsl), instead of sampling empty air step by step:
// looking up through the shell or grazing above a deck, most search samples found nothing.
//
// Built on the CPU with the window (skyservice/weather/column_bounds.h). Level 0 is conservative for the
// bilinear weather lookups: a point inside texel c's cell interpolates texels of c's 3x3 neighbourhood, so
// a layer counts at c when its coverage reaches CLOUD_COVERAGE_MIN anywhere in that neighbourhood, with
// the lowest base and highest top found there (the anvil slice is one more layer). Level l >= 1 texel
// (i, j) is the min of the bases and the max of the tops of level l-1 texels (2i..2i+1, 2j..2j+1).
//
// Storage: one R8G8_UINT 2D atlas, COLUMN_BOUNDS_WIDTH x WEATHER_WINDOW_SIZE (0.2 MB at 256): level 0 at
// (0, 0), level l >= 1 at columnBoundsLevelOrigin(l, N), side WEATHER_WINDOW_SIZE >> l. R: base in units of
// COLUMN_BOUNDS_UNIT_M rounded down less one (0: no lower bound); G: top rounded up plus one (255: no
// upper bound; 0: no cloud). The extra unit covers the half-float rounding of the window (8 m steps up to
// 16 km). An empty column reads R 255, G 0.
#ifndef SKY_SHARED_COLUMN_BOUNDS_H
#define SKY_SHARED_COLUMN_BOUNDS_H
#include "shaders/shared/weather_window.h"

#define COLUMN_BOUNDS_UNIT_M 64.0f  // 255 units: 16.3 km, the top of the troposphere's tallest cells
#define COLUMN_BOUNDS_LEVELS 9      // log2(WEATHER_WINDOW_SIZE) + 1: the last level is one texel
// What a decoded bound reads where the code says "no bound" (m, with the sign of the side it opens).
#define COLUMN_BOUNDS_NONE_M 1e9f
// Atlas texel of the origin of pyramid level `level` of a window `size` texels a side (level 0 at the
// origin; the others stacked in a column to its right, level l at row size - 2 (size >> l)).
#ifdef __cplusplus
inline  // a header function in C++ (GLSL has no linker)
#endif
ivec2 columnBoundsLevelOrigin(int level, int size)
{
    if (level == 0)
        return ivec2(0, 0);
    return ivec2(size, size - 2 * (size >> level));
}

// The lowest base (m) a base code stands for: -COLUMN_BOUNDS_NONE_M for 0 (no lower bound).
#ifdef __cplusplus
inline
#endif
float columnBoundsBaseM(uint code)
{
    return code == 0u ? -COLUMN_BOUNDS_NONE_M : float(code) * COLUMN_BOUNDS_UNIT_M;
}

// The highest top (m) a top code stands for: -COLUMN_BOUNDS_NONE_M for 0 (no cloud), +COLUMN_BOUNDS_NONE_M
// for 255 (no upper bound).
#ifdef __cplusplus
inline
#endif
float columnBoundsTopM(uint code)
{
    return code == 0u ? -COLUMN_BOUNDS_NONE_M : code == 255u ? COLUMN_BOUNDS_NONE_M : float(code) * COLUMN_BOUNDS_UNIT_M;
}

#endif
