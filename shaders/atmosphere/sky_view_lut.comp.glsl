// SPDX-License-Identifier: MIT
// Sky-view LUT (Hillaire 2020 §5.3) around the eye: sky radiance from the sun and the moon (single and
// multiple scattering) by view zenith angle (rows crowded at the horizon) and absolute azimuth in the
// eye's ENU frame (u = azimuth / 2 pi clockwise from north), SKY_VIEW_LUT_WIDTH x SKY_VIEW_LUT_HEIGHT.
// Per frame, after transmittance_lut and multiscatter_lut; read it with sampleSkyView().
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
layout(set = 0, binding = ATMOSPHERE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputLut;
layout(set = 0, binding = ATMOSPHERE_BINDING_TRANSMITTANCE) uniform sampler2D transmittanceLut;
layout(set = 0, binding = ATMOSPHERE_BINDING_MULTISCATTER) uniform sampler2D multiscatterLut;

layout(push_constant, std430) uniform SkyViewConstants
{
    SkyViewPushConstants pc;
};

#include "shaders/lib/atmosphere_sampling.glsl"

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= SKY_VIEW_LUT_WIDTH || texel.y >= SKY_VIEW_LUT_HEIGHT)
        return;
    vec2 uv = (vec2(texel) + 0.5f) / vec2(SKY_VIEW_LUT_WIDTH, SKY_VIEW_LUT_HEIGHT);
    float camRM = pc.sunDirection.w;
    float zenith;
    float azimuth;
    skyViewLutDirection(atmosphere, camRM, uv, zenith, azimuth);
    vec3 dir = enuDirectionFromAngles(zenith, azimuth);
    vec3 radiance = computeSkyRadiance(transmittanceLut, multiscatterLut, atmosphere, camRM, dir, pc.sunDirection.xyz,
                                       pc.sunIrradiance.rgb, pc.moonDirection.xyz, pc.moonIrradiance.rgb,
                                       (pc.flags.x & SKY_VIEW_FLAG_GROUND) != 0u);
    imageStore(outputLut, texel, vec4(radiance, 1.0f));
}
