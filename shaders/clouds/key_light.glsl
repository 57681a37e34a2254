// SPDX-License-Identifier: MIT
// The key light arriving at a point: shared by the march (cloud_lighting.glsl), the high-cloud layer and the
// reference path tracer. Included after light_cone.glsl (keyLightDirection) and atmosphere_sampling.glsl.
#ifndef SKY_KEY_LIGHT_GLSL
#define SKY_KEY_LIGHT_GLSL

vec3 keyLightIrradiance()
{
    return moonIsKeyLight() ? frame.light.moonIrradiance : frame.light.sunIrradiance;
}

// Key light arriving at `p` through the atmosphere (transmittance LUT at the point's radius).
vec3 keyLightAt(vec3 p, vec3 lightDir)
{
    vec3 pc = p + vec3(0.0f, 0.0f, frame.earth.centreToEyeM);
    float r = length(pc);
    float muLight = dot(pc, lightDir) / r;
    return keyLightIrradiance() * sampleTransmittance(transmittanceLut, atmosphere, r, muLight);
}

#endif
