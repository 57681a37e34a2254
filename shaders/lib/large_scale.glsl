// SPDX-License-Identifier: MIT
// Large-scale fields computed from sums of sines (no texture: lavapipe filters an 8-bit texture in 8-bit
// steps, so a coarse lookup of the noise came back in steps that cut cloud edges and streaks). Every wave
// vector is a whole number of cycles per noise offset modulus along each noise-frame axis (`radPerM` =
// 2 pi / the modulus, frame_params.h NOISE_OFFSET_MODULUS_HIGH_PERIODS), so the fields repeat with the
// offsets and nothing jumps when they wrap.
#ifndef SKY_LIB_LARGE_SCALE_GLSL
#define SKY_LIB_LARGE_SCALE_GLSL

// A smooth warp (m) of noise-frame position p: along each axis two sines of 16-24 km wavelength, each of
// amplitude `amplitudeM`, so that a regular noise tile never lines up with itself (cloud_density.glsl
// baseShapeAt) and the cirrus streaks do not lie in rows (high_cloud_alpha.glsl).
vec3 largeScaleWarp(vec3 p, float radPerM, float amplitudeM)
{
    vec3 a = vec3(dot(p, vec3(13.0f, 9.0f, 0.0f)), dot(p, vec3(0.0f, 11.0f, 17.0f)), dot(p, vec3(19.0f, 0.0f, 8.0f)));
    vec3 b = vec3(dot(p, vec3(0.0f, 17.0f, 12.0f)), dot(p, vec3(14.0f, 0.0f, 19.0f)), dot(p, vec3(9.0f, 15.0f, 11.0f)));
    return amplitudeM * (sin(a * radPerM + vec3(1.9f, 3.7f, 6.0f)) + sin(b * radPerM + vec3(3.3f, 0.5f, 4.6f)));
}

#endif
