// SPDX-License-Identifier: MIT
// The cloud history of reprojected frames, packed small: all device memory at 1080p must stay <= 64 MB.
//
// Two 32-bit images a frame, 8 bytes a texel (the RGBA16F radiance and R32F depth they replaced took 12).
// Shaders write them as plain bits through R32_UINT storage views (a core storage format) and read them
// through sampled views in formats the texture unit decodes, and filters: the reconstruct pass's
// Catmull-Rom read is five bilinear fetches of each, not twelve texels unpacked by hand (the images:
// skyservice/render/cloud_history_images.h):
//   colour       E5B9G9R9_UFLOAT: R, G, B 9-bit mantissas (bits 0-8, 9-17, 18-26) of a shared exponent
//                (bits 27-31, bias 15): premultiplied radiance
//   alpha/depth  R16G16_UNORM: R (bits 0-15) alpha, G (bits 16-31) the depth's log code
// Precision (tests/unit/test_cloud_math.cpp CloudHistory*): every colour channel within 2^-9 of the
// brightest one (premultiplied cloud radiance is near grey; 2^-9 of the brightest is half an 8-bit display
// step at white, less below); alpha within 1/131070; depth within 1.2e-4 of (1 m + depth): 0.12 m at 1 km,
// 12 m at 100 km; 0 (no cloud) exactly. Decoding and packing again gives the same bits, so a still pixel's
// history does not drift from frame to frame.
// Fresh (marched this frame) pixels never go through this: the composite and the readback take them
// from the fresh image at full precision, so frames where every pixel is marched equal a full render.
#ifndef SKY_LIB_CLOUD_HISTORY_GLSL
#define SKY_LIB_CLOUD_HISTORY_GLSL

// Shared-exponent RGB: VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 (EXT_texture_shared_exponent's RGB9E5).
SKY_CONST int kHistoryMantissaBits = 9;
SKY_CONST int kHistoryExponentBias = 15;
SKY_CONST float kHistoryMaxRadiance = 65408.0f;  // (511 / 512) * 2^(31 - 15)
SKY_CONST float kHistoryUnormSteps = 65535.0f;   // the 16-bit alpha and depth code
// Depth code: round(log2(1 + d / 1 m) / log2(1 + kHistoryMaxDepthM / 1 m) * 65535); beyond the
// march's longest distance setting (2000 km, config_file.cpp).
SKY_CONST float kHistoryMaxDepthM = 4.0e6f;
SKY_CONST float kHistoryDepthLog2Range = 21.931568f;  // log2(1 + 4e6)

// `colour`: premultiplied radiance (>= 0), as the bits of an E5B9G9R9 texel (rounded to nearest).
uint packHistoryColour(vec3 colour)
{
    vec3 c = clamp(colour, vec3(0.0f), vec3(kHistoryMaxRadiance));
    float maxc = max(max(c.x, c.y), c.z);
    int e = 0;
    frexp(maxc, e);  // maxc = f * 2^e, f in [0.5, 1): floor(log2(maxc)) = e - 1 (e = 0 for 0)
    int exponent = max(-kHistoryExponentBias - 1, e - 1) + 1 + kHistoryExponentBias;
    // Multiplying by a power of two is exact (a division or exp2 need not be).
    float toMantissa = ldexp(1.0f, kHistoryExponentBias + kHistoryMantissaBits - exponent);
    if (floor(maxc * toMantissa + 0.5f) >= 512.0f)
    {
        exponent += 1;
        toMantissa *= 0.5f;
    }
    uvec3 m = uvec3(floor(c * toMantissa + 0.5f));
    return m.x | (m.y << 9) | (m.z << 18) | (uint(exponent) << 27);
}

// What the texture unit reads from packHistoryColour's bits (for the CPU and the tests: shaders sample).
vec3 unpackHistoryColour(uint bits)
{
    float scale = ldexp(1.0f, int(bits >> 27) - kHistoryExponentBias - kHistoryMantissaBits);
    return vec3(float(bits & 511u), float((bits >> 9) & 511u), float((bits >> 18) & 511u)) * scale;
}

// `alpha` in [0, 1] and the cloud's distance `depthM` (m, >= 0), as the bits of an R16G16_UNORM texel.
uint packHistoryAlphaDepth(float alpha, float depthM)
{
    float d = clamp(depthM, 0.0f, kHistoryMaxDepthM);
    uint depthCode = uint(floor(log2(1.0f + d) * (kHistoryUnormSteps / kHistoryDepthLog2Range) + 0.5f));
    uint alphaCode = uint(floor(clamp(alpha, 0.0f, 1.0f) * kHistoryUnormSteps + 0.5f));
    return alphaCode | (depthCode << 16);
}

// The distance (m) from the depth channel as sampled (the code / 65535).
float historyDepthM(float depthUnorm)
{
    return exp2(depthUnorm * kHistoryDepthLog2Range) - 1.0f;
}

// What the texture unit reads from packHistoryAlphaDepth's bits: alpha, and the depth channel.
vec2 unpackHistoryAlphaDepth(uint bits)
{
    return vec2(float(bits & 0xffffu), float(bits >> 16)) / kHistoryUnormSteps;
}

#endif
