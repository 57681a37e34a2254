// SPDX-License-Identifier: MIT
// The shadow of the clouds beyond the light cone's reach, for a low sun. The cone (light_cone.glsl) looks
// ~3-4 km toward the light; with the sun a few degrees up, light reaching a cloud of a cumulus field has
// crossed tens of kilometres of the layer, and most of it met other clouds on the way. Without this term
// the sunset look view (skyservice/app/look_views.cpp) came out 6x brighter than the path-traced
// reference (mean luminance of its cloud pixels 0.47 vs 0.08), its bases golden where the reference's
// are dark blue-grey. Included by the march after cloud_density.glsl; the march takes it once per ray, at
// its first lit sample (cloud_lighting.glsl marchClouds).
//
// The clouds along that path are taken as a random field: a path of length L through a layer of
// coverage c crosses about c L / D cells, each of them opaque to the direct light (a kilometre of
// cumulus is tens of optical depths), so the light that gets through is exp(-c L / D) (a Poisson count).
// c comes from the weather window at a few points along the path, so a clear sky toward the sun leaves
// the clouds lit. With the sun high the path leaves the layer within the cone's
// reach and nothing changes.

// The path length per crossed cell at coverage 1 (m). Calibrated on the sunset look view against the
// reference (96x54, 8 samples per pixel): mean cloud luminance 0.082 vs 0.079, underside/top 0.26 vs
// 0.23 (means of the lowest and highest fifth); 1 km, the size of a cell, left no direct light at all
// (0.050): cells are not opaque at their thin edges, nor are they laid out at random.
const float kFarShadowCellChordM = 3000.0f;

// Distance along a ray from radius `r` (m from the earth's centre) with cosine `mu` to the vertical to
// where it leaves the sphere of radius `sphereR` > r.
float distanceOutOfSphere(float r, float mu, float sphereR)
{
    return -r * mu + sqrt(max(r * r * (mu * mu - 1.0f) + sphereR * sphereR, 0.0f));
}

// Transmittance of the direct light from `p` toward `lightDir` beyond `reachM` metres (the cone's reach).
// For each layer, the part of the path inside the layer's altitude band (frame.layers lowestBaseM, highestTopM, over the whole
// window) beyond the reach, with the coverage at its middle: one window lookup and one fetch per layer
// that the path crosses, twice (a lookup at points spread along the whole shell missed a low layer under a
// high shell top).
float farShadowTransmittance(vec3 p, vec3 lightDir, float reachM)
{
    vec3 pc = p + vec3(0.0f, 0.0f, frame.earth.centreToEyeM);
    float r = length(pc);
    float mu = dot(pc, lightDir) / r;
    float crossings = 0.0f;
    for (int k = 0; k < MAX_CLOUD_LAYERS; ++k)
    {
        float baseM = frame.layers[k].lowestBaseM, topM = frame.layers[k].highestTopM;
        float rTop = frame.earth.radiusM + topM;
        if (topM <= baseM || r >= rTop)
            continue;
        float rBottom = frame.earth.radiusM + baseM;
        float fromM = max(r < rBottom ? distanceOutOfSphere(r, mu, rBottom) : 0.0f, reachM);
        float toM = distanceOutOfSphere(r, mu, rTop);
        if (toM <= fromM)
            continue;
        // Two samples, at a quarter and three quarters of the way: the path rises through the layer, and
        // its cells narrow toward their tops (cloud_shape.glsl coverageHeightFactor).
        for (int i = 0; i < 2; ++i)
        {
            float h;
            float atM = mix(fromM, toM, i == 0 ? 0.25f : 0.75f);
            WeatherLookup w = weatherLookup(weatherMapPosition(p + lightDir * atM, h));
            vec4 layer = textureLod(weatherWindow, vec3(w.uv, float(k)), 0.0f);
            if (!w.inside || layer.x < CLOUD_COVERAGE_MIN || h < layer.y || h > layer.z)
                continue;
            float hf = (h - layer.y) / max(layer.z - layer.y, 1.0f);
            crossings += layer.x * coverageHeightFactor(int(layer.w + 0.5f), hf) * 0.5f * (toM - fromM);
        }
    }
    return exp(-crossings / kFarShadowCellChordM);
}
