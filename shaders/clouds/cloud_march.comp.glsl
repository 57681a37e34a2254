// SPDX-License-Identifier: MIT
// Volumetric cloud march (docs/model.md): one invocation per pixel, front to back through the cloud shell,
// cone-sampled key light, multiple-scattering octaves, ambient sky and ground light, then the 2D
// high-cloud layer. Writes premultiplied cloud radiance + alpha (1 - transmittance) and the
// transmittance-weighted cloud depth, and, for the depth layer (FRAME_FLAG_DEPTH_LAYER), the cloud's front
// (cloud_path.glsl kCloudFrontOpacity).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] in cloud_density.glsl

#include "shaders/shared/frame_params.h"
#include "shaders/shared/weather_window.h"
#include "shaders/shared/atmosphere_params.h"
#include "shaders/shared/light_volume.h"
#include "shaders/shared/column_bounds.h"
#include "shaders/shared/march_order.h"
#include "shaders/lib/shell.glsl"
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/phase.glsl"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/window_warp.glsl"
#include "shaders/lib/world_jitter.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1, std140) PARAMS_BLOCK AtmosphereBlock { AtmosphereParams atmosphere; };
layout(binding = 2) uniform sampler2DArray weatherWindow;
layout(binding = 3) uniform sampler3D baseNoise;
layout(binding = 4) uniform sampler3D detailNoise;
layout(binding = 5) uniform sampler2D curlNoise;
layout(binding = 6) uniform sampler2D blueNoise;
layout(binding = 7) uniform sampler2D transmittanceLut;
layout(binding = 8, rgba16f) uniform writeonly image2D cloudOut;
layout(binding = 9, r32f) uniform writeonly image2D depthOut;
// Optical depth of the far part of the light cone around the eye (light_volume.h); a 1x1x1 stand-in
// when frame.lightVolume.nearCascade.texelM is 0 (no volume this frame).
layout(binding = 10) uniform sampler3D lightVolume;
// The weather window's column-bounds pyramid (column_bounds.h): empty-space skipping in the search.
layout(binding = 11) uniform usampler2D columnBounds;
// The light volume's far cascade (320 m texels; frame.lightVolume.farCascade.texelM 0: none this frame).
layout(binding = 12) uniform sampler3D lightVolumeFar;
// Which image row of workgroups this dispatch row marches, and the lookups each row took (march_order.h).
layout(binding = 13, std430) buffer MarchOrderBlock
{
    uint rowOrder[MARCH_ORDER_MAX_ROWS];
    uint rowLookups[MARCH_ORDER_MAX_ROWS];
} marchOrder;
// The cloud's front distance (m) beside depthOut: only with FRAME_FLAG_DEPTH_LAYER (a 1x1 stand-in otherwise).
layout(binding = 14, r32f) uniform writeonly image2D frontOut;

// The largest density-lookup count of this workgroup's rays (their sum with FRAME_FLAG_LOOKUP_TOTALS).
shared uint groupLookups;

#include "shaders/lib/atmosphere_sampling.glsl"
#include "shaders/clouds/cloud_density.glsl"
#include "shaders/clouds/light_cone.glsl"
#include "shaders/clouds/far_shadow.glsl"
#include "shaders/clouds/empty_space.glsl"
#include "shaders/clouds/cloud_path.glsl"
#include "shaders/clouds/cloud_lighting.glsl"
#include "shaders/clouds/high_cloud.glsl"
#include "shaders/clouds/view_ray.glsl"
#include "shaders/lib/new_lines.glsl"

