// SPDX-License-Identifier: MIT
// Temporal reconstruction of the cloud image (DESIGN §3 "Temporal reprojection", issue 5).
//
// The march marched one pixel of every BxB block this frame (B = frame.reprojection.x: 4, or 2 and 1
// near and inside a cloud layer; position frame.reprojection.yz in the block) into a block-resolution
// image. Every full-resolution pixel here is either that fresh pixel, taken as is, or the previous
// frame's cloud image reprojected: the pixel's ray is followed to the
// cloud depth of its nearest fresh pixel (or to infinity where that ray saw no cloud), the point is
// projected into the previous camera (axes and eye given relative to the current eye, computed in
// double on the CPU), and the previous image is read there. History is rejected when that lands off
// screen, when the previous depth there disagrees with the expected one (disocclusion), or when it
// lies outside the range of the fresh 3x3 neighbourhood (colour clamp); a rejected pixel takes its
// nearest fresh pixel's value, a pixel without any history (off the previous screen, or no history)
// the fresh pixels interpolated. The result is this frame's cloud history, packed in 64 bits a texel
// (shaders/lib/cloud_history.glsl): the composite reads the pixels not marched this frame from it (the
// marched ones from the fresh image, at full precision), and the next frame reprojects it.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shaders/shared/frame_params.h"
#include "shaders/lib/cloud_history.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1, rgba16f) uniform readonly image2D freshCloud;   // block resolution
layout(binding = 2, r32f) uniform readonly image2D freshDepth;      // block resolution
// The previous frame's cloud radiance, alpha and depth, full resolution, packed (cloud_history.glsl).
layout(binding = 3, rgba16ui) uniform readonly uimage2D historyIn;
// This frame's: the composite reads it (for the pixels not marched this frame), the next frame reprojects it.
layout(binding = 4, rgba16ui) uniform writeonly uimage2D historyOut;

#include "shaders/clouds/view_ray.glsl"

// Relative tolerance on the previous depth before a pixel counts as disoccluded (our choice: the
// transmittance-weighted depth of a cumulus moves by less than 10% between neighbouring rays), and
// the absolute floor of that tolerance (m).
const float kDepthTolerance = 0.1f;
const float kDepthToleranceFloorM = 100.0f;
// The colour box of the fresh neighbourhood is widened by this share of its size on each side plus an
// absolute margin (pre-exposed radiance is ~1 by day): fresh pixels are B pixels apart, so detail
// between them is often outside their range and still right. Measured on the 2-degree pan of
// tests/gpu/test_reprojection.cpp: a box not widened loses ~1.5 dB against full-resolution renders,
// widened by its size ~0.1 dB, while gross misses (a cloud reprojected onto clear sky) stay rejected.
const float kClampWiden = 1.0f;
const float kClampMargin = 0.02f;

// History within this many pixels of where it was counts as still (not colour-clamped).
const float kStillPx = 0.01f;

vec4 historyCloud(ivec2 p)
{
    float depthM;
    return unpackCloudHistory(imageLoad(historyIn, p), depthM);
}

float historyDepth(ivec2 p)
{
    float depthM;
    unpackCloudHistory(imageLoad(historyIn, p), depthM);
    return depthM;
}

