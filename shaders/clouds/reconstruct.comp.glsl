// SPDX-License-Identifier: MIT
// Temporal reconstruction of the cloud image (docs/model.md).
//
// The march marched one pixel of every BxB block this frame (B = frame.reprojection.blockPx: 4, or 2 and 1
// near and inside a cloud layer; position frame.reprojection.phasePx in the block) into a block-resolution
// image; in a turn or a pitch change, it also marched every pixel of the columns or rows the previous
// frame did not see (shaders/lib/new_lines.glsl), taken as is too. Every other pixel is either its
// block's fresh pixel, taken as is, or the previous frame's cloud image reprojected: the pixel's ray is
// followed to the cloud depth of its nearest fresh pixel (or to infinity where that ray saw no cloud), the point is
// projected into the previous camera (axes and eye given relative to the current eye, computed in
// double on the CPU), and the previous image is read there. History is rejected when that lands off
// screen, when the previous depth there disagrees with the expected one (disocclusion), or when it
// lies outside the range of the fresh 3x3 neighbourhood (colour clamp); a rejected pixel takes its
// nearest fresh pixel's value, a pixel without any history (off the previous screen, or no history)
// the fresh pixels interpolated. The result is this frame's cloud history, 8 bytes a texel in two images
// (shaders/lib/cloud_history.glsl): the composite reads the pixels not marched this frame from it (the
// marched ones from the fresh image, at full precision), and the next frame reprojects it.
//
// Cost (this pass is a large share of a reprojected frame's time budget, BENCHMARKS.md):
// the fresh neighbourhood is loaded only when a pixel's history moved (a still
// pixel is never colour-clamped), and once for all the pixels of an invocation's quad
// (RECONSTRUCT_QUAD_PX^2 pixels, inside one block for every block size: B = 4 or 2, and B = 1 marches
// every pixel); the nearest fresh pixel is computed, not searched with a depth load per candidate; the
// alpha and depth texel found by the depth fixed point is read once and serves the still pixel too.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shaders/shared/frame_params.h"
#include "shaders/lib/cloud_history.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1, rgba16f) uniform readonly image2D freshCloud;   // block resolution
layout(binding = 2, r32f) uniform readonly image2D freshDepth;      // block resolution
// The previous frame's cloud history, full resolution (shaders/lib/cloud_history.glsl): sampled views the
// texture unit decodes (colour E5B9G9R9, alpha and depth code R16G16_UNORM), bilinear, clamped to the edge.
layout(binding = 3) uniform sampler2D historyColourIn;
layout(binding = 4) uniform sampler2D historyAlphaDepthIn;
// This frame's, as plain bits: the composite reads it (for the pixels not marched this frame), the next
// frame reprojects it.
layout(binding = 5, r32ui) uniform writeonly uimage2D historyColourOut;
layout(binding = 6, r32ui) uniform writeonly uimage2D historyAlphaDepthOut;
// The depth layer's front distance (FRAME_FLAG_DEPTH_LAYER; 1x1 stand-ins otherwise): the march's fresh
// fronts (block resolution) and a history of its own beside the cloud history, carried the way the depth is.
layout(binding = 7, r32f) uniform readonly image2D freshFront;
layout(binding = 8, r32f) uniform readonly image2D frontHistoryIn;
layout(binding = 9, r32f) uniform writeonly image2D frontHistoryOut;

#include "shaders/clouds/view_ray.glsl"
#include "shaders/lib/new_lines.glsl"

// Relative tolerance on the previous depth before a pixel counts as disoccluded (our choice: the
// transmittance-weighted depth of a cumulus moves by less than 10% between neighbouring rays), and
// the absolute floor of that tolerance (m).
const float kDepthTolerance = 0.1f;
const float kDepthToleranceFloorM = 100.0f;
// The colour box of the fresh neighbourhood is widened by this share of its size on each side plus an
// absolute margin (pre-exposed radiance is ~1 by day): fresh pixels are B pixels apart, so detail
// between them is often outside their range and still right. Widened by its own size, the box keeps
// that detail on a pan (tests/gpu/test_reprojection.cpp; figures in BENCHMARKS.md) while gross misses
// (a cloud reprojected onto clear sky) stay rejected.
const float kClampWiden = 1.0f;
const float kClampMargin = 0.02f;

