// SPDX-License-Identifier: MIT
// Multiple-scattering LUT (Hillaire 2020 §5.5): Psi_ms(altitude, sun zenith cosine) per unit sun
// irradiance, MULTISCATTER_LUT_SIZE^2, one invocation per texel (64 directions x 20 steps each), no push
// constants. Reads the transmittance LUT, so it runs after transmittance_lut with a barrier between.
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

#include "shaders/lib/atmosphere_sampling.glsl"

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= MULTISCATTER_LUT_SIZE || texel.y >= MULTISCATTER_LUT_SIZE)
        return;
    vec2 uv = (vec2(texel) + 0.5f) / float(MULTISCATTER_LUT_SIZE);
    vec3 psi = computeMultiscatterTexel(transmittanceLut, atmosphere, uv);
    imageStore(outputLut, texel, vec4(psi, 1.0f));
}
