// SPDX-License-Identifier: MIT
// Where in a layer cloud can be at all, from the shape terms of cloud_shape.glsl alone (no textures; CPU-tested,
// docs/style.md §8). Included after cloud_shape.glsl.
//
// Why: the density is applyCoverage(shape, coverage') with shape = the equalized base noise (always below 1)
// times the genus's height profile, and coverage' = coverage x coverageHeightFactor. Where the profile cannot
// reach the coverage threshold the density is 0 whatever the noise: above the domes of a cumulus layer of
// coverage 0.4 (its top 30 %), in the thin edge of an anvil. cloudDensity then skips the noise lookups and
// does not count the point as inside the layer, so the march's search may jump over such stretches, and the
// column bounds (skyservice/weather/column_bounds.cpp) bound each column by the heights where cloud can be.
#ifndef SKY_LIB_CLOUD_EXTENT_GLSL
#define SKY_LIB_CLOUD_EXTENT_GLSL

// Slack on the bound (in shape units): cloud is ruled out only where the bound lies this far below the
// threshold, so that float rounding (pow, smoothstep) never rules out a point the density would fill.
SKY_CONST float CLOUD_EXTENT_SLACK = 1e-3f;

// The threshold of applyCoverage for a coverage c > 0: the density is 0 where the shape is at or below it.
float coverageThreshold(float coverage)
{
    return 1.0f - coverage - COVERAGE_SOFTNESS * smoothstep(0.97f, 1.0f, coverage);
}

// Upper bound of a layer's shape before the coverage at height fraction h (the equalized noise is below 1;
// anvilShape is increasing in its shape value).
float layerShapeBound(int cloudType, float h, float anvilAmount)
{
    float profile = cloudHeightProfile(cloudType, h);
    if (cloudType == CLOUD_TYPE_CUMULONIMBUS)
        return anvilShape(profile, h, anvilAmount);
    return profile;
}

// False where a layer of this genus and coverage (before coverageHeightFactor) holds no cloud at height
// fraction h whatever the noise (cloudDensity's non-anvil layers).
bool layerMayHoldCloud(int cloudType, float h, float coverage, float anvilAmount)
{
    float c = coverage * coverageHeightFactor(cloudType, h);
    if (c <= 0.0f)
        return false;
    // Written so that a NaN (bad weather data) counts as cloud: the bounds must never hide any.
    return !(layerShapeBound(cloudType, h, anvilAmount) + CLOUD_EXTENT_SLACK <= coverageThreshold(c));
}

// The same for the anvil slab of coverage `coverage` (cloudDensity: its profile and its coverage x 1.8).
bool anvilSlabMayHoldCloud(float h, float coverage)
{
    float c = saturate1(coverage * 1.8f);
    if (c <= 0.0f)
        return false;
    return !(anvilSlabProfile(h, coverage) + CLOUD_EXTENT_SLACK <= coverageThreshold(c));
}

#endif
