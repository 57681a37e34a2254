// SPDX-License-Identifier: MIT
// The order in which the cloud march's workgroup rows run, and what each row cost (docs/model.md).
//
// Why: in a reprojected frame the GPU holds most of the march's workgroups at once, and the frame ends
// when the last of them does. The costly rays (the horizon band, a Cb tower, a deck seen edge-on) take
// 5-7x the lookups of the median ray (BENCHMARKS.md); launched last, they ran after
// the cheap rows instead of alongside them. So each frame the march counts the density
// lookups of every workgroup row, and the next frame launches the rows costliest first
// (skyservice/render/march_order.h). On lavapipe, which hands each thread a contiguous range of
// workgroups, the rows are dealt so that every thread's range costs about the same.
//
// A row here is one row of march workgroups: WORKGROUP_SIZE_2D rows of march pixels (or of blocks in a
// reprojected frame). The order never changes a pixel: every invocation marches the same ray whichever
// workgroup runs it.
#ifndef SKY_SHARED_MARCH_ORDER_H
#define SKY_SHARED_MARCH_ORDER_H
#include "shaders/shared/bindings.h"

// Workgroup rows at most: 8192 pixels (the largest image a request may ask for, renderer.cpp) / 8 at
// block 1.
#define MARCH_ORDER_MAX_ROWS 1024u

// The storage buffer's layout (std430, uint32 each): rowOrder[MARCH_ORDER_MAX_ROWS], the image row of
// workgroups the i-th workgroup row of the dispatch marches (written by the host, a permutation of the
// frame's rows), then rowLookups[MARCH_ORDER_MAX_ROWS], per image row the sum over its workgroups of the
// largest density-lookup count of their rays (zeroed by the host, added to by the march).
#define MARCH_ORDER_BUFFER_BYTES (2u * MARCH_ORDER_MAX_ROWS * 4u)

#endif