// History within this many pixels of where it was counts as still (not colour-clamped).
const float kStillPx = 0.01f;

// The previous frame's cloud (premultiplied radiance, alpha) interpolated bilinearly at `uv` (normalized).
vec4 historySample(vec2 uv)
{
    return vec4(textureLod(historyColourIn, uv, 0.0f).rgb, textureLod(historyAlphaDepthIn, uv, 0.0f).x);
}

// Read of the previous cloud image at pixel coordinates `q` (premultiplied colour and alpha interpolate
// correctly). Catmull-Rom, not bilinear: a pixel lives on in the history for up to B x B frames and is
// resampled in each of them; bilinear weights blur it every time, and in a 60 deg/s turn the display lost
// ~30 % of its detail against a full render (tests/gpu/test_flight_path.cpp, sharpness.h), which the
// cubic's negative lobes keep. The 4x4 stencil without its corners (their weights, w0 w0, w0 w3, ..., are
// at most 0.0055; left out and the rest renormalized) is five bilinear reads: the inner 2x2 texels in one
// (the pair of weights w1, w2 of an axis is one read at w2 / (w1 + w2) between them, weighing w1 + w2),
// and each side's pair of the outer ring in one. The texture unit decodes and weighs the texels; unpacking
// twelve texels by hand and weighing them costs more GPU time a frame than these bilinear reads
// (BENCHMARKS.md). Its weights are rounded to 1/256 on common GPUs: the read is then off by at most 1/512 of
// the step between neighbouring texels. The overshoot is cut at 0 and at alpha 1; the colour clamp against
// the fresh neighbourhood follows. Where the inner read holds no cloud the result is 0 whatever the outer
// texels hold (their weights are never positive), so clear sky costs one read of each image.
vec4 cubicHistory(vec2 q)
{
    vec2 t = q - 0.5f;
    vec2 i1 = floor(t);
    vec2 f = t - i1;
    // Catmull-Rom weights of the taps at -1, 0, 1, 2 for the fractions f.x and f.y.
    vec2 f2 = f * f, f3 = f2 * f;
    vec2 w0 = 0.5f * (-f3 + 2.0f * f2 - f);
    vec2 w1 = 0.5f * (3.0f * f3 - 5.0f * f2 + 2.0f);
    vec2 w2 = 0.5f * (-3.0f * f3 + 4.0f * f2 + f);
    vec2 w3 = 0.5f * (f3 - f2);
    vec2 w12 = w1 + w2;  // >= 1 (w0, w3 <= 0 and the four sum to 1)
    vec2 toUv = 1.0f / vec2(uvec2(frame.image.widthPx, frame.image.heightPx));
    vec2 uvInner = (i1 + 0.5f + w2 / w12) * toUv;  // texel i1's centre is at i1 + 0.5
    vec2 uvBefore = (i1 - 0.5f) * toUv;            // the centre of texel i1 - 1 (clamped to the edge)
    vec2 uvAfter = (i1 + 2.5f) * toUv;             // of texel i1 + 2
    vec4 inner = historySample(uvInner);
    if (inner.w <= 0.0f)
        return vec4(0.0f);
    vec4 sum = w12.x * (w12.y * inner + w0.y * historySample(vec2(uvInner.x, uvBefore.y)) +
                        w3.y * historySample(vec2(uvInner.x, uvAfter.y))) +
               w12.y * (w0.x * historySample(vec2(uvBefore.x, uvInner.y)) +
                        w3.x * historySample(vec2(uvAfter.x, uvInner.y)));
    sum /= w12.x * (w12.y + w0.y + w3.y) + w12.y * (w0.x + w3.x);
    return vec4(max(sum.xyz, vec3(0.0f)), clamp(sum.w, 0.0f, 1.0f));
}

