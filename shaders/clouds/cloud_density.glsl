// SPDX-License-Identifier: MIT
// Cloud density at a point: weather window lookup, base shape, coverage, anvils, detail erosion.
// Included by cloud passes after the FrameBlock and the texture bindings.

// Vertical stretch of the base noise: 1 = isotropic, 0.35 = features ~3 times taller than wide.
const float BASE_NOISE_VERTICAL_SCALE = 0.35f;
// Extinction relative to cloudLook.x per genus: stratiform decks are optically thinner per metre.
float genusDensityScale(int cloudType)
{
    if (cloudType == CLOUD_TYPE_STRATUS || cloudType == CLOUD_TYPE_ALTOSTRATUS)
        return 0.6f;
    if (cloudType == CLOUD_TYPE_STRATOCUMULUS || cloudType == CLOUD_TYPE_ALTOCUMULUS)
        return 0.8f;
    if (cloudType == CLOUD_TYPE_NIMBOSTRATUS || cloudType == CLOUD_TYPE_CUMULONIMBUS)
        return 1.2f;
    return 1.0f;
}

// Position on the weather window (azimuthal equidistant on the local sphere, metres east/north of the
// eye) and the altitude of `p` (ENU metres from the eye), both free of float cancellation:
// h = hc + (2 rc z + |p|^2) / (r + rc) instead of |p - centre| - R.
vec2 weatherMapPosition(vec3 p, out float altitudeM)
{
    float rc = frame.earth.y;
    vec3 pc = p + vec3(0.0f, 0.0f, rc);
    float r = length(pc);
    altitudeM = frame.cameraForward.w + (2.0f * rc * p.z + dot(p, p)) / (r + rc);
    float horizontal = length(pc.xy);
    if (horizontal < 1e-3f)
        return vec2(0.0f);
    float arcM = frame.earth.x * atan(horizontal, pc.z);
    return pc.xy * (arcM / horizontal);
}

vec3 toNoiseFrame(vec3 p)
{
    return vec3(dot(frame.enuToEcef0.xyz, p), dot(frame.enuToEcef1.xyz, p), dot(frame.enuToEcef2.xyz, p));
}

struct WeatherLookup
{
    vec2 uv;
    ivec2 texel;
    bool inside;
};

// Window-plane position (m, the weather window's unwarped plane) of the point at map position `mapPosM`.
vec2 windowPlanePosition(vec2 mapPosM)
{
    return frame.windowOffsetM.xy + mapPosM.x * frame.windowAxes.xy + mapPosM.y * frame.windowAxes.zw;
}

WeatherLookup weatherLookup(vec2 mapPosM)
{
    WeatherLookup w;
    vec2 planeM = windowPlanePosition(mapPosM);
    w.uv = windowWarp(planeM, frame.earth.w, frame.earth.z) / (2.0f * frame.earth.w) + 0.5f;
    w.inside = all(greaterThanEqual(w.uv, vec2(0.0f))) && all(lessThan(w.uv, vec2(1.0f)));
    w.texel = clamp(ivec2(w.uv * float(WEATHER_WINDOW_SIZE)), ivec2(0), ivec2(WEATHER_WINDOW_SIZE - 1));
    return w;
}

// Base shape from the Perlin-Worley noise (Schneider: remap(R, lowFreqFBM - 1, 1, 0, 1)).
float baseShapeAt(vec3 noisePos)
{
    vec4 n = textureLod(baseNoise, noisePos / frame.noiseScale.x, 0.0f);
    // Half of the low-frequency FBM comes from a second lookup at 3x the period, so that the 128^3 tile
    // does not visibly repeat every period across a wide view or the shadow map (it repeats every 3).
    vec4 m = textureLod(baseNoise, noisePos / (3.0f * frame.noiseScale.x) + vec3(0.37f, 0.11f, 0.73f), 0.0f);
    float lowFreqFbm = 0.5f * (n.y * 0.625f + n.z * 0.25f + n.w * 0.125f) + 0.5f * (m.y * 0.625f + m.z * 0.25f + m.w * 0.125f);
    return equalizeBaseShape(remapValue(n.x, lowFreqFbm - 1.0f, 1.0f, 0.0f, 1.0f));
}

float erodeAt(float density, vec3 noisePos, float hf, float distanceM)
{
    // Detail erosion fades out with distance (frame.marchLod.xy): far away its noise is finer than a pixel.
    float fade = 1.0f - smoothstep(frame.marchLod.x, frame.marchLod.y, distanceM);
    if (fade <= 0.0f || (frame.image.w & FRAME_FLAG_NO_DETAIL) != 0u)
        return density;
    // Curl-distorted coordinates, strongest at the base where clouds look torn by turbulence.
    vec2 curl = textureLod(curlNoise, noisePos.xy / frame.noiseScale.z, 0.0f).xy;
    vec3 q = noisePos + vec3(curl, -curl.x) * (1.0f - hf) * 0.12f * frame.noiseScale.y;
    vec4 dn = textureLod(detailNoise, q / frame.noiseScale.y, 0.0f);
    float detailFbm = dn.x * 0.625f + dn.y * 0.25f + dn.z * 0.125f;
    return erodeWithDetail(density, detailFbm, hf, frame.cloudLook.y * fade);
}