// Marches the ray of `pixel` and stores it at `texel`; returns its density lookups.
uint marchPixel(ivec2 pixel, ivec2 texel)
{
    vec3 dir = viewRayDirection(vec2(pixel) + 0.5f);
    float R = frame.earth.radiusM;
    float hc = frame.camera.eyeAltitudeM;
    float mu = dir.z;

    // The volumetric clouds, then the 2D high-cloud layer in front of or behind them. The march starts
    // from a transmittance of 1 whether or not the high cloud lies in front: the high cloud is sampled
    // after it, so that nothing of it is held in registers through the march. With that and fewer variables
    // carried through the march's loop (marchClouds) the NVIDIA compiler gives this shader far fewer
    // registers: more rays in flight, faster full-resolution frames (BENCHMARKS.md).
    CloudPath clouds = CloudPath(vec3(0.0f), 1.0f, 0.0f, 0.0f, 0.0f);
    uint lookups = 0u;
    float tEnter;
    float tExit;
    if (rayShellInterval(mu, hc, frame.shell.lowestBaseM, frame.shell.highestTopM, R, frame.shell.maxMarchDistanceM, tEnter, tExit))
    {
        marchClouds(dir, tEnter, tExit, clouds.radiance, clouds.transmittance, clouds.depthWeighted, clouds.frontM,
                    lookups);
        // The weights of the weighted depth add up to the opacity (each step adds the transmittance it
        // takes): one variable less carried through the march's loop. A march stopped at the transmittance
        // cutoff is opaque.
        clouds.depthWeight = 1.0f - clouds.transmittance;
        if (clouds.transmittance < kMarchOpaqueTransmittance)
            clouds.transmittance = 0.0f;
    }

    HighCloudSample high = sampleHighCloud(dir, mu, hc, R);
    CloudPath c = clouds;
    if (high.alpha > 0.0f)
    {
        CloudPath highCloud = CloudPath(high.radiance, 1.0f - high.alpha, high.alpha * high.distanceM, high.alpha,
                                        high.alpha >= kCloudFrontOpacity ? high.distanceM : 0.0f);
        c = hc > frame.shell.highCloudAltitudeM ? inFrontOf(highCloud, clouds) : inFrontOf(clouds, highCloud);
    }
    vec2 depth = cloudDepthLayer(c);
    imageStore(cloudOut, texel, vec4(c.radiance, 1.0f - c.transmittance));
    imageStore(depthOut, texel, vec4(depth.y, 0.0f, 0.0f, 0.0f));
    if ((frame.image.flags & FRAME_FLAG_DEPTH_LAYER) != 0u)
        imageStore(frontOut, texel, vec4(depth.x, 0.0f, 0.0f, 0.0f));
    return lookups;
}

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        groupLookups = 0u;
    barrier();
    // Reprojected frames (frame.reprojection.blockPx = B: 4, or 2 or 1 near clouds) march one pixel of each
    // BxB block and store it at the block's texel of a block-resolution image (and, in a turn or a pitch
    // change, every pixel of the columns or rows the previous frame did not see, beside and below them);
    // full-resolution frames march every pixel. The dispatch's workgroup rows run in the order the host
    // chose (march_order.h).
    uint block = max(frame.reprojection.blockPx, 1u);
    uint rows = (frame.image.heightPx + block - 1u) / block + (block > 1u ? newRowCount() * block : 0u);
    uint groupRows = (rows + gl_WorkGroupSize.y - 1u) / gl_WorkGroupSize.y;
    uint groupRow = min(marchOrder.rowOrder[min(gl_WorkGroupID.y, MARCH_ORDER_MAX_ROWS - 1u)], groupRows - 1u);
    uvec2 id = uvec2(gl_GlobalInvocationID.x, groupRow * gl_WorkGroupSize.y + gl_LocalInvocationID.y);
    ivec2 pixel = ivec2(id * block + uvec2(frame.reprojection.phasePx.x, frame.reprojection.phasePx.y));
    // Beside and below the blocks: the pixels of the lines marched in full (new_lines.glsl).
    if (block > 1u && (int(id.x) >= newColumnsTexelX0(int(block)) || int(id.y) >= newRowsTexelY0(int(block))))
        pixel = newLinePixel(ivec2(id), int(block));
    if (pixel.x >= 0 && pixel.x < int(frame.image.widthPx) && pixel.y < int(frame.image.heightPx))
    {
        uint lookups = marchPixel(pixel, ivec2(id));
        if ((frame.image.flags & FRAME_FLAG_LOOKUP_TOTALS) != 0u)
            atomicAdd(groupLookups, lookups);
        else
            atomicMax(groupLookups, lookups);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u)
        atomicAdd(marchOrder.rowLookups[groupRow], groupLookups);
}
