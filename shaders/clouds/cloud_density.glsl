// SPDX-License-Identifier: MIT
// Cloud density at a point: weather window lookup, base shape, coverage, anvils, detail erosion.
// Included by cloud passes after the FrameBlock and the texture bindings.

#include "shaders/lib/cloud_extent.glsl"
#include "shaders/lib/large_scale.glsl"

// Extinction relative to look.extinctionPerM per genus: stratiform decks are optically thinner per metre.
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
    float rc = frame.earth.centreToEyeM;
    vec3 pc = p + vec3(0.0f, 0.0f, rc);
    float r = length(pc);
    altitudeM = frame.camera.eyeAltitudeM + (2.0f * rc * p.z + dot(p, p)) / (r + rc);
    float horizontal = length(pc.xy);
    if (horizontal < 1e-3f)
        return vec2(0.0f);
    float arcM = frame.earth.radiusM * atan(horizontal, pc.z);
    return pc.xy * (arcM / horizontal);
}

vec3 toNoiseFrame(vec3 p)
{
    return vec3(dot(frame.enuToEcef.row0, p), dot(frame.enuToEcef.row1, p), dot(frame.enuToEcef.row2, p));
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
    return frame.window.eyeOnPlaneM + mapPosM.x * frame.window.eastAxis + mapPosM.y * frame.window.northAxis;
}

WeatherLookup weatherLookup(vec2 mapPosM)
{
    WeatherLookup w;
    vec2 planeM = windowPlanePosition(mapPosM);
    w.uv = windowWarp(planeM, frame.window.halfExtentM, frame.window.warpRadiusM) / (2.0f * frame.window.halfExtentM) + 0.5f;
    w.inside = all(greaterThanEqual(w.uv, vec2(0.0f))) && all(lessThan(w.uv, vec2(1.0f)));
    w.texel = clamp(ivec2(w.uv * float(WEATHER_WINDOW_SIZE)), ivec2(0), ivec2(WEATHER_WINDOW_SIZE - 1));
    return w;
}

// The amplitude (m) of largeScaleWarp (large_scale.glsl) on the base noise lookup, a smooth warp so that
// the 8 km tile never lines up with itself: near 44 N 8.5 E the lattice vector (-8, 0, 8) km lies in the
// horizontal plane, and without a warp the shadow map correlated 0.82 with itself 11 km north
// (tests/gpu/test_cloud_shapes.cpp). Cells move by up to 1 km along each axis, by about as much relative
// to cells 10 km away (shadow-map autocorrelation beyond 5 km 0.18; 0.58 with wavelengths of 50-66 km and
// 400 m). Computed, not read from the large-scale lookup as it was
// first: lavapipe filters an 8-bit texture to 8 bits, so the warp jumped by 1/255 of its range (31 m)
// along surfaces ~100 m apart and broke sharp cloud edges into steps that resampling cannot follow
// (tests/gpu/test_channels.cpp AChannelsEdgeMatchesACentredViewAtTheSameRays: 0.0041 of the peak at
// the same rays, 0.0025 computed, 0.0023 without any warp).
const float BASE_NOISE_WARP_M = 500.0f;

// Base shape from the Perlin-Worley noise (Schneider: remap(R, lowFreqFBM - 1, 1, 0, 1)) at `lookupPos`
// (the noise-frame position, already warped by largeScaleWarp), where largeScaleFbm (cloud_shape.glsl) at
// `largePos` (the unslid position: the same up a column) gives BASE_SHAPE_LARGE_WEIGHT of the FBM, so cloud
// fraction and cell size vary over tens of kilometres.
float baseShapeAt(vec3 lookupPos, vec3 largePos, float radPerM)
{
    vec4 n = textureLod(baseNoise, lookupPos / frame.noisePeriod.baseM, 0.0f);
    float lowFreqFbm = mix(dot(n.yzw, vec3(0.625f, 0.25f, 0.125f)), largeScaleFbm(largePos, radPerM),
                           BASE_SHAPE_LARGE_WEIGHT);
    return equalizeBaseShape(remapValue(n.x, lowFreqFbm - 1.0f, 1.0f, 0.0f, 1.0f));
}

// Whether detail erosion applies at `distanceM` (between frame.march.detailFadeStartM and detailFadeEndM: it fades out with distance, where its
// noise is finer than a pixel).
float detailFade(float distanceM)
{
    if ((frame.image.flags & FRAME_FLAG_NO_DETAIL) != 0u)
        return 0.0f;
    return 1.0f - smoothstep(frame.march.detailFadeStartM, frame.march.detailFadeEndM, distanceM);
}

// The curl noise that distorts the detail lookup at `noisePos`. Fetched by cloudDensity before the base
// noise, not after it: the two fetches then wait together instead of one after the other (the march is
// bound by such chains of dependent fetches: weather, base noise, curl, detail).
vec2 curlAt(vec3 noisePos)
{
    return textureLod(curlNoise, noisePos.xy / frame.noisePeriod.curlM, 0.0f).xy;
}

// Detail erosion of `density` at `noisePos` (`curl`: curlAt there), faded by `fade` (detailFade), and the
// torn base of a genus with `raggedness` (cloud_shape.glsl baseRaggedness; the detail noise tears it, so it
// fades with the detail).
float erodeAt(float density, vec3 noisePos, vec2 curl, float hf, float fade, float raggedness)
{
    // Curl-distorted coordinates, strongest at the base where clouds look torn by turbulence.
    vec3 q = noisePos + vec3(curl, -curl.x) * (1.0f - hf) * 0.12f * frame.noisePeriod.detailM;
    vec4 dn = textureLod(detailNoise, q / frame.noisePeriod.detailM, 0.0f);
    float detailFbm = dn.x * 0.625f + dn.y * 0.25f + dn.z * 0.125f;
    float eroded = erodeWithDetail(density, detailFbm, hf, frame.look.detailErosion * fade);
    return eroded * raggedBaseFactor(hf, raggedness * fade, 1.0f - detailFbm);
}

