// SPDX-License-Identifier: MIT
// Cloud shadow map (docs/model.md): for each texel, a ground point on the eye-centred azimuthal equidistant
// grid (shaders/shared/shadow_map_params.h), the key-light transmittance through every volumetric layer
// (Beer's law over a fixed number of density samples along the light ray) and through the cirrus layer
// (its alpha where the light ray crosses its sphere). The density is the view's (cloud_density.glsl,
// with the detail level the view uses at that point), so the shadows fall from the clouds the eye sees.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] in cloud_density.glsl

#include "shaders/shared/frame_params.h"
#include "shaders/shared/shadow_map_params.h"
#include "shaders/shared/weather_window.h"
#include "shaders/lib/shell.glsl"
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/window_warp.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(binding = SHADOW_BINDING_FRAME, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = SHADOW_BINDING_WEATHER) uniform sampler2DArray weatherWindow;
layout(binding = SHADOW_BINDING_BASE_NOISE) uniform sampler3D baseNoise;
layout(binding = SHADOW_BINDING_DETAIL_NOISE) uniform sampler3D detailNoise;
layout(binding = SHADOW_BINDING_CURL_NOISE) uniform sampler2D curlNoise;
layout(binding = SHADOW_BINDING_OUTPUT, rgba16f) uniform writeonly image2D shadowOut;

layout(push_constant, std430) uniform ShadowBlock { ShadowMapPush shadow; };

#include "shaders/clouds/cloud_density.glsl"
#include "shaders/clouds/high_cloud_alpha.glsl"

// The ground point (eye ENU, metres) at arc distance |m| along azimuth atan2(m.x, m.y) on the sphere of
// radius R: the inverse of weatherMapPosition at altitude 0. z = R cos(theta) - (R + hc), written as
// -2 R sin^2(theta / 2) - hc so that float does not cancel.
vec3 groundPoint(vec2 mapPosM)
{
    float R = frame.earth.radiusM;
    float s = length(mapPosM);
    if (s < 1e-3f)
        return vec3(mapPosM, -frame.camera.eyeAltitudeM);
    float theta = s / R;
    float sinHalf = sin(0.5f * theta);
    return vec3(mapPosM * (R * sin(theta) / s), -2.0f * R * sinHalf * sinHalf - frame.camera.eyeAltitudeM);
}

// Distance along a ray that leaves the ground (altitude 0) with zenith cosine mu > 0 to altitude a >= 0:
// the positive root of the ray/sphere equation (shell.glsl; c < 0, so the roots have opposite signs).
float distanceToAltitude(float mu, float altitudeM)
{
    float R = frame.earth.radiusM;
    float tNear;
    float tFar;
    raySphereRoots(R, mu, 0.0f, altitudeM, R, tNear, tFar);
    return max(tFar, 0.0f);
}

// Altitude bands that hold volumetric cloud: the layers' ranges in the window, sorted and merged, so
// overlapping layers are marched once and a thin deck under a tall cell still gets its samples.
int cloudBands(out vec2 bands[MAX_CLOUD_LAYERS + 1])
{
    int n = 0;
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        vec2 r = vec2(max(frame.layers[k].lowestBaseM, 0.0f), frame.layers[k].highestTopM);
        if (r.y <= r.x)
            continue;
        // insertion by base altitude
        int i = n;
        while (i > 0 && bands[i - 1].x > r.x)
        {
            bands[i] = bands[i - 1];
            --i;
        }
        bands[i] = r;
        ++n;
    }
    int merged = 0;
    for (int i = 0; i < n; ++i)
    {
        if (merged > 0 && bands[i].x <= bands[merged - 1].y)
            bands[merged - 1].y = max(bands[merged - 1].y, bands[i].y);
        else
            bands[merged++] = bands[i];
    }
    return merged;
}

// Optical depth of the volumetric layers from `ground` toward the light (zenith cosine mu > 0).
float volumetricOpticalDepth(vec3 ground, vec3 lightDir, float mu)
{
    vec2 bands[MAX_CLOUD_LAYERS + 1];
    int n = cloudBands(bands);
    float thickness = 0.0f;
    for (int i = 0; i < n; ++i)
        thickness += bands[i].y - bands[i].x;
    if (thickness <= 0.0f)
        return 0.0f;
    float depth = 0.0f;
    for (int i = 0; i < n; ++i)
    {
        float t0 = distanceToAltitude(mu, bands[i].x);
        float t1 = min(distanceToAltitude(mu, bands[i].y), frame.shell.maxMarchDistanceM);
        if (t1 <= t0)
            continue;
        // Samples shared out by thickness (a band's path length is its thickness / mu for every band).
        uint steps = max(SHADOW_MIN_STEPS_PER_BAND,
                         uint(float(shadow.params.y) * (bands[i].y - bands[i].x) / thickness + 0.5f));
        float dt = (t1 - t0) / float(steps);
        for (uint k = 0u; k < steps; ++k)
        {
            vec3 q = ground + lightDir * (t0 + (float(k) + 0.5f) * dt);
            bool cheap = depth > SHADOW_CHEAP_OPTICAL_DEPTH;
            depth += cloudDensity(q, cheap, length(q)).density * frame.look.extinctionPerM * dt;
            if (depth > SHADOW_MAX_OPTICAL_DEPTH)
                return SHADOW_MAX_OPTICAL_DEPTH;
        }
    }
    return depth;
}

// Alpha of the cirrus layer where the light ray from `ground` crosses its sphere.
float cirrusAlpha(vec3 ground, vec3 lightDir, float mu)
{
    float hHigh = frame.shell.highCloudAltitudeM;
    if ((frame.image.flags & FRAME_FLAG_NO_HIGH_CLOUD) != 0u || hHigh <= 0.0f)
        return 0.0f;
    return highCloudAlpha(ground + lightDir * distanceToAltitude(mu, hHigh));
}

void main()
{
    uvec2 texel = gl_GlobalInvocationID.xy;
    uint size = shadow.params.x;
    if (texel.x >= size || texel.y >= size)
        return;
    float texelM = shadow.grid.x;
    float halfM = shadow.grid.y;
    // Column i from the west edge, row j from the north edge (image order).
    vec2 mapPosM = vec2((float(texel.x) + 0.5f) * texelM - halfM, halfM - (float(texel.y) + 0.5f) * texelM);
    vec3 ground = groundPoint(mapPosM);
    vec3 up = normalize(ground + vec3(0.0f, 0.0f, frame.earth.centreToEyeM));
    vec3 lightDir = shadow.lightDirection.xyz;
    float mu = dot(up, lightDir);
    float transmittance = 0.0f;
    float depth = SHADOW_MAX_OPTICAL_DEPTH;
    if (mu > 0.0f)
    {
        depth = volumetricOpticalDepth(ground, lightDir, mu);
        float alpha = cirrusAlpha(ground, lightDir, mu);
        transmittance = exp(-depth) * (1.0f - alpha);
        depth = min(depth - log(max(1.0f - alpha, 1e-6f)), SHADOW_MAX_OPTICAL_DEPTH);
    }
    imageStore(shadowOut, ivec2(texel), vec4(transmittance, depth, 0.0f, 0.0f));
}
