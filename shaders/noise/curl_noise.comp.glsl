#version 460
#extension GL_GOOGLE_include_directive : require
// 2D curl noise for turbulence at cloud bases (docs/model.md): CURL_NOISE_SIZE^2 rgba16f, xy = divergence-free
// curl vector in about [-1, 1], zw = 0, tileable. The recipe is curlNoiseTexel() in noise.glsl.
#include "shaders/shared/noise_params.h"
#include "shaders/lib/noise.glsl"

// 8x1: see NOISE_WORKGROUP_SIZE (lavapipe start-up time)
layout(local_size_x = NOISE_WORKGROUP_SIZE, local_size_y = 1) in;

layout(binding = NOISE_BINDING_OUTPUT, rgba16f) uniform writeonly image2D outCurl;

layout(push_constant) uniform NoisePushBlock
{
    NoisePush params;
};

void main()
{
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (texel.x >= params.sizeTexels || texel.y >= params.sizeTexels)
        return;
    imageStore(outCurl, ivec2(texel), curlNoiseTexel(texel, params.sizeTexels, params.seed));
}