// Fresh pixels per row and column: they sit B pixels apart, at b * B + phase, inside the image.
ivec2 freshBlockCount(ivec2 phase, int B)
{
    return (ivec2(uvec2(frame.image.widthPx, frame.image.heightPx)) - phase + B - 1) / B;
}

// The fresh pixels interpolated bilinearly at `pixel`: what a pixel without any history shows. Outside
// the fresh pixels' grid (the image borders) the nearest row or column is extended. Bilinear, because
// the nearest fresh pixel copies B x B blocks into the band a turning view uncovers, which ends up
// further from the full render (tests/gpu/test_flight_path.cpp; figures in BENCHMARKS.md); for rejected
// history inside the image the nearest pixel does better.
vec4 freshBilinear(ivec2 pixel, ivec2 phase, int B)
{
    vec2 u = vec2(pixel - phase) / float(B);
    ivec2 b0 = ivec2(floor(u));
    vec2 f = u - vec2(b0);
    ivec2 top = freshBlockCount(phase, B) - 1;
    vec4 c00 = imageLoad(freshCloud, clamp(b0, ivec2(0), top));
    vec4 c10 = imageLoad(freshCloud, clamp(b0 + ivec2(1, 0), ivec2(0), top));
    vec4 c01 = imageLoad(freshCloud, clamp(b0 + ivec2(0, 1), ivec2(0), top));
    vec4 c11 = imageLoad(freshCloud, clamp(b0 + ivec2(1, 1), ivec2(0), top));
    return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// The block of the fresh pixel nearest to `pixel`. Distance separates into x and y, so each axis takes
// its nearer fresh column (row): round((pixel - phase) / B), halves rounded down (the earlier search
// over the 3x3 neighbourhood kept the first of equals, the lower one), then clamped to the fresh pixels
// inside the image (the nearest one along an axis when the rounded one lies outside). B is a power of
// two, so the float division is exact.
ivec2 nearestFreshBlock(ivec2 pixel, ivec2 phase, int B)
{
    ivec2 b = ivec2(floor(vec2(2 * (pixel - phase) + B - 1) / float(2 * B)));
    return clamp(b, ivec2(0), freshBlockCount(phase, B) - 1);
}

// The colour range of the fresh 3x3 neighbourhood of a block (the fresh pixels inside the image).
struct FreshBox
{
    bool loaded;
    vec4 lo;
    vec4 hi;
};

void loadFreshBox(ivec2 block, ivec2 phase, int B, INOUT(FreshBox) box)
{
    box.loaded = true;
    box.lo = vec4(1e30f);
    box.hi = vec4(-1e30f);
    ivec2 first = max(block - 1, ivec2(0));
    ivec2 last = min(block + 1, freshBlockCount(phase, B) - 1);
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x)
        {
            vec4 c = imageLoad(freshCloud, ivec2(x, y));
            box.lo = min(box.lo, c);
            box.hi = max(box.hi, c);
        }
}

// Projects `v` (from the previous eye, current ENU axes) into the previous image: pixel coordinates
// in `q`, false when behind the previous camera or off its screen. An off-centre frustum comes with
// shifted right and up axes (frame_params.h) and takes the same formula.
bool projectPrevious(vec3 v, out vec2 q)
{
    q = vec2(-1.0f);
    float z = dot(v, frame.reprojection.previous.forwardEnu);
    if (z <= 0.0f)
        return false;
    vec2 ndc = vec2(dot(v, frame.reprojection.previous.rightEnu) / (z * frame.reprojection.previous.halfWidthTan),
                    -dot(v, frame.reprojection.previous.upEnu) / (z * frame.reprojection.previous.halfHeightTan));
    q = (ndc + 1.0f) * 0.5f * vec2(uvec2(frame.image.widthPx, frame.image.heightPx));
    return q.x >= 0.0f && q.y >= 0.0f && q.x < float(frame.image.widthPx) && q.y < float(frame.image.heightPx);
}

