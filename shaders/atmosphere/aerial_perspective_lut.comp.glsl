// SPDX-License-Identifier: MIT
// Aerial-perspective LUT (atmosphere_params.h AERIAL_LUT_*): for each direction of the sky-view mapping
// and each distance slice (atmosphere.glsl aerialSliceDistanceM), the light the air scatters toward the
// eye and the transmittance between the eye and that distance. One invocation per direction marches
// the slices front to back, AERIAL_LUT_STEPS_PER_SLICE steps each. Per frame, right after the sky-view
// LUT and with the same inputs (kept with it while they are unchanged); read with aerial_lut.glsl.
#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/shared/atmosphere_params.h"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/phase.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(set = 0, binding = ATMOSPHERE_BINDING_PARAMS, std140) PARAMS_BLOCK AtmosphereBlock
{
    AtmosphereParams atmosphere;
};
layout(set = 0, binding = ATMOSPHERE_BINDING_OUTPUT, rgba16f) uniform writeonly image3D inscatterOut;
layout(set = 0, binding = ATMOSPHERE_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(set = 0, binding = ATMOSPHERE_BINDING_MULTISCATTER) uniform sampler2D multiscatterLut;
layout(set = 0, binding = ATMOSPHERE_BINDING_OUTPUT_TRANSMITTANCE, rgba16f) uniform writeonly image3D transmittanceOut;

layout(push_constant, std430) uniform SkyViewConstants
{
    SkyViewPushConstants pc;
};

#include "shaders/lib/atmosphere_sampling.glsl"

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= AERIAL_LUT_WIDTH || texel.y >= AERIAL_LUT_HEIGHT)
        return;
    float camRM = pc.sunDirection.w;
    float v = texCoordToUnitRange((float(texel.y) + 0.5f) / float(AERIAL_LUT_HEIGHT), float(AERIAL_LUT_HEIGHT));
    float zenith = skyViewZenithOfUnitV(atmosphere, camRM, clamp(v, 0.0f, 1.0f));
    float azimuth = (float(texel.x) + 0.5f) / float(AERIAL_LUT_WIDTH) * 2.0f * SKY_PI;
    vec3 dir = enuDirectionFromAngles(zenith, azimuth);
    vec3 originM = vec3(0.0f, 0.0f, camRM);

    float tStart;
    float tEnd;
    bool hitsGround;
    bool inAir = clipRayToAtmosphere(atmosphere, originM, dir, tStart, tEnd, hitsGround);
    ViewPhases ph = viewPhases(atmosphere, dir, pc.sunDirection.xyz, pc.moonDirection.xyz);
    vec3 inscatter = vec3(0.0f);
    vec3 transmittance = vec3(1.0f);
    float tPrev = 0.0f;
    for (int k = 0; k < AERIAL_LUT_SLICES; ++k)
    {
        float d = aerialSliceDistanceM(float(k));
        // The part of [tPrev, d] inside the atmosphere (beyond the ground nothing changes: no cloud is there).
        float a = inAir ? clamp(tPrev, tStart, tEnd) : 0.0f;
        float b = inAir ? clamp(d, tStart, tEnd) : 0.0f;
        float dt = (b - a) / float(AERIAL_LUT_STEPS_PER_SLICE);
        for (int j = 0; j < AERIAL_LUT_STEPS_PER_SLICE && dt > 0.0f; ++j)
        {
            vec3 pos = originM + (a + (float(j) + 0.5f) * dt) * dir;
            scatteringStep(transmittanceLut, multiscatterLut, atmosphere, pos, dt, ph, pc.sunDirection.xyz,
                           pc.sunIrradiance.rgb, pc.moonDirection.xyz, pc.moonIrradiance.rgb, inscatter, transmittance);
        }
        imageStore(inscatterOut, ivec3(texel, k), vec4(inscatter, 1.0f));
        imageStore(transmittanceOut, ivec3(texel, k), vec4(transmittance, 1.0f));
        tPrev = d;
    }
}
