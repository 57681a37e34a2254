// SPDX-License-Identifier: MIT
// Composite: sky (sky-view LUT + sun and moon disks) behind, clouds in front with aerial perspective,
// then exposure, tone mapping and sRGB encoding for display.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shaders/shared/frame_params.h"
#include "shaders/shared/atmosphere_params.h"
#include "shaders/lib/shell.glsl"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/phase.glsl"
#include "shaders/lib/tonemap.glsl"
#include "shaders/lib/cloud_history.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1, std140) PARAMS_BLOCK AtmosphereBlock { AtmosphereParams atmosphere; };
layout(binding = 2) uniform sampler2D transmittanceLut;
layout(binding = 3) uniform sampler2D skyViewLut;
// The aerial-perspective LUT of this frame (in-scattered light, transmittance).
layout(binding = 4) uniform sampler3D aerialInscatterLut;
layout(binding = 5) uniform sampler3D aerialTransmittanceLut;
// Full-resolution frames: the march's cloud image and depth. Reprojected frames (FRAME_FLAG_REPROJECTED):
// the block-resolution fresh pixels, and the history of the pixels not marched this frame (sampled views
// the texture unit decodes: shaders/lib/cloud_history.glsl).
layout(binding = 6, rgba16f) uniform readonly image2D cloudIn;
layout(binding = 7, r32f) uniform readonly image2D depthIn;
layout(binding = 8) uniform sampler2D historyColourIn;  // 1x1 stand-ins in full-resolution frames
layout(binding = 9) uniform sampler2D historyAlphaDepthIn;
// The linear frame only when a caller reads it (FRAME_FLAG_NO_LINEAR_OUTPUT clear): 16.6 MB at 1080p.
layout(binding = 10, rgba16f) uniform writeonly image2D linearOut;
layout(binding = 11, rgba8) uniform writeonly image2D displayOut;
// Compositing layers and the reprojected frame's cloud image, each only when asked for (FRAME_FLAG_*).
layout(binding = 12, rgba16f) uniform writeonly image2D skyOut;
layout(binding = 13, rgba16f) uniform writeonly image2D cloudLayerOut;
layout(binding = 14, rgba16f) uniform writeonly image2D cloudOut;
layout(binding = 15, r32f) uniform writeonly image2D depthOut;
// The depth layer (FRAME_FLAG_DEPTH_LAYER; 1x1 stand-ins otherwise): the march's fronts (full resolution,
// or block resolution in reprojected frames), the front history of the pixels not marched this frame, and
// the layer: R the cloud's front, G its transmittance-weighted distance (m).
layout(binding = 16, r32f) uniform readonly image2D frontIn;
layout(binding = 17, r32f) uniform readonly image2D frontHistoryIn;
layout(binding = 18, rg32f) uniform writeonly image2D depthLayerOut;

#include "shaders/lib/atmosphere_sampling.glsl"
#include "shaders/clouds/view_ray.glsl"
#include "shaders/lib/aerial_lut.glsl"

