// SPDX-License-Identifier: MIT
// Lighting of cloud samples and the view march. Included by cloud passes after cloud_density.glsl.

vec3 keyLightIrradiance()
{
    return moonIsKeyLight() ? frame.moonIrradiance.rgb : frame.sunIrradiance.rgb;
}

// Key light arriving at `p` through the atmosphere (transmittance LUT at the point's radius).
vec3 keyLightAt(vec3 p, vec3 lightDir)
{
    vec3 pc = p + vec3(0.0f, 0.0f, frame.earth.y);
    float r = length(pc);
    float muLight = dot(pc, lightDir) / r;
    return keyLightIrradiance() * sampleTransmittance(transmittanceLut, atmosphere, r, muLight);
}

// Optical depth toward the light: 6 samples in a widening cone, then one long sample at 3x the cone
// length (Schneider 2015); cheap density once the path is already dense, and beyond the first
// frame.marchLod.w samples. Near the eye those cheap far samples come precomputed from the light volume
// (shaders/shared/light_volume.h): one fetch instead of 5 density lookups. Beyond frame.marchLod.z metres
// (0: never) 3 cheap samples cover the same cone: there a pixel spans tens of metres and the view
// samples are far apart.
float lightOpticalDepth(vec3 p, vec3 lightDir, float distanceM)
{
    float stepM = frame.phaseTerms.w;
    uint samples = min(frame.march.y, 6u);
    bool coarse = frame.marchLod.z > 0.0f && distanceM > frame.marchLod.z;
    if (coarse && samples > 3u)
    {
        // Steps i = 1..n of stepM * i cover stepM * n(n+1)/2: the same length with 3 samples.
        stepM *= float(samples * (samples + 1u)) / 12.0f;
        samples = 3u;
    }
    uint fullSamples = coarse ? 0u : uint(frame.marchLod.w);
    uint liveSamples = samples;
    vec3 uvw = vec3(0.0f);
    bool fromVolume = false;
    if (!coarse && fullSamples < samples)
    {
        float h;
        vec2 mapPosM = weatherMapPosition(p, h);
        fromVolume = lightVolumeCoordinates(windowPlanePosition(mapPosM), h, uvw);
        if (fromVolume)
            liveSamples = fullSamples;
    }
    float depth = 0.0f;
    float t = 0.0f;
    for (uint i = 0u; i < liveSamples; ++i)
    {
        float len = stepM * float(i + 1u);
        t += len;
        bool cheap = i >= fullSamples || depth * frame.cloudLook.x > 0.3f;
        depth += cloudDensity(coneSamplePoint(p, lightDir, i, t, len), cheap, distanceM).density * len;
    }
    if (fromVolume)
    {
        // The volume holds transmittance (light_volume.h says why); 1e-7: below it, no light reaches.
        float tailTransmittance = textureLod(lightVolume, uvw, 0.0f).x;
        return depth * frame.cloudLook.x - log(max(tailTransmittance, 1e-7f));
    }
    depth += cloudDensity(p + lightDir * (3.0f * t), true, distanceM).density * t;
    return depth * frame.cloudLook.x;
}

// Light scattered toward the eye per unit incident radiance: multiple-scattering octaves (Wrenninge
// 2013, Hillaire 2016) of a two-lobe phase function, with Beer-powder darkening seen away from the light.
// The powder factor E(d)/e^-d = 2 (1 - e^-2d) is taken on the local optical depth over ~100 m (as Nubis
// does with the sample density), so thin wisps and crevices darken while sunlit faces do not.
float multipleScattering(float opticalDepth, float cosTheta, float localOpticalDepth)
{
    float a = 1.0f;
    float b = 1.0f;
    float c = 1.0f;
    float sum = 0.0f;
    int octaves = int(frame.cloudLook.w);
    for (int o = 0; o < octaves; ++o)
    {
        float phase = phaseTwoLobeHG(frame.phaseTerms.x * c, frame.phaseTerms.y * c, frame.phaseTerms.z, cosTheta);
        sum += b * phase * exp(-opticalDepth * a);
        a *= frame.lightingTerms.x;
        b *= frame.lightingTerms.y;
        c *= frame.lightingTerms.z;
    }
    float powder = 0.5f * beerPowder(localOpticalDepth) / max(exp(-localOpticalDepth), 1e-6f);
    float powderWeight = frame.lightingTerms.w * saturate1(0.5f - 0.5f * cosTheta);
    return sum * mix(1.0f, powder, powderWeight);
}

// Ambient light: sky above (brighter toward the top of the cloud) and ground bounce below.
vec3 ambientLight(float heightFraction)
{
    vec3 sky = frame.ambientSky.rgb * mix(0.35f, 1.0f, heightFraction);
    vec3 ground = frame.ambientGround.rgb * (frame.ambientSky.w / 3.14159265f) * (1.0f - heightFraction);
    return frame.cloudLook.z * (sky + ground);
}

