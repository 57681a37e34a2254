// SPDX-License-Identifier: MIT
// The high-altitude 2D texture layer: cirrus (streaks along the upper wind), cirrostratus (a smooth
// veil) and cirrocumulus (small cells), on a sphere at the high layer's altitude.

struct HighCloudSample
{
    vec3 radiance;   // premultiplied
    float alpha;
    float distanceM;
};

HighCloudSample sampleHighCloud(vec3 dir, float mu, float hc, float R)
{
    HighCloudSample s;
    s.radiance = vec3(0.0f);
    s.alpha = 0.0f;
    s.distanceM = 0.0f;
    float hHigh = frame.shell.w;
    if ((frame.image.w & FRAME_FLAG_NO_HIGH_CLOUD) != 0u || hHigh <= 0.0f)
        return s;
    float tNear;
    float tFar;
    if (!raySphereRoots(R + hc, mu, hc, hHigh, R, tNear, tFar))
        return s;
    float t = hc < hHigh ? tFar : tNear;
    if (t <= 0.0f || t > frame.shell.z)
        return s;
    if (hc < hHigh)
    {
        float tGround = rayGroundDistance(R + hc, mu, hc, R);
        if (tGround > 0.0f && tGround < t)
            return s;
    }
    vec3 p = dir * t;
    float h;
    WeatherLookup w = weatherLookup(weatherMapPosition(p, h));
    if (!w.inside)
        return s;
    vec4 high = textureLod(weatherWindow, vec3(w.uv, float(WEATHER_WINDOW_HIGH_SLICE)), 0.0f);
    float coverage = high.x;
    if (coverage < 0.01f)
        return s;
    int cloudType = int(texelFetch(weatherWindow, ivec3(w.texel, WEATHER_WINDOW_HIGH_SLICE), 0).z + 0.5f);
    vec2 wind = textureLod(weatherWindow, vec3(w.uv, float(WEATHER_WINDOW_HIGH_SLICE + 1)), 0.0f).xy;

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
        // Cirrus: fibres stretched along the upper wind, bent by curl noise.
        vec3 along = vec3(normalize(wind + vec2(1e-3f, 0.0f)), 0.0f);
        vec3 alongNoise = toNoiseFrame(along);
        float s0 = dot(q, alongNoise);
        vec3 stretched = q - alongNoise * (s0 * 0.8f);
        vec2 curl = textureLod(curlNoise, stretched.xy / (0.5f * period), 0.0f).xy;
        vec4 n = textureLod(baseNoise, (stretched + vec3(curl, 0.0f) * 0.05f * period) / period, 0.0f);
        pattern = n.x * 0.5f + n.y * 0.3f + n.z * 0.2f;
    }
    float density = saturate1(remapValue(pattern, 1.0f - coverage, 1.0f, 0.0f, 1.0f));
    // Ice cloud: thin (optical depth < ~0.5) with strong forward scattering (DESIGN §3).
    s.alpha = 0.55f * density * smoothstep(0.0f, 0.2f, coverage);
    vec3 lightDir = keyLightDirection();
    float cosTheta = dot(dir, lightDir);
    vec3 light = keyLightAt(p, lightDir);
    float phase = phaseTwoLobeHG(0.85f, -0.2f, 0.75f, cosTheta);
    s.radiance = s.alpha * (light * phase + frame.ambientSky.rgb * frame.cloudLook.z);
    s.distanceM = t;
    return s;
}
