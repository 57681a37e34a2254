// SPDX-License-Identifier: MIT
// Transmittance LUT (Bruneton 2017 §4.1, Hillaire 2020 §5.1): transmittance from (r, mu) to the top of
// the atmosphere, TRANSMITTANCE_LUT_WIDTH x TRANSMITTANCE_LUT_HEIGHT, no push constants. Recompute when
// AtmosphereParams changes (the ground radius follows the eye's osculating radius).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/shared/atmosphere_params.h"
#include "shaders/lib/atmosphere.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(set = 0, binding = ATMOSPHERE_BINDING_PARAMS, std140) PARAMS_BLOCK AtmosphereBlock
{
    AtmosphereParams atmosphere;
};
layout(set = 0, binding = ATMOSPHERE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outputLut;

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= TRANSMITTANCE_LUT_WIDTH || texel.y >= TRANSMITTANCE_LUT_HEIGHT)
        return;
    vec2 uv = (vec2(texel) + 0.5f) / vec2(TRANSMITTANCE_LUT_WIDTH, TRANSMITTANCE_LUT_HEIGHT);
    float r;
    float mu;
    transmittanceLutRMu(atmosphere, uv, r, mu);
    vec3 transmittance = transmittanceToTop(atmosphere, r, mu, ATMOSPHERE_TRANSMITTANCE_STEPS);
    imageStore(outputLut, texel, vec4(transmittance, 1.0f));
}
