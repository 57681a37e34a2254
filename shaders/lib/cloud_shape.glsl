// SPDX-License-Identifier: MIT
// Cloud shape and light-transport terms that do not touch textures (CPU-tested, docs/style.md §8).
// Sources: Schneider 2015/2016 (remap, coverage, Beer-powder), Häggström 2018 (anvil shape and density
// terms), Hillaire 2016 (energy-conserving integration), Wrenninge et al. 2013 (scattering octaves).

float remapValue(float v, float lo0, float hi0, float lo1, float hi1)
{
    return lo1 + (v - lo0) * (hi1 - lo1) / (hi0 - lo0);
}

float saturate1(float v)
{
    return clamp(v, 0.0f, 1.0f);
}

// Vertical profile of each genus over the height fraction h in [0,1] between the layer's base and top:
// (bottom ramp end, top fade start) of a smoothstep-up, smoothstep-down envelope, in [0,1].
vec2 cloudTypeProfileShape(int cloudType)
{
    if (cloudType == CLOUD_TYPE_STRATUS)
        return vec2(0.10f, 0.70f);
    if (cloudType == CLOUD_TYPE_STRATOCUMULUS)
        return vec2(0.12f, 0.50f);
    if (cloudType == CLOUD_TYPE_CUMULUS)
        return vec2(0.08f, 0.60f);
    if (cloudType == CLOUD_TYPE_CUMULONIMBUS)
        return vec2(0.04f, 0.80f);
    if (cloudType == CLOUD_TYPE_NIMBOSTRATUS)
        return vec2(0.05f, 0.75f);
    if (cloudType == CLOUD_TYPE_ALTOSTRATUS)
        return vec2(0.10f, 0.70f);
    if (cloudType == CLOUD_TYPE_ALTOCUMULUS)
        return vec2(0.20f, 0.50f);
    return vec2(0.15f, 0.50f);  // cirrus-family genera in a volumetric layer: thin sheet
}

// Density envelope of a genus at height fraction h (0 at the base, 1 at the top); always in [0,1].
float cloudHeightProfile(int cloudType, float h)
{
    vec2 shape = cloudTypeProfileShape(cloudType);
    float up = smoothstep(0.0f, shape.x, h);
    float down = 1.0f - smoothstep(shape.y, 1.0f, h);
    return saturate1(up * down);
}

// Vertical stretch of the base noise per genus (1 = isotropic, 0.35 = features ~3 times taller than
// wide). Stretching makes clouds vertically coherent, but the noise's fine octaves stretch too and read
// as vertical striations on every wall of a cumulus: there the domes of coverageHeightFactor give the
// coherence instead and the noise stays nearly isotropic (bulging turrets). Stratiform decks keep the
// stretch: their tops and bases come from the profile, and their edges stay put with height.
float baseNoiseVerticalScale(int cloudType)
{
    if (cloudType == CLOUD_TYPE_CUMULUS || cloudType == CLOUD_TYPE_CUMULONIMBUS)
        return 0.8f;
    return 0.35f;
}

// Factor on the coverage with height (the coverage threshold rises): a vertically coherent column would
// otherwise end in a flat plateau over vertical walls. Cumulus: only the cores of the cells reach the
// upper part, so each cell is a dome over a flat base and cells of many heights stand side by side.
// Cumulonimbus: the tower narrows with height (5-10 km wide at mid level, the cell wider at the base);
// anvilShape then spreads the top again.
float coverageHeightFactor(int cloudType, float h)
{
    if (cloudType == CLOUD_TYPE_CUMULUS)
        return 1.0f - 0.8f * h * h;
    if (cloudType == CLOUD_TYPE_CUMULONIMBUS)
        return 1.0f - 0.35f * smoothstep(0.3f, 0.75f, h);
    return 1.0f;
}

// Vertical profile of the anvil slab (the part spread downwind at the tropopause) at height fraction h,
// where the slab's coverage is `coverage`: flat on top, the underside rising from 0.1 of the slab under
// the tower to its top at the thin edge, so the anvil tapers instead of ending in a square wall.
float anvilSlabProfile(float h, float coverage)
{
    float bottom = 1.0f - 0.9f * smoothstep(0.0f, 0.8f, coverage);
    return smoothstep(bottom, min(bottom + 0.25f, 1.0f), h) * (1.0f - smoothstep(0.75f, 1.0f, h));
}

// Häggström's cumulonimbus shape: the coverage-shaped base value raised to an exponent that falls from
// 1 to (1 - anvilAmount) between 65% and 95% of the height, so the top spreads into an anvil.
float anvilShape(float shapeValue, float h, float anvilAmount)
{
    float exponent = saturate1(remapValue(h, 0.65f, 0.95f, 1.0f, 1.0f - anvilAmount));
    return pow(saturate1(shapeValue), max(exponent, 0.05f));
}

// Häggström's density-height term for towers: dense low, thinning toward 0.2 at the top.
float anvilDensity(float h)
{
    float bottom = saturate1(remapValue(h, 0.0f, 0.15f, 0.0f, 1.0f));
    float top = mix(1.0f, 0.2f, smoothstep(0.3f, 1.0f, h));
    return bottom * top;
}

// Share of the low-frequency FBM that comes from the large-scale field (largeScaleFbm), the rest from
// the texel of R itself. It shifts the local cloud fraction over tens of kilometres: a share of 0.5
// turned whole 20 km regions clear or overcast at a coverage of 0.4; 0.2 keeps the data's coverage
// meaningful over a few kilometres while cells still cluster.
SKY_CONST float BASE_SHAPE_LARGE_WEIGHT = 0.2f;
// Amplitude of each of the three sines of largeScaleFbm: its spread (0.1) is about that of the noise's
// low-frequency FBM.
SKY_CONST float LARGE_FBM_AMPLITUDE = 0.08f;

