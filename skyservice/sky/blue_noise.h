// SPDX-License-Identifier: MIT
// Tileable blue-noise dither mask for the cloud march's start offset (docs/model.md "blue-noise start offset").
#pragma once

#include <cstdint>
#include <vector>

namespace sky
{

/// Builds a size x size blue-noise dither mask with Ulichney's void-and-cluster method (Ulichney,
/// "The void-and-cluster method for dither array generation", SPIE 1913, 1993): Gaussian energy filter
/// (sigma 1.5 texels) on a torus, so the mask tiles without seams.
///
/// @param[in] size edge length in texels (>= 4; BLUE_NOISE_SIZE = 64 takes a few milliseconds).
/// @param[in] seed selects the random initial pattern; the same seed always gives the same mask.
/// @return size*size bytes, row-major (index y * size + x). Each texel's value is its rank in the
///   void-and-cluster order scaled to 0..255 (rank * 256 / (size*size)), so every level is used equally
///   often (size*size/256 times when size*size is a multiple of 256) and the mask has little
///   low-frequency energy. Throws std::invalid_argument when size < 4.
std::vector<uint8_t> makeBlueNoise(uint32_t size, uint32_t seed);

}  // namespace sky
