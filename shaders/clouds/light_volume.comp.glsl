// SPDX-License-Identifier: MIT
// Builds the light volume (shaders/shared/light_volume.h): for each texel, the transmittance and the
// diffusion factor (light_cone.glsl) of the far cone samples toward the key light (from frame.march.fullConeSamples
// on) and of the long sample, exactly as the march would take them at the texel centre (coneTailDepth).
// One invocation per texel.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] in cloud_density.glsl

#include "shaders/shared/frame_params.h"
#include "shaders/shared/weather_window.h"
#include "shaders/shared/light_volume.h"
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/window_warp.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1) uniform sampler2DArray weatherWindow;
layout(binding = 2) uniform sampler3D baseNoise;
layout(binding = 3) uniform sampler3D detailNoise;  // not read (cheap density only); cloud_density.glsl names it
layout(binding = 4) uniform sampler2D curlNoise;    // idem
layout(binding = 5, rg16f) uniform writeonly image3D lightVolumeOut;
// Which volume this dispatch fills: 0 the light volume (frame.lightVolume.nearCascade), 1 its far cascade.
layout(push_constant) uniform LightVolumePush { uint cascade; } push;

#include "shaders/clouds/cloud_density.glsl"
#include "shaders/clouds/light_cone.glsl"

// The point (ENU metres from the eye) at map position `mapPosM` (azimuthal equidistant on the local
// sphere, as weatherMapPosition measures it) and altitude `altitudeM`: the inverse of weatherMapPosition.
// The vertical is written without the cancellation of r cos(theta) - rc in float.
vec3 pointAtMapPosition(vec2 mapPosM, float altitudeM)
{
    float R = frame.earth.radiusM;
    float r = R + altitudeM;
    float arcM = length(mapPosM);
    float theta = arcM / R;
    vec2 horizontal = arcM > 1e-3f ? mapPosM * (r * sin(theta) / arcM) : vec2(0.0f);
    float s = sin(0.5f * theta);
    return vec3(horizontal, (altitudeM - frame.camera.eyeAltitudeM) - 2.0f * r * s * s);
}

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(texel, ivec3(LIGHT_VOLUME_SIZE, LIGHT_VOLUME_SIZE, LIGHT_VOLUME_LEVELS))))
        return;
    // Member by member: a whole struct copied out of the block is invalid SPIR-V (its layout decorations).
    bool nearCascade = push.cascade == 0u;
    vec2 cornerM = nearCascade ? frame.lightVolume.nearCascade.cornerM : frame.lightVolume.farCascade.cornerM;
    float texelM = nearCascade ? frame.lightVolume.nearCascade.texelM : frame.lightVolume.farCascade.texelM;
    vec2 planeM = cornerM + (vec2(texel.xy) + 0.5f) * texelM;
    // Map position from the window plane: invert planeM = eyeOnPlaneM + A mapPosM, A = [eastAxis northAxis].
    vec2 a = frame.window.eastAxis;
    vec2 b = frame.window.northAxis;
    vec2 rel = planeM - frame.window.eyeOnPlaneM;
    float det = a.x * b.y - b.x * a.y;
    vec2 mapPosM = vec2(rel.x * b.y - b.x * rel.y, a.x * rel.y - rel.x * a.y) / det;
    float altitudeM = frame.shell.lowestBaseM + (float(texel.z) + 0.5f) / float(LIGHT_VOLUME_LEVELS) * (frame.shell.highestTopM - frame.shell.lowestBaseM);
    vec3 p = pointAtMapPosition(mapPosM, altitudeM);
    uint samples = min(frame.march.coneSamples, 6u);
    uint first = min(frame.march.fullConeSamples, samples);
    float depth = coneTailDepth(p, keyLightDirection(), first, samples, frame.look.coneStepM);
    float opticalDepth = depth * frame.look.extinctionPerM;
    imageStore(lightVolumeOut, texel, vec4(exp(-opticalDepth), diffusionFactor(opticalDepth), 0.0f, 0.0f));
}