// A pixel not marched this frame (its block is `block`; `box` is shared by the pixels of the block):
// its cloud, its depth (m) in `depthM` and, for the depth layer, its front (m) in `frontM`. One value and
// one store per pixel, whichever way it goes (lavapipe runs both sides of every branch: a store and a
// packing per way would all be paid).
vec4 reconstructPixel(ivec2 pixel, ivec2 block, ivec2 phase, int B, INOUT(FreshBox) box, OUT(float) depthM,
                      OUT(float) frontM)
{
    const bool front = (frame.image.flags & FRAME_FLAG_DEPTH_LAYER) != 0u;
    // Where was this pixel's cloud in the previous frame? Project the direction alone first (exact for
    // anything far away), read the previous depth found there, and project again at that depth (one
    // fixed-point step: follows the parallax of near clouds when the eye moves; exact for a still
    // camera). Zero depth (no cloud) keeps the direction alone: the second step would repeat the first.
    // Starting from the previous depth at this pixel instead misplaces near clouds when the eye moves
    // tens of metres per frame (BENCHMARKS.md).
    vec3 dir = viewRayDirection(vec2(pixel) + 0.5f);
    vec2 q = vec2(0.0f);
    vec3 v = dir;
    bool onScreen = frame.reprojection.historyValid != 0u && projectPrevious(v, q);
    ivec2 texel = ivec2(q);
    vec2 previousAlphaDepth = vec2(0.0f);  // at `texel`: alpha, depth channel (cloud_history.glsl)
    float previousDepth = 0.0f;
    float depthGuess = 0.0f;
    if (onScreen)
    {
        previousAlphaDepth = texelFetch(historyAlphaDepthIn, texel, 0).xy;
        previousDepth = historyDepthM(previousAlphaDepth.y);
        // The previous depth is measured from the previous eye: the distance from this eye.
        depthGuess = previousDepth > 0.0f ? length(frame.reprojection.previous.eyeEnuM + normalize(v) * previousDepth) : 0.0f;
    }
    if (onScreen && depthGuess > 0.0f)
    {
        v = dir * depthGuess - frame.reprojection.previous.eyeEnuM;
        onScreen = projectPrevious(v, q);
        if (onScreen)
        {
            if (ivec2(q) != texel)
            {
                texel = ivec2(q);
                previousAlphaDepth = texelFetch(historyAlphaDepthIn, texel, 0).xy;
                previousDepth = historyDepthM(previousAlphaDepth.y);
            }
            depthGuess = previousDepth > 0.0f ? length(frame.reprojection.previous.eyeEnuM + normalize(v) * previousDepth) : 0.0f;
        }
    }
    bool accept = onScreen;
    vec4 previous = vec4(0.0f);
    if (accept)
    {
        // A pixel that lands where it was (a still view) keeps its history whatever its neighbours say:
        // it was marched at this very place, and the 16-frame refresh brings in what changed since.
        // Its history is the texel whose depth was just read (q lies within kStillPx of this pixel's centre).
        bool still = distance(q, vec2(pixel) + 0.5f) < kStillPx;
        previous = still ? vec4(texelFetch(historyColourIn, texel, 0).rgb, previousAlphaDepth.x) : cubicHistory(q);
        // Disocclusion: the fixed point did not settle: the refined depth, seen from the previous eye,
        // disagrees with the previous depth found there (the ray crossed a cloud edge of another distance).
        if (previousDepth > 0.0f && depthGuess > 0.0f)
        {
            float expected = length(dir * depthGuess - frame.reprojection.previous.eyeEnuM);
            accept = abs(previousDepth - expected) <= kDepthTolerance * expected + kDepthToleranceFloorM;
        }
        // Colour clamp against the fresh neighbourhood (not for a still pixel, which keeps its history).
        if (accept && !still)
        {
            if (!box.loaded)
                loadFreshBox(block, phase, B, box);
            vec4 margin = kClampWiden * (box.hi - box.lo) + kClampMargin;
            accept = all(greaterThanEqual(previous, box.lo - margin)) && all(lessThanEqual(previous, box.hi + margin));
        }
    }
    if (accept)
    {
        depthM = depthGuess;
        // The front found at the depth's history texel, measured from this eye like the depth.
        float previousFront = front ? imageLoad(frontHistoryIn, texel).x : 0.0f;
        frontM = previousFront > 0.0f ? length(frame.reprojection.previous.eyeEnuM + normalize(v) * previousFront) : 0.0f;
        return previous;
    }
    // Rejected history (disocclusion, colour clamp) takes the nearest fresh pixel: a sharp value beside a
    // cloud edge; no history at all (none kept, or off the previous screen: the border the view turns
    // toward) the interpolated fresh pixels, which do not copy 4x4 blocks there. Both keep the nearest
    // fresh pixel's depth.
    ivec2 nearestBlock = nearestFreshBlock(pixel, phase, B);
    depthM = imageLoad(freshDepth, nearestBlock).x;
    frontM = front ? imageLoad(freshFront, nearestBlock).x : 0.0f;
    return onScreen ? imageLoad(freshCloud, nearestBlock) : freshBilinear(pixel, phase, B);
}

