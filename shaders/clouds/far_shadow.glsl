// SPDX-License-Identifier: MIT
// The shadow of the clouds beyond the light cone's reach, for a low sun. The cone (light_cone.glsl) looks
// ~3-4 km toward the light; with the sun a few degrees up, light reaching a cloud of a cumulus field has
// crossed tens of kilometres of the layer, and most of it met other clouds on the way. Without this term
// the sunset look view (skyservice/app/look_views.cpp) came out 6x brighter than the path-traced
// reference (mean luminance of its cloud pixels 0.47 vs 0.08), its bases golden where the reference's
// are dark blue-grey. Included by the march after cloud_density.glsl.
//
// The clouds along that path are taken as a random field: a path of length L through a layer of
// coverage c crosses about c L / D cells of chord D, each of them opaque to the direct light (a
// kilometre of cumulus is tens of optical depths), so the light that gets through is exp(-c L / D) (a
// Poisson count). c comes from the weather window at a few points along the path, so a clear sky
// toward the sun leaves the clouds lit. With the sun high the path leaves the layer within the cone's
// reach and nothing changes.

// The chord of a cloud cell that a low sun's path crosses (m): cumulus cells are 0.5-2 km across.
const float kFarShadowCellChordM = 1000.0f;
const int kFarShadowSamples = 4;

// Transmittance of the direct light from `p` toward `lightDir` beyond `reachM` metres (the cone's reach)
// up to where the path leaves the top of the cloud shell.
float farShadowTransmittance(vec3 p, vec3 lightDir, float reachM)
{
    vec3 pc = p + vec3(0.0f, 0.0f, frame.earth.y);
    float r = length(pc);
    float mu = dot(pc, lightDir) / r;
    // Distance to the sphere of the shell's top along the light (the point lies below it).
    float rTop = frame.earth.x + frame.shell.y;
    float disc = r * r * (mu * mu - 1.0f) + rTop * rTop;
    if (disc <= 0.0f)
        return 1.0f;
    float exitM = -r * mu + sqrt(disc);
    float pathM = exitM - reachM;
    if (pathM <= 0.0f)
        return 1.0f;
    float segmentM = pathM / float(kFarShadowSamples);
    float crossings = 0.0f;
    for (int i = 0; i < kFarShadowSamples; ++i)
    {
        vec3 q = p + lightDir * (reachM + (float(i) + 0.5f) * segmentM);
        float h;
        WeatherLookup w = weatherLookup(weatherMapPosition(q, h));
        if (!w.inside)
            continue;
        float coverage = 0.0f;
        for (int k = 0; k < MAX_CLOUD_LAYERS; ++k)
        {
            vec4 layer = textureLod(weatherWindow, vec3(w.uv, float(k)), 0.0f);
            if (layer.x < CLOUD_COVERAGE_MIN || h < layer.y || h > layer.z)
                continue;
            // Domes narrow toward the top (cloud_shape.glsl): a path near the tops crosses fewer cells.
            int cloudType = int(texelFetch(weatherWindow, ivec3(w.texel, k), 0).w + 0.5f);
            float hf = (h - layer.y) / max(layer.z - layer.y, 1.0f);
            coverage = max(coverage, layer.x * coverageHeightFactor(cloudType, hf));
        }
        crossings += coverage * segmentM;
    }
    return exp(-crossings / kFarShadowCellChordM);
}
