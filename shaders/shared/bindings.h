// SPDX-License-Identifier: MIT
// Compile-time limits and descriptor slots shared by GLSL and C++ (docs/style.md §7). Each value says why.
#ifndef SKY_SHARED_BINDINGS_H
#define SKY_SHARED_BINDINGS_H
#include "shaders/shared/prelude.h"

// Volumetric layers per weather window: up to 4 (low, middle, convective, spare; docs/model.md).
#define MAX_CLOUD_LAYERS 4

// 8x8 = 64 invocations: a multiple of both NVIDIA's 32-wide warps and lavapipe's 8-wide SIMD.
#define WORKGROUP_SIZE_2D 8
// 4x4x4 = 64 invocations for 3D noise generation, for the same reason.
#define WORKGROUP_SIZE_3D 4
// Pixels per axis of the quad each reconstruct invocation handles (shaders/clouds/reconstruct.comp.glsl):
// 1 or 2 (a 2x2 quad lies inside one march block for every block size, so its pixels share one fresh
// neighbourhood). 1 is faster in still views and about as fast in motion, on GPUs and on lavapipe
// (BENCHMARKS.md).
#define RECONSTRUCT_QUAD_PX 1

// Noise texture sizes (docs/model.md: Perlin-Worley 128^3 RGBA8, Worley 32^3, 2D curl noise).
#define BASE_NOISE_SIZE 128
#define DETAIL_NOISE_SIZE 32
#define CURL_NOISE_SIZE 128
// Blue noise tile for the march's start offset: 64^2 is big enough that the pattern is not visible.
#define BLUE_NOISE_SIZE 64

// Weather window: a camera-centred square texture grid (see weather_window.h).
// 256 texels over the default 1600 km gives 6.25 km texels, finer than 0.25-degree model data.
#define WEATHER_WINDOW_SIZE 256

// How the shaders see the per-frame and atmosphere parameter blocks: uniform buffers (NVIDIA reads them
// through its constant cache: the march is faster than with storage buffers, BENCHMARKS.md),
// or std140 readonly storage buffers in the `.storage.spv` variant that CMake
// builds of every shader with SKY_PARAMS_IN_STORAGE_BUFFERS (lavapipe, Mesa 22.3, leaks ~0.5 MB per
// frame with uniform buffers bound through push descriptors; skyservice/vk/context.h picks).
#ifdef SKY_PARAMS_IN_STORAGE_BUFFERS
#define PARAMS_BLOCK readonly buffer
#else
#define PARAMS_BLOCK uniform
#endif

#endif