// Bilinear read of the previous cloud image at pixel coordinates `q` (premultiplied colour and alpha
// interpolate correctly); a nearest read would shift every reprojected pixel by up to half a pixel.
vec4 bilinearHistory(vec2 q)
{
    vec2 t = q - 0.5f;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - vec2(i0);
    ivec2 top = ivec2(frame.image.xy) - 1;
    vec4 c00 = historyCloud(clamp(i0, ivec2(0), top));
    vec4 c10 = historyCloud(clamp(i0 + ivec2(1, 0), ivec2(0), top));
    vec4 c01 = historyCloud(clamp(i0 + ivec2(0, 1), ivec2(0), top));
    vec4 c11 = historyCloud(clamp(i0 + ivec2(1, 1), ivec2(0), top));
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// The fresh pixels interpolated bilinearly at `pixel`: what a pixel without any history shows. Fresh
// pixels sit B pixels apart, at b * B + phase; outside their grid (the image borders) the nearest row or
// column is extended. Measured on the turns of tests/gpu/test_flight_path.cpp: the worst 8-pixel band
// the view turns toward is 0.7-1.7 dB closer to the full render than with the nearest fresh pixel, which
// copies B x B blocks there; for rejected history inside the image the nearest pixel measured better.
vec4 freshBilinear(ivec2 pixel, ivec2 phase, int B)
{
    ivec2 blocks = (ivec2(frame.image.xy) - phase + B - 1) / B;  // fresh pixels per row and column
    vec2 u = vec2(pixel - phase) / float(B);
    ivec2 b0 = ivec2(floor(u));
    vec2 f = u - vec2(b0);
    ivec2 top = blocks - 1;
    vec4 c00 = imageLoad(freshCloud, clamp(b0, ivec2(0), top));
    vec4 c10 = imageLoad(freshCloud, clamp(b0 + ivec2(1, 0), ivec2(0), top));
    vec4 c01 = imageLoad(freshCloud, clamp(b0 + ivec2(0, 1), ivec2(0), top));
    vec4 c11 = imageLoad(freshCloud, clamp(b0 + ivec2(1, 1), ivec2(0), top));
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

void writeAll(ivec2 pixel, vec4 cloud, float depth)
{
    imageStore(historyOut, pixel, packCloudHistory(cloud, depth));
}

// Projects `v` (from the previous eye, current ENU axes) into the previous image: pixel coordinates
// in `q`, false when behind the previous camera or off its screen.
bool projectPrevious(vec3 v, out vec2 q)
{
    q = vec2(-1.0f);
    float z = dot(v, frame.previousForward.xyz);
    if (z <= 0.0f)
        return false;
    vec2 ndc = vec2(dot(v, frame.previousRight.xyz) / (z * frame.previousRight.w),
                    -dot(v, frame.previousUp.xyz) / (z * frame.previousUp.w));
    q = (ndc + 1.0f) * 0.5f * vec2(frame.image.xy);
    return q.x >= 0.0f && q.y >= 0.0f && q.x < float(frame.image.x) && q.y < float(frame.image.y);
}

void main()
{
    ivec2 pixel = ivec2(permutedPixel(gl_GlobalInvocationID.xy));
    if (pixel.x >= int(frame.image.x) || pixel.y >= int(frame.image.y))
        return;
    const int B = int(frame.reprojection.x);  // 4; 2 or 1 near or inside a cloud layer
    ivec2 phase = ivec2(int(frame.reprojection.y), int(frame.reprojection.z));
    ivec2 block = pixel / B;
    if (pixel == block * B + phase)
    {
        writeAll(pixel, imageLoad(freshCloud, block), imageLoad(freshDepth, block).x);
        return;
    }

    // The fresh 3x3 neighbourhood: its colour range and the fresh pixel nearest to this one.
    vec4 lo = vec4(1e30f);
    vec4 nearest = vec4(0.0f);
    vec4 hi = vec4(-1e30f);
    float nearestDepth = 0.0f;
    int nearestD2 = 1 << 30;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
            ivec2 b = block + ivec2(dx, dy);
            ivec2 p = b * B + phase;
            if (b.x < 0 || b.y < 0 || p.x >= int(frame.image.x) || p.y >= int(frame.image.y))
                continue;
            vec4 c = imageLoad(freshCloud, b);
            lo = min(lo, c);
            hi = max(hi, c);
            ivec2 d = p - pixel;
            int d2 = d.x * d.x + d.y * d.y;
            if (d2 < nearestD2)
            {
                nearestD2 = d2;
                nearest = c;
                nearestDepth = imageLoad(freshDepth, b).x;
            }
        }
    if (frame.reprojection.w == 0u)
    {
        writeAll(pixel, freshBilinear(pixel, phase, B), nearestDepth);
        return;
    }

    // Where was this pixel's cloud in the previous frame? Project the direction alone first (exact for
    // anything far away), read the previous depth found there, and project again at that depth (one
    // fixed-point step: follows the parallax of near clouds when the eye moves; exact for a still
    // camera). Zero depth (no cloud) keeps the direction alone. Starting from the previous depth at
    // this pixel instead measured 1-2 dB worse on a pan with 50-200 m of eye motion per frame.
    vec3 dir = viewRayDirection(vec2(pixel) + 0.5f);
    vec2 q = vec2(0.0f);
    vec3 v = dir;
    float depthGuess = 0.0f;
    bool accept = true;
    float previousDepth = 0.0f;
    for (int pass = 0; pass < 2 && accept; ++pass)
    {
        v = depthGuess > 0.0f ? dir * depthGuess - frame.previousEye.xyz : dir;
        accept = projectPrevious(v, q);
        if (!accept)
            break;
        previousDepth = historyDepth(ivec2(q));
        // The previous depth is measured from the previous eye: the distance from this eye.
        depthGuess = previousDepth > 0.0f ? length(frame.previousEye.xyz + normalize(v) * previousDepth) : 0.0f;
    }
    bool onScreen = accept;
    vec4 previous = vec4(0.0f);
    if (accept)
    {
        // A pixel that lands where it was (a still view) keeps its history whatever its neighbours say:
        // it was marched at this very place, and the 16-frame refresh brings in what changed since.
        bool still = distance(q, vec2(pixel) + 0.5f) < kStillPx;
        previous = still ? historyCloud(pixel) : bilinearHistory(q);
        // Disocclusion: the fixed point did not settle: the refined depth, seen from the previous eye,
        // disagrees with the previous depth found there (the ray crossed a cloud edge of another distance).
        if (previousDepth > 0.0f && depthGuess > 0.0f)
        {
            float expected = length(dir * depthGuess - frame.previousEye.xyz);
            accept = abs(previousDepth - expected) <= kDepthTolerance * expected + kDepthToleranceFloorM;
        }
        // Colour clamp against the fresh neighbourhood.
        vec4 margin = kClampWiden * (hi - lo) + kClampMargin;
        bool inBox = all(greaterThanEqual(previous, lo - margin)) && all(lessThanEqual(previous, hi + margin));
        accept = accept && (still || inBox);
    }
    if (!accept)
    {
        // Rejected history (disocclusion, colour clamp) takes the nearest fresh pixel: a sharp value
        // beside a cloud edge; no history at all (the border the view turns toward) the interpolated
        // fresh pixels, which do not copy 4x4 blocks there.
        writeAll(pixel, onScreen ? nearest : freshBilinear(pixel, phase, B), nearestDepth);
        return;
    }
    writeAll(pixel, previous, depthGuess);
}
