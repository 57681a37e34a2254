// SPDX-License-Identifier: MIT
// Opacity of the high-altitude 2D texture layer (cirrus streaks along the upper wind, a smooth
// cirrostratus veil, small cirrocumulus cells) at a point of its sphere. Used by the view (high_cloud.glsl)
// and by the cloud shadow map. Included after cloud_density.glsl.

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

    vec3 q = toNoiseFrame(p) + frame.layerNoiseOffsetM[MAX_CLOUD_LAYERS].xyz;
    float period = frame.noiseScale.w;
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
        // Cirrus: fibres stretched along the upper wind, bent by curl noise. A lookup at 8 periods
        // (192 km, wider than the shadow map) warps them first, so the bands across the wind do not
        // come back every period in regular rows.
        vec3 large = textureLod(baseNoise, q / (8.0f * period) + vec3(0.61f, 0.29f, 0.17f), 0.0f).yzw;
        q += (large - vec3(0.5f)) * (0.6f * period);
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