void main()
{
    const int B = int(frame.reprojection.blockPx);  // 4; 2 or 1 near or inside a cloud layer
    ivec2 phase = ivec2(int(frame.reprojection.phasePx.x), int(frame.reprojection.phasePx.y));
    uint quadRows = (frame.image.heightPx + RECONSTRUCT_QUAD_PX - 1u) / RECONSTRUCT_QUAD_PX;
    ivec2 quadOrigin = ivec2(permutedId(gl_GlobalInvocationID.xy, quadRows)) * RECONSTRUCT_QUAD_PX;
    FreshBox box;
    box.loaded = false;
    for (int i = 0; i < RECONSTRUCT_QUAD_PX * RECONSTRUCT_QUAD_PX; ++i)
    {
        ivec2 pixel = quadOrigin + ivec2(i % RECONSTRUCT_QUAD_PX, i / RECONSTRUCT_QUAD_PX);
        if (pixel.x >= int(frame.image.widthPx) || pixel.y >= int(frame.image.heightPx))
            continue;
        ivec2 block = pixel / B;
        vec4 cloud;
        float depthM;
        float frontM = 0.0f;
        ivec2 freshTexel = block;
        // The line counts are the same for the whole dispatch: without a turn the integer divisions are skipped.
        if (pixel == block * B + phase ||
            (newColumnCount() + newRowCount() != 0u && newLineTexel(pixel, B, freshTexel)))
        {
            cloud = imageLoad(freshCloud, freshTexel);
            depthM = imageLoad(freshDepth, freshTexel).x;
            if ((frame.image.flags & FRAME_FLAG_DEPTH_LAYER) != 0u)
                frontM = imageLoad(freshFront, freshTexel).x;
        }
        else
            cloud = reconstructPixel(pixel, block, phase, B, box, depthM, frontM);
        imageStore(historyColourOut, pixel, uvec4(packHistoryColour(cloud.rgb), 0u, 0u, 0u));
        imageStore(historyAlphaDepthOut, pixel, uvec4(packHistoryAlphaDepth(cloud.a, depthM), 0u, 0u, 0u));
        // As the march's (cloud_path.glsl cloudDepthLayer): never beyond the depth, the depth where there
        // is none (a history made before the layer was asked for holds 0), 0 without cloud.
        if ((frame.image.flags & FRAME_FLAG_DEPTH_LAYER) != 0u)
            imageStore(frontHistoryOut, pixel, vec4(frontM > 0.0f ? min(frontM, depthM) : depthM, 0.0f, 0.0f, 0.0f));
    }
}
