// SPDX-License-Identifier: MIT
// The packed cloud history texel of reprojected frames (issue 5: device memory at 1080p <= 64 MB).
//
// One 64-bit texel (an RGBA16UI image, a core storage format: no shaderStorageImageExtendedFormats)
// holds what two images held before (RGBA16F radiance + alpha and R32F depth, 12 bytes):
//   word x: bits 0-9, 10-19, 20-29: R, G, B mantissas of a shared exponent (bits 30-31 unused)
//   word y: bits 0-15: depth (log code); bits 16-26: alpha (11-bit unorm); bits 27-31: shared exponent
// Precision (tests/unit/test_cloud_math.cpp CloudHistory*): every colour channel within 2^-10 of the
// brightest one (a half float keeps 2^-11 of each channel; premultiplied cloud radiance is near grey,
// and 2^-10 is a quarter of an 8-bit display step); alpha within 1/4094; depth within 1.2e-4 of
// (1 m + depth): 0.12 m at 1 km, 12 m at 100 km; 0 (no cloud) exactly. Unpacking and packing
// again gives the same bits, so a still pixel's history does not drift from frame to frame.
// Fresh (marched this frame) pixels never go through this: the composite and the readback take them
// from the fresh image at full precision, so frames where every pixel is marched equal a full render.
#ifndef SKY_LIB_CLOUD_HISTORY_GLSL
#define SKY_LIB_CLOUD_HISTORY_GLSL

// Shared-exponent RGB (the RGB9E5 scheme of EXT_texture_shared_exponent with 10-bit mantissas).
SKY_CONST int kHistoryMantissaBits = 10;
SKY_CONST int kHistoryExponentBias = 15;
SKY_CONST float kHistoryMaxRadiance = 65472.0f;  // (1023 / 1024) * 2^(31 - 15)
SKY_CONST float kHistoryAlphaSteps = 2047.0f;    // 11 bits
// Depth code: round(log2(1 + d / 1 m) / log2(1 + kHistoryMaxDepthM / 1 m) * 65535); beyond the
// march's longest distance setting (2000 km, config_file.cpp).
SKY_CONST float kHistoryMaxDepthM = 4.0e6f;
SKY_CONST float kHistoryDepthLog2Range = 21.931568f;  // log2(1 + 4e6)

uint packHistoryDepth(float depthM)
{
    float d = clamp(depthM, 0.0f, kHistoryMaxDepthM);
    return uint(floor(log2(1.0f + d) * (65535.0f / kHistoryDepthLog2Range) + 0.5f));
}

float unpackHistoryDepth(uint code)
{
    return exp2(float(code) * (kHistoryDepthLog2Range / 65535.0f)) - 1.0f;
}

// `cloud`: premultiplied radiance (>= 0) and alpha [0, 1]; `depthM`: cloud distance (m, >= 0).
// Returned as the four 16-bit channels of the RGBA16UI texel.
uvec4 packCloudHistory(vec4 cloud, float depthM)
{
    vec3 c = clamp(vec3(cloud.x, cloud.y, cloud.z), vec3(0.0f), vec3(kHistoryMaxRadiance));
    float maxc = max(max(c.x, c.y), c.z);
    int e = 0;
    frexp(maxc, e);  // maxc = f * 2^e, f in [0.5, 1): floor(log2(maxc)) = e - 1 (e = 0 for 0)
    int exponent = max(-kHistoryExponentBias - 1, e - 1) + 1 + kHistoryExponentBias;
    // Multiplying by a power of two is exact (a division or exp2 need not be).
    float toMantissa = ldexp(1.0f, kHistoryExponentBias + kHistoryMantissaBits - exponent);
    if (floor(maxc * toMantissa + 0.5f) >= 1024.0f)
    {
        exponent += 1;
        toMantissa *= 0.5f;
    }
    uvec3 m = uvec3(floor(c * toMantissa + 0.5f));
    uint a = uint(floor(clamp(cloud.w, 0.0f, 1.0f) * kHistoryAlphaSteps + 0.5f));
    uint x = m.x | (m.y << 10) | (m.z << 20);
    uint y = packHistoryDepth(depthM) | (a << 16) | (uint(exponent) << 27);
    return uvec4(x & 0xffffu, x >> 16, y & 0xffffu, y >> 16);
}

// A small unsigned integer (< 2^23) as a float without an integer-to-float conversion, which NVIDIA GPUs
// run at a quarter of the rate of other arithmetic: the float with the bits of 2^23 + n, less 2^23. Exact.
// The reconstruct pass unpacks 16 history texels per moving pixel (its Catmull-Rom read), 4 conversions each.
vec3 smallUintsToFloat(uvec3 n)
{
    return uintBitsToFloat(uvec3(0x4b000000u) | n) - 8388608.0f;
}

// Inverse of packCloudHistory: radiance and alpha in the return value, the depth (m) in `depthM`.
vec4 unpackCloudHistory(uvec4 texel, OUT(float) depthM)
{
    uint x = texel.x | (texel.y << 16);
    uint y = texel.z | (texel.w << 16);
    // 2^(exponent - bias - mantissa bits), built as a float's bits (exponent 0..31: always a normal float).
    float scale = uintBitsToFloat(uint(int(y >> 27) - kHistoryExponentBias - kHistoryMantissaBits + 127) << 23);
    vec3 c = smallUintsToFloat(uvec3(x & 1023u, (x >> 10) & 1023u, (x >> 20) & 1023u)) * scale;
    float alpha = smallUintsToFloat(uvec3((y >> 16) & 2047u, 0u, 0u)).x;
    depthM = unpackHistoryDepth(y & 0xffffu);
    return vec4(c.x, c.y, c.z, alpha * (1.0f / kHistoryAlphaSteps));
}

#endif
