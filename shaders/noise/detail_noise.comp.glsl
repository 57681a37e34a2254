#version 460
#extension GL_GOOGLE_include_directive : require
// Detail erosion noise (docs/model.md): DETAIL_NOISE_SIZE^3 rgba8, R,G,B = Worley FBM at increasing
// frequencies, A = their FBM. One invocation per texel; the recipe is detailNoiseTexel() in noise.glsl.
#include "shaders/shared/noise_params.h"
#include "shaders/lib/noise.glsl"

// 8x1x1: see NOISE_WORKGROUP_SIZE (lavapipe start-up time)
layout(local_size_x = NOISE_WORKGROUP_SIZE, local_size_y = 1, local_size_z = 1) in;

layout(binding = NOISE_BINDING_OUTPUT, rgba8) uniform writeonly image3D outNoise;

layout(push_constant) uniform NoisePushBlock
{
    NoisePush params;
};

void main()
{
    uvec3 texel = gl_GlobalInvocationID;
    if (texel.x >= params.sizeTexels || texel.y >= params.sizeTexels || texel.z >= params.sizeTexels)
        return;
    imageStore(outNoise, ivec3(texel), detailNoiseTexel(texel, params.sizeTexels, params.seed));
}