struct DensitySample
{
    float density;   // relative density (multiplies look.extinctionPerM for the extinction per metre)
    float rainMmH;   // precipitation rate of the densest layer here (mm/h), for rain darkening
    float heightFraction;  // 0 at the base, 1 at the top of the layer that contributed most
    bool inLayer;    // a layer may hold cloud at the point (cloud_extent.glsl; its noise may still leave it empty)
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
    if (!w.inside || h < frame.shell.lowestBaseM || h > frame.shell.highestTopM)
        return s;
    vec3 noiseRel = toNoiseFrame(p);
    // The detail and the rain rate of full samples are fetched early (curlAt says why); the rain rate is
    // the same texel for every layer.
    float fade = cheap ? 0.0f : detailFade(distanceM);
    vec4 rainMmH = cheap ? vec4(0.0f) : textureLod(weatherWindow, vec3(w.uv, float(WEATHER_GPU_PRECIP_SLICE)), 0.0f);
    vec3 radial = normalize(p + vec3(0.0f, 0.0f, frame.earth.centreToEyeM));  // local vertical at p
    float radPerM = 6.2831853f / (float(NOISE_OFFSET_MODULUS_HIGH_PERIODS) * frame.noisePeriod.highCloudM);
    float best = 0.0f;
    // Unrolled: with the current cloud shapes the unrolled loop makes the march faster in cumulus,
    // stratocumulus and cumulonimbus (BENCHMARKS.md). The including passes enable GL_EXT_control_flow_attributes.
    [[unroll]] for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        CloudLayerParams layerParams = frame.layers[k];
        if (h < layerParams.lowestBaseM || h > layerParams.highestTopM)
            continue;
        bool anvilSlab = k == MAX_CLOUD_LAYERS;
        vec4 layer = textureLod(weatherWindow, vec3(w.uv, float(anvilSlab ? WEATHER_GPU_ANVIL_SLICE : k)), 0.0f);
        float coverage = layer.x;
        float base = layer.y;
        float top = layer.z;
        if (coverage < CLOUD_COVERAGE_MIN || top <= base || h < base || h > top)
            continue;
        float hf = (h - base) / (top - base);
        int cloudType = anvilSlab ? CLOUD_TYPE_CUMULONIMBUS
                                  : int(texelFetch(weatherWindow, ivec3(w.texel, k), 0).w + 0.5f);
        // Above the domes, in an anvil's thin edge: no noise reaches the coverage (cloud_extent.glsl).
        if (!(anvilSlab ? anvilSlabMayHoldCloud(hf, coverage) : layerMayHoldCloud(cloudType, hf, coverage, layerParams.anvilAmount)))
            continue;
        s.inLayer = true;
        vec3 shear = vec3(frame.layers[k].topShearM * hf, 0.0f);
        vec3 noisePos = toNoiseFrame(-shear) + noiseRel + frame.layers[k].noiseOffsetM;
        // The base shape varies slowly with height: its lookup point slides down the local vertical
        // toward the layer base by (1 - s) of the height (s per genus, baseNoiseVerticalScale), so that
        // clouds are vertically coherent while the detail noise keeps full 3D variation. Written as a
        // shift of p, so nothing cancels in float and the point stays world-fixed.
        float verticalScale = baseNoiseVerticalScale(anvilSlab ? CLOUD_TYPE_CIRROSTRATUS : cloudType);
        vec3 radialNoise = toNoiseFrame(radial);
        vec2 curl = fade > 0.0f ? curlAt(noisePos) : vec2(0.0f);
        vec3 warp = largeScaleWarp(noisePos, radPerM, BASE_NOISE_WARP_M);
        vec3 lookupPos = noisePos - radialNoise * ((h - base) * (1.0f - verticalScale)) + warp;
        float shape = baseShapeAt(lookupPos, noisePos, radPerM);
        float densityScale = genusDensityScale(cloudType);
        if (anvilSlab)
        {
            // The anvil: a lens under the tropopause, flat on top, its underside rising toward the edge so
            // it thins out there instead of ending in a wall (coverage falls off away from the tower).
            shape *= anvilSlabProfile(hf, coverage);
            // A sheet, not a field of puffs: the noise only breaks it up where it thins toward the edge.
            coverage = saturate1(coverage * 1.8f);
            densityScale *= 0.8f;
        }
        else
        {
            shape *= cloudHeightProfile(cloudType, hf);
            coverage *= coverageHeightFactor(cloudType, hf);
            if (cloudType == CLOUD_TYPE_CUMULONIMBUS)
            {
                shape = anvilShape(shape, hf, layerParams.anvilAmount);
                densityScale *= anvilDensity(hf) * 1.5f;
            }
        }
        float d = applyCoverage(shape, coverage);
        if (d <= 0.0f)
            continue;
        if (fade > 0.0f)
            d = erodeAt(d, noisePos, curl, hf, fade, anvilSlab ? 0.0f : baseRaggedness(cloudType));
        d *= densityScale;
        s.density += d;
        if (d > best)
        {
            best = d;
            s.heightFraction = hf;
            if (!cheap && !anvilSlab)
                s.rainMmH = rainMmH[k];
        }
    }
    return s;
}