struct DensitySample
{
    float density;   // relative density (multiplies cloudLook.x for the extinction per metre)
    float rainMmH;   // precipitation rate of the densest layer here (mm/h), for rain darkening
    float heightFraction;  // 0 at the base, 1 at the top of the layer that contributed most
    bool inLayer;    // a layer's coverage and altitude range hold the point (its noise may still leave it empty)
};

DensitySample cloudDensity(vec3 p, bool cheap, float distanceM)
{
    DensitySample s;
    s.density = 0.0f;
    s.rainMmH = 0.0f;
    s.heightFraction = 0.5f;
    s.inLayer = false;
    float h;
    WeatherLookup w = weatherLookup(weatherMapPosition(p, h));
    if (!w.inside || h < frame.shell.x || h > frame.shell.y)
        return s;
    vec3 noiseRel = toNoiseFrame(p);
    vec3 radial = normalize(p + vec3(0.0f, 0.0f, frame.earth.y));  // local vertical at p
    float best = 0.0f;
    // Not unrolled: on the H200 the rolled loop made the 1/16 march 1-3 % faster (BENCHMARKS.md, tenth
    // session); the including passes enable GL_EXT_control_flow_attributes.
    [[dont_unroll]] for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        vec4 range = frame.layerRangeM[k];
        if (h < range.x || h > range.y)
            continue;
        bool anvilSlab = k == MAX_CLOUD_LAYERS;
        vec4 layer = textureLod(weatherWindow, vec3(w.uv, float(anvilSlab ? WEATHER_GPU_ANVIL_SLICE : k)), 0.0f);
        float coverage = layer.x;
        float base = layer.y;
        float top = layer.z;
        if (coverage < CLOUD_COVERAGE_MIN || top <= base || h < base || h > top)
            continue;
        s.inLayer = true;
        float hf = (h - base) / (top - base);
        int cloudType = anvilSlab ? CLOUD_TYPE_CUMULONIMBUS
                                  : int(texelFetch(weatherWindow, ivec3(w.texel, k), 0).w + 0.5f);
        vec3 shear = vec3(frame.layerShearM[k].xy * hf, 0.0f);
        vec3 noisePos = toNoiseFrame(-shear) + noiseRel + frame.layerNoiseOffsetM[k].xyz;
        // The base shape varies slowly with height: its lookup point slides down the local vertical
        // toward the layer base by (1 - s) of the height, so that clouds are vertically coherent columns
        // (coverage c shades about c of the ground) while the detail noise keeps full 3D variation.
        // Written as a shift of p, so nothing cancels in float and the point stays world-fixed.
        vec3 baseNoisePos = noisePos - toNoiseFrame(radial) * ((h - base) * (1.0f - BASE_NOISE_VERTICAL_SCALE));
        float shape = baseShapeAt(baseNoisePos);
        float densityScale = genusDensityScale(cloudType);
        if (anvilSlab)
        {
            // The anvil: a flat slab spreading downwind of the tower top, thinning at its edges.
            shape *= smoothstep(0.0f, 0.3f, hf) * (1.0f - smoothstep(0.6f, 1.0f, hf));
            densityScale *= 0.8f;
        }
        else
        {
            shape *= cloudHeightProfile(cloudType, hf);
            // Cumulus domes: the cloud narrows toward its top (the coverage threshold rises with height),
            // so a vertically coherent column ends in a rounded top rather than a flat plateau.
            if (cloudType == CLOUD_TYPE_CUMULUS)
                coverage *= 1.0f - 0.6f * smoothstep(0.15f, 1.0f, hf);
            if (cloudType == CLOUD_TYPE_CUMULONIMBUS)
            {
                // The tower narrows with height (towers are 5-10 km wide at mid level, the cell wider at
                // the base); the anvil term then spreads the top again.
                coverage *= 1.0f - 0.35f * smoothstep(0.3f, 0.75f, hf);
                shape = anvilShape(shape, hf, range.z);
                densityScale *= anvilDensity(hf) * 1.5f;
            }
        }
        float d = applyCoverage(shape, coverage);
        if (d <= 0.0f)
            continue;
        if (!cheap)
            d = erodeAt(d, noisePos, hf, distanceM);
        d *= densityScale;
        s.density += d;
        if (d > best)
        {
            best = d;
            s.heightFraction = hf;
            if (!cheap && !anvilSlab)
                s.rainMmH = textureLod(weatherWindow, vec3(w.uv, float(WEATHER_GPU_PRECIP_SLICE)), 0.0f)[k];
        }
    }
    return s;
}
