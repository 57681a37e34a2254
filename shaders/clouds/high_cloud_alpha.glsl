// SPDX-License-Identifier: MIT
// Opacity of the high-altitude 2D texture layer (cirrus streaks along the upper wind, a smooth
// cirrostratus veil, small cirrocumulus cells) at a point of its sphere. Used by the view (high_cloud.glsl)
// and by the cloud shadow map. Included after cloud_density.glsl.

// Amplitude (m) of each sine of the cirrus warp: 1.5 km bends the fibres by a quarter of a 24 km period
// without folding them (the warp's gradient stays under 1).
const float CIRRUS_WARP_M = 1500.0f;

// Alpha (1 - transmittance) of the high layer at `p` (eye ENU, metres, at the high layer's altitude);
// 0 outside the weather window or where the coverage is below 1%.
float highCloudAlpha(vec3 p)
{
    float h;
    WeatherLookup w = weatherLookup(weatherMapPosition(p, h));
    if (!w.inside)
        return 0.0f;
    vec4 high = textureLod(weatherWindow, vec3(w.uv, float(WEATHER_GPU_HIGH_SLICE)), 0.0f);
    float coverage = high.x;
    if (coverage < 0.01f)
        return 0.0f;
    int cloudType = int(texelFetch(weatherWindow, ivec3(w.texel, WEATHER_GPU_HIGH_SLICE), 0).z + 0.5f);
    vec2 wind = textureLod(weatherWindow, vec3(w.uv, float(WEATHER_GPU_HIGH_WIND_SLICE)), 0.0f).xy;

    vec3 q = toNoiseFrame(p) + frame.layers[MAX_CLOUD_LAYERS].noiseOffsetM;
    float period = frame.noisePeriod.highCloudM;
    float pattern;
    if (cloudType == CLOUD_TYPE_CIRROCUMULUS)
    {
        vec4 n = textureLod(detailNoise, q / (0.15f * period), 0.0f);
        pattern = n.x * 0.7f + textureLod(baseNoise, q / period, 0.0f).y * 0.3f;
    }
    else if (cloudType == CLOUD_TYPE_CIRROSTRATUS)
    {
        vec4 n = textureLod(baseNoise, q / (2.0f * period), 0.0f);
        pattern = 0.55f + 0.45f * n.y;
    }
    else
    {
        // Cirrus: fibres stretched along the upper wind, bent by curl noise. A computed warp of 16-24 km
        // wavelength (large_scale.glsl) moves them first by up to CIRRUS_WARP_M along each axis, so the
        // fibres of neighbouring periods do not line up in regular rows across the wind.
        q += largeScaleWarp(q, 6.2831853f / (float(NOISE_OFFSET_MODULUS_HIGH_PERIODS) * period), CIRRUS_WARP_M);
        vec3 along = vec3(normalize(wind + vec2(1e-3f, 0.0f)), 0.0f);
        vec3 alongNoise = toNoiseFrame(along);
        float s0 = dot(q, alongNoise);
        vec3 stretched = q - alongNoise * (s0 * 0.8f);
        vec2 curl = textureLod(curlNoise, stretched.xy / (0.5f * period), 0.0f).xy;
        vec4 n = textureLod(baseNoise, (stretched + vec3(curl, 0.0f) * 0.05f * period) / period, 0.0f);
        pattern = n.x * 0.5f + n.y * 0.3f + n.z * 0.2f;
    }
    float density = saturate1(remapValue(pattern, 1.0f - coverage, 1.0f, 0.0f, 1.0f));
    // Ice cloud: thin (optical depth < ~0.5) with strong forward scattering (docs/model.md).
    return 0.55f * density * smoothstep(0.0f, 0.2f, coverage);
}