// The large-scale field at noise-frame position p (m): three sines of 50-66 km wavelength around 0.5,
// their wave vectors whole cycles per offset modulus along each axis (`radPerM` = 2 pi / the modulus),
// so the field repeats with the offsets. Computed rather than read from a 192 km lookup of the noise as
// it was first: lavapipe filters the 8-bit noise to 8 bits, and a lookup that coarse came back in steps
// that cut cloud edges (tests/gpu/test_channels.cpp AChannelsEdgeMatchesACentredViewAtTheSameRays).
float largeScaleFbm(vec3 p, float radPerM)
{
    vec3 c = vec3(dot(p, vec3(5.0f, 3.0f, 0.0f)), dot(p, vec3(0.0f, 4.0f, 6.0f)), dot(p, vec3(7.0f, 0.0f, 3.0f)));
    vec3 s = sin(c * radPerM + vec3(4.2f, 1.3f, 0.4f));
    return 0.5f + LARGE_FBM_AMPLITUDE * (s.x + s.y + s.z);
}

// The base shape remap(R, lowFreqFbm - 1, 1, 0, 1) of our 128^3 noise (lowFreqFbm from the same texel
// and, BASE_SHAPE_LARGE_WEIGHT of it, from largeScaleFbm) is close to normal with this mean and spread
// (measured over the texture; tests/unit/test_cloud_math.cpp keeps them true). Mapping
// it through the normal CDF (logistic approximation, Bowling et al. 2009: 1.702) makes it uniform in
// [0,1], so that a coverage c leaves a cloud fraction of about c where the height profile is 1.
SKY_CONST float BASE_SHAPE_MEAN = 0.8299f;
SKY_CONST float BASE_SHAPE_SD = 0.0437f;

float equalizeBaseShape(float shape)
{
    return 1.0f / (1.0f + exp(-1.702f * (shape - BASE_SHAPE_MEAN) / BASE_SHAPE_SD));
}

// Coverage (after Schneider 2015, remap(base, 1 - coverage, 1, 0, 1)): with a uniform shape, the cloud
// fraction follows the coverage. Density rises over 0.25 of shape instead of the whole remaining range,
// so that full coverage is a solid deck and not a sponge, while edges stay soft.
SKY_CONST float COVERAGE_SOFTNESS = 0.25f;

float applyCoverage(float baseShape, float coverage)
{
    if (coverage <= 0.0f)
        return 0.0f;
    // Threshold 1 - c (fraction ~c); above 97 % coverage it slides down to -s so that full coverage has
    // no holes, while a 0.9-0.96 deck keeps lumpy tops and a few gaps.
    float threshold = 1.0f - coverage - COVERAGE_SOFTNESS * smoothstep(0.97f, 1.0f, coverage);
    return saturate1(remapValue(baseShape, threshold, threshold + COVERAGE_SOFTNESS, 0.0f, 1.0f));
}

// Detail erosion: wispy (inverted detail) at the base, billowy at the top (Schneider 2015).
float erodeWithDetail(float shape, float detailFbm, float h, float strength)
{
    float detail = mix(detailFbm, 1.0f - detailFbm, saturate1(h * 5.0f));
    return saturate1(remapValue(shape, detail * strength, 1.0f, 0.0f, 1.0f));
}

// How far up its layer (height fraction) the base of a genus is torn: stratus and nimbostratus hang
// ragged fragments (fractus, pannus) instead of a flat underside; 0 keeps the base flat.
float baseRaggedness(int cloudType)
{
    if (cloudType == CLOUD_TYPE_STRATUS)
        return 0.25f;
    if (cloudType == CLOUD_TYPE_NIMBOSTRATUS)
        return 0.2f;
    return 0.0f;
}

// Share of the layer over which a torn base fades in above its local height.
SKY_CONST float RAGGED_BASE_SOFTNESS = 0.05f;

// Factor on the density at height fraction h of a base torn up to `raggedness` of the layer: the local
// base lies at raggedness * tear (tear in [0,1], from the detail noise), so the underside is an uneven
// surface with fragments hanging below the rest; 1 above raggedness + the softness. It only removes
// cloud: nothing appears below the layer's base.
float raggedBaseFactor(float h, float raggedness, float tear)
{
    if (raggedness <= 0.0f)
        return 1.0f;
    float localBase = raggedness * saturate1(tear);
    return smoothstep(localBase, localBase + RAGGED_BASE_SOFTNESS, h);
}

// Rain makes bases dark: precipitation adds absorption near the base (docs/model.md). The extinction is
// the scattering coefficient times (1 + this factor), so the single-scattering albedo is 1 / (1 + it).
float rainAbsorptionFactor(float rainMmH, float heightFraction)
{
    return saturate1(rainMmH / 20.0f) * (1.0f - heightFraction) * 1.5f;
}

// Beer-powder (Schneider 2015): E = 2 e^-d (1 - e^-2d) for optical depth d.
float beerPowder(float opticalDepth)
{
    return 2.0f * exp(-opticalDepth) * (1.0f - exp(-2.0f * opticalDepth));
}

// Energy-conserving integration over one step (Hillaire 2016): the light scattered inside a segment
// of length dt, extinction sigmaE, in-scattered source S (radiance per metre), seen through the
// segment itself: S * (1 - e^-sigmaE dt) / sigmaE.
vec3 integrateScattering(vec3 source, float sigmaE, float dt)
{
    if (sigmaE <= 1e-8f)
        return source * dt;
    return source * ((1.0f - exp(-sigmaE * dt)) / sigmaE);
}
