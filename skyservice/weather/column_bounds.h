// SPDX-License-Identifier: MIT
// The column-bounds pyramid of a weather window (layout and meaning: shaders/shared/column_bounds.h),
// which lets the march skip empty stretches of its rays.
#pragma once

#include "skyservice/weather/weather_window.h"

#include <cstdint>
#include <vector>

namespace sky
{

/// Base and top bounds of one column, decoded (metres; -inf / +inf where the code says "no bound").
struct ColumnBound
{
    float minBaseM;
    float maxTopM;
    bool empty() const { return maxTopM < minBaseM; }
};

/// The R8G8 atlas of `window` (after computeAnvils): columnBoundsWidth(n) x n texels of 2 bytes, rows of
/// increasing northing as in the window. Non-finite bases or tops count as unbounded.
std::vector<uint8_t> buildColumnBounds(const WeatherWindow& window);

/// Atlas width for a window of `size` texels a side.
inline uint32_t columnBoundsWidth(uint32_t size) { return size + size / 2; }

/// The decoded bound of texel (i, j) of pyramid level `level` in `atlas` (a window `size` texels a side).
ColumnBound columnBoundAt(const std::vector<uint8_t>& atlas, uint32_t size, int level, uint32_t i, uint32_t j);

}  // namespace sky
