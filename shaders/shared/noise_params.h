// SPDX-License-Identifier: MIT
// Interface of the noise generation passes (base_noise, detail_noise, curl_noise), shared by GLSL and C++.
//
// Each pass writes one storage image at binding NOISE_BINDING_OUTPUT, one invocation per texel, and
// takes a NoisePush as its push constants. The host dispatches sizeTexels^3 (3D) or sizeTexels^2 (2D)
// threads; dispatch() derives the group counts from the reflected local size.
//
//   base_noise   : BASE_NOISE_SIZE^3   rgba8   R = Perlin-Worley, G,B,A = Worley FBM at 3 increasing frequencies
//   detail_noise : DETAIL_NOISE_SIZE^3 rgba8   R,G,B = Worley FBM at 3 increasing frequencies, A = their weighted sum
//   curl_noise   : CURL_NOISE_SIZE^2   rgba16f xy = curl vector (about [-1,1]), zw = 0
//
// Every texture tiles seamlessly (the noise is periodic in the texture size) and depends only on the
// seed: the same seed gives the same bytes on every device that rounds floats the same way.
#ifndef SKY_SHARED_NOISE_PARAMS_H
#define SKY_SHARED_NOISE_PARAMS_H
#include "shaders/shared/bindings.h"

// binding 0: the output storage image (image3D rgba8 or image2D rgba16f)
#define NOISE_BINDING_OUTPUT 0

// Workgroups of 8x1x1 (2D: 8x1), not WORKGROUP_SIZE_3D^3: llvmpipe (lavapipe) runs a workgroup as
// 8-wide SIMD chunks and the per-chunk overhead (coroutine switches, probably) dominates: there
// (Mesa 22.3, LLVM 15) 8x1x1 makes the base texture many times faster than 4x4x4, with identical
// output. The noise runs once at start-up, so partly filled warps on real GPUs cost nothing that matters.
#define NOISE_WORKGROUP_SIZE 8

// Lattice periods (cells per texture tile) of the lowest octave of each texture; octave i has period << i.
// Any texture size tiles (the noise is periodic in texture coordinates), but a cell should span at least
// 2 texels or the octave turns into white noise.
// Base: 4 Perlin cells per tile (4 octaves: 4..32) and Worley octaves of 4..64 cells, so the finest spans
// 2 texels at 128^3 (Schneider 2015: a few large cells per tile for the low-frequency shape).
#define BASE_NOISE_PERLIN_PERIOD 4
#define BASE_NOISE_PERLIN_OCTAVES 4
#define BASE_NOISE_WORLEY_PERIOD 4
// Detail: Worley octaves of 2..32 cells at 32^3; the 32-cell octave only enters the B channel at 12.5%.
#define DETAIL_NOISE_WORLEY_PERIOD 2
// Curl: 4 gradient-noise cells per tile at the lowest of CURL_NOISE_OCTAVES octaves.
#define CURL_NOISE_PERIOD 4
#define CURL_NOISE_OCTAVES 3

// Salts that decorrelate the noise functions sharing one seed.
#define NOISE_SALT_PERLIN 0x1000u
#define NOISE_SALT_WORLEY 0x2000u
#define NOISE_SALT_CURL 0x3000u
#define NOISE_SALT_DETAIL 0x4000u

// 16 bytes of push constants (well under the 128 bytes Vulkan guarantees).
struct NoisePush
{
    uint seed;        // any value; the same seed gives the same texture
    uint sizeTexels;  // edge length of the image in texels (e.g. BASE_NOISE_SIZE)
    uint pad0;
    uint pad1;
};

#endif