void main()
{
    ivec2 pixel = ivec2(permutedPixel(gl_GlobalInvocationID.xy));
    if (pixel.x >= int(frame.image.widthPx) || pixel.y >= int(frame.image.heightPx))
        return;
    vec3 dir = viewRayDirection(vec2(pixel) + 0.5f);
    float rc = frame.earth.centreToEyeM;
    float hc = frame.camera.eyeAltitudeM;

    // The direction's angles, for the sky-view LUT and again for the aerial-perspective LUT.
    float zenithRad = acos(clamp(dir.z, -1.0f, 1.0f));
    float azimuthRad = enuAzimuth(dir);
    vec3 sky = sampleSkyViewAt(skyViewLut, atmosphere, rc, zenithRad, azimuthRad);
    bool groundHit = rayGroundDistance(rc, dir.z, hc, frame.earth.radiusM) >= 0.0f;
    if (!groundHit)
    {
        // Both disks are seen through the same air, the transmittance from the eye along dir: one LUT
        // read, and only on a disk (lavapipe runs both sides of every branch: it paid two reads a pixel).
        vec3 sun = sunDiskEmission(atmosphere, dir, rc, frame.light.sunDirectionEnu, frame.light.sunIrradiance);
        vec3 moon = moonDiskEmission(atmosphere, dir, rc, frame.light.moonDirectionEnu, frame.light.sunDirectionEnu,
                                     frame.light.moonIrradiance);
        if (sun != vec3(0.0f) || moon != vec3(0.0f))
        {
            vec3 viewTransmittance = sampleTransmittance(transmittanceLut, atmosphere, rc, dir.z);
            sky += sun * viewTransmittance;
            sky += moon * viewTransmittance;
        }
    }

    vec4 cloud;
    float depth;
    const int B = int(frame.reprojection.blockPx);
    ivec2 block = pixel / max(B, 1);
    // Where this pixel's cloud comes from: the march's image at `source`, or the history.
    bool fresh = true;
    ivec2 source = pixel;
    if ((frame.image.flags & FRAME_FLAG_REPROJECTED) == 0u)
    {
        cloud = imageLoad(cloudIn, pixel);
        depth = imageLoad(depthIn, pixel).x;
    }
    else if (pixel == block * B + ivec2(int(frame.reprojection.phasePx.x), int(frame.reprojection.phasePx.y)))
    {
        cloud = imageLoad(cloudIn, block);
        depth = imageLoad(depthIn, block).x;
        source = block;
    }
    else
    {
        vec2 alphaDepth = texelFetch(historyAlphaDepthIn, pixel, 0).xy;
        cloud = vec4(texelFetch(historyColourIn, pixel, 0).rgb, alphaDepth.x);
        depth = historyDepthM(alphaDepth.y);
        fresh = false;
    }
    vec3 color = sky;
    // The clouds as the eye sees them through the air in front of them, premultiplied by their alpha.
    vec3 cloudSeen = vec3(0.0f);
    if (cloud.a > 0.0f)
    {
        vec3 inscatter;
        vec3 transmittance;
        sampleAerialLut(aerialInscatterLut, aerialTransmittanceLut, atmosphere, zenithRad, azimuthRad, rc, depth,
                        inscatter, transmittance);
        color = sky * (1.0f - cloud.a) + cloud.rgb * transmittance + inscatter * cloud.a;
        cloudSeen = cloud.rgb * transmittance + inscatter * cloud.a;
    }
    if ((frame.image.flags & FRAME_FLAG_SKY_LAYER) != 0u)
        imageStore(skyOut, pixel, vec4(sky, 1.0f));
    if ((frame.image.flags & FRAME_FLAG_CLOUD_LAYER) != 0u)
        imageStore(cloudLayerOut, pixel, vec4(cloudSeen, cloud.a));
    if ((frame.image.flags & FRAME_FLAG_DEPTH_LAYER) != 0u)
    {
        float front = fresh ? imageLoad(frontIn, source).x : imageLoad(frontHistoryIn, pixel).x;
        // The history's depth is rounded (cloud_history.glsl): the front stays in front of it.
        imageStore(depthLayerOut, pixel, vec4(min(front, depth), depth, 0.0f, 0.0f));
    }
    if ((frame.image.flags & FRAME_FLAG_WRITE_CLOUD) != 0u)
    {
        imageStore(cloudOut, pixel, cloud);
        imageStore(depthOut, pixel, vec4(depth));
    }
    if ((frame.image.flags & FRAME_FLAG_NO_LINEAR_OUTPUT) == 0u)
        imageStore(linearOut, pixel, vec4(color, 1.0f));
    vec3 display = encodeSrgb(tonemapAces(color * frame.image.exposure));
    imageStore(displayOut, pixel, vec4(display, 1.0f));
}