// March from tEnter to tExit: cheap samples with double steps until a cloud is hit, full samples inside,
// back to cheap after 6 empty full samples; step length grows with distance; blue-noise start offset;
// stop when the transmittance falls below 0.01 (DESIGN §3 "March").
void marchClouds(vec3 dir, float tEnter, float tExit, inout vec3 radiance, inout float transmittance,
                 inout float depthWeighted, inout float depthWeight)
{
    vec3 lightDir = keyLightDirection();
    float cosTheta = dot(dir, lightDir);
    float thickness = frame.shell.y - frame.shell.x;
    float baseStep = clamp(thickness / 64.0f, 30.0f, 250.0f);
    // Steps grow geometrically with distance, just fast enough to reach tExit within the step budget
    // (long grazing paths through a layer get 1-10% steps; short ones keep the base step).
    float ratio = max(tExit, 1.0f) / max(tEnter + baseStep, baseStep);
    float growth = clamp(pow(ratio, 1.0f / float(frame.march.x)) - 1.0f, 0.005f, 0.015f);
    // Blue-noise start offset read at the ray's earth-fixed direction (world_jitter.glsl), not at its
    // pixel: the noise stays on the clouds when the view turns, and channels agree. Decorrelated per
    // frame by the golden ratio for accumulated full renders (frame.image.z; 0 in reprojected frames, so
    // that a pixel marched again gives the same value and a still view converges to the full render).
    ivec2 jitterTexel = worldJitterTexel(toNoiseFrame(dir), frame.worldJitter.x);
    float jitter = fract(texelFetch(blueNoise, jitterTexel, 0).x + 0.61803399f * float(frame.image.z));
    float t = tEnter + jitter * max(baseStep, tEnter * growth);
    bool full = false;
    int emptyFull = 0;
    uint fullSamples = 0u;
    bool lit = false;
    vec3 lightAtCloud = vec3(0.0f);
    // The budget counts full samples; cheap samples (no detail, no light march) may take as many again.
    float lastEmptyT = tEnter;  // the last sample that found no cloud
    for (uint i = 0u; i < 2u * frame.march.x && fullSamples < frame.march.x && t < tExit; ++i)
    {
        float dt = max(baseStep, t * growth);
        vec3 p = dir * t;
        if (!full)
        {
            if (cloudDensity(p, true, t).density > 0.0f)
            {
                full = true;
                emptyFull = 0;
                t = max(tEnter, t - dt);
            }
            else
            {
                lastEmptyT = t;
                t += 2.0f * dt;
            }
            continue;
        }
        // Deep in a cloud, where little of what lies behind reaches the eye, the base shape without detail
        // erosion (frame.detailLod.x: the view transmittance below which; 0: never).
        bool deep = transmittance < frame.detailLod.x;
        DensitySample ds = cloudDensity(p, deep, t);
        ++fullSamples;
        if (ds.density <= 0.0f)
        {
            lastEmptyT = t;
            if (++emptyFull >= 6)
                full = false;
            t += dt;
            continue;
        }
        if (t - lastEmptyT > 60.0f && lastEmptyT < t)
        {
            // Entering a cloud with long steps: find its surface by bisection, so that the sunlit skin
            // (a mean free path is ~20 m) is lit and not a point hundreds of metres inside it.
            float lo = lastEmptyT;
            float hi = t;
            for (int b = 0; b < 5; ++b)
            {
                float mid = 0.5f * (lo + hi);
                if (cloudDensity(dir * mid, true, mid).density > 0.0f)
                    hi = mid;
                else
                    lo = mid;
            }
            t = hi;
            p = dir * t;
            ds = cloudDensity(p, deep, t);
            lastEmptyT = t;
            if (ds.density <= 0.0f)
                continue;
        }
        emptyFull = 0;
        float sigmaS = ds.density * frame.cloudLook.x;
        // Rain makes bases dark: precipitation adds absorption near the base (DESIGN §3).
        float rainAbsorption = saturate1(ds.rainMmH / 20.0f) * (1.0f - ds.heightFraction) * 1.5f;
        float sigmaE = sigmaS * (1.0f + rainAbsorption);
        if (!lit)
        {
            lightAtCloud = keyLightAt(p, lightDir);
            lit = true;
        }
        // Light the part of the step that the eye sees: within ~one mean free path of its start.
        vec3 lightPoint = p + dir * min(0.5f * dt, 1.0f / sigmaE);
        float lightDepth = lightOpticalDepth(lightPoint, lightDir, t);
        vec3 source = sigmaS * (lightAtCloud * multipleScattering(lightDepth, cosTheta, sigmaS * 100.0f) + ambientLight(ds.heightFraction));
        radiance += transmittance * integrateScattering(source, sigmaE, dt);
        float next = transmittance * exp(-sigmaE * dt);
        depthWeighted += (transmittance - next) * t;
        depthWeight += transmittance - next;
        transmittance = next;
        if (transmittance < 0.01f)
        {
            transmittance = 0.0f;
            break;
        }
        t += dt;
    }
}
