// SPDX-License-Identifier: MIT
// The key light and the far part of its cone of samples, shared by the march (cloud_lighting.glsl) and
// the light volume that precomputes that part around the eye (light_volume.comp.glsl). Included after
// cloud_density.glsl.

// The octaves of multiple scattering beyond the last are kept as one diffuse term that light diffusing
// through a conservative cloud attenuates as 1 / (1 + k tau) (the two-stream transmission,
// k = 0.75 (1 - g) ~ 0.1 for cloud droplets): cloud_lighting.glsl multipleScattering. The light volume
// holds this factor of its far samples beside their transmittance. k is matched to the path-traced
// reference on the look views (skyservice/app/look_views.cpp; 96x54, reference at 32 samples per pixel):
// with 0.3 the median cloud luminance is within 1 % of the reference's from under the cumulus, -12 % from
// above, -2 % at sunset, +19 % among them; with 0.2, +23 %, -5 %, +3 %, +32 %; the underside/top ratio
// from below +12 % (0.2: +31 %).
const float kDiffusionPerOpticalDepth = 0.3f;
float diffusionFactor(float opticalDepth)
{
    return 1.0f / (1.0f + kDiffusionPerOpticalDepth * opticalDepth);
}

// The long sample after the cone's steps, which cover C metres: at 2 C toward the light, standing for
// [C, 3 C]. At 3 C standing for C (Schneider's placement) the path from C to 2.5 C was not counted at all:
// with 4 cone samples (C = 700 m) a cumulus base at noon saw 0.7 km of the 2 km of cloud above it, and the
// long sample, 2 km higher, lay above the tops: the bases seen from below came out 1.37x the reference's
// (median of the lowest fifth of the cloud pixels), 1.23x with this placement.
const float kConeLongSampleSpan = 2.0f;
const float kConeLongSampleAt = 2.0f;

// How far toward the light a cone looks (m): the end of its long sample's span, 3 C for steps covering C
// (far_shadow.glsl takes over from there).
float lightConeReachM()
{
    uint n = min(frame.march.coneSamples, 6u);
    float coveredM = frame.look.coneStepM * float(n * (n + 1u) / 2u);
    return (kConeLongSampleAt + 0.5f * kConeLongSampleSpan) * coveredM;
}

// Offsets that spread the six light samples over a cone (unit-length-ish, fixed so frames agree).
const vec3 kConeKernel[6] = vec3[](vec3(0.38f, -0.52f, 0.29f), vec3(-0.71f, 0.12f, -0.44f),
                                  vec3(0.15f, 0.83f, -0.31f), vec3(-0.27f, -0.36f, 0.88f),
                                  vec3(0.91f, 0.24f, -0.18f), vec3(-0.48f, 0.66f, 0.52f));

// The light that shapes the clouds: the sun by day and in twilight down to -4 degrees, else the moon.
bool moonIsKeyLight()
{
    return frame.light.sunDirectionEnu.z < -0.07f;
}
vec3 keyLightDirection()
{
    return moonIsKeyLight() ? frame.light.moonDirectionEnu : frame.light.sunDirectionEnu;
}

// Cone sample i (0-based) toward the light from `p`: step i is (i + 1) x stepM long and ends at the
// distance `t` the steps so far cover; the sample sits mid-step, pushed sideways by a quarter of `t`.
vec3 coneSamplePoint(vec3 p, vec3 lightDir, uint i, float t, float len)
{
    return p + lightDir * (t - 0.5f * len) + kConeKernel[i] * (0.25f * t);
}

// Relative density x metres of cone samples first..samples-1 (cheap density) and of the long sample
// (kConeLongSampleAt): the part of the light path the light volume holds.
float coneTailDepth(vec3 p, vec3 lightDir, uint first, uint samples, float stepM)
{
    float t = stepM * float(first * (first + 1u) / 2u);
    float depth = 0.0f;
    for (uint i = first; i < samples; ++i)
    {
        float len = stepM * float(i + 1u);
        t += len;
        depth += cloudDensity(coneSamplePoint(p, lightDir, i, t, len), true, 0.0f).density * len;
    }
    return depth + cloudDensity(p + lightDir * (kConeLongSampleAt * t), true, 0.0f).density * (kConeLongSampleSpan * t);
}

// Coordinates in the light volume placed at `placement` (frame.lightVolume.nearCascade or farCascade) of a point at window-plane position `planeM` and altitude `altitudeM`; false when
// it lies outside the volume's texel centres (the march then tries the next, or takes the live cone) or
// the volume is off.
bool lightVolumeCoordinates(LightVolumeCascadeParams placement, vec2 planeM, float altitudeM, out vec3 uvw)
{
    float texelM = placement.texelM;
    vec2 uv = (planeM - placement.cornerM) / (texelM * float(LIGHT_VOLUME_SIZE));
    float w = (altitudeM - frame.shell.lowestBaseM) / max(frame.shell.highestTopM - frame.shell.lowestBaseM, 1.0f);
    uvw = vec3(uv, w);
    float margin = 0.5f / float(LIGHT_VOLUME_SIZE);
    return texelM > 0.0f && all(greaterThanEqual(uv, vec2(margin))) && all(lessThanEqual(uv, vec2(1.0f - margin)));
}
