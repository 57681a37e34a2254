// SPDX-License-Identifier: MIT
// Lighting of cloud samples and the view march. Included by cloud passes after cloud_density.glsl.

#include "shaders/clouds/key_light.glsl"

// The light cone of one lit view sample: optical depth toward the light from 6 samples in a widening
// cone, then one long sample beyond it (Schneider 2015; light_cone.glsl); cheap density once the path is
// already dense, and beyond the first frame.march.fullConeSamples samples. Within 15.4 km of the eye those cheap far
// samples come precomputed from the light volume or its far cascade (shaders/shared/light_volume.h): one
// fetch instead of 5 density lookups. Beyond frame.march.coneCheapBeyondM metres (0: never) 3 cheap samples cover the
// same cone: there a pixel spans tens of metres and the view samples are far apart. Beyond the light
// volume, a lit sample within frame.lightReuse.coneTailReuseM metres of the last one whose cone marched its far
// samples takes that cone's far part (ConeTail) instead of marching its own: the next lit sample in a
// cloud is tens of metres away, its far samples hundreds. The march takes the cone's density lookups
// one per loop iteration (marchClouds says why), so the cone is a small state. Beyond frame.march.coneNearMergeBeyondM
// metres (0: never) the detailed near samples are taken as one sample over their length: there the
// detail erosion has faded out and a pixel spans tens of metres. The frame ends when its costliest rays
// do, and those are far ones (the horizon bands, the Cb's surroundings).
struct LightCone
{
    float originT;         // the lit point's distance along the view ray (m): one register, not three
    float stepM;           // length of the first cone step; step i is (i + 1) x stepM
    uint next;             // the next cone sample (0-based); == live: the long sample, unless fromVolume
    uint live;             // cone samples marched here
    uint detailed;         // of which the first this many may take the detailed density
    float coveredM;        // the length the cone steps so far cover
    float depth;           // relative density x metres so far
    float tailTransmittance;  // the light volume's transmittance of the rest; < 0: no volume here
    // Relative density x metres of the far samples: marched here, or taken over; with the volume, the
    // depth whose diffusion factor (light_cone.glsl) the volume holds for them.
    float tailDepth;
    bool tailTaken;        // the far samples' depth is taken over from an earlier cone (ConeTail)
    bool tailMarched;      // this cone marches its far samples (the next lit samples may take them)
    bool nearMerged;       // its detailed near samples are taken as one, over their whole length
};

// The far samples of the last cone that marched them: where that cone started and their depth.
struct ConeTail
{
    float originT;  // along the view ray (m), as LightCone::originT
    float depth;
    bool valid;
};

// The relative density x metres whose diffusion factor is `factor` (diffusionFactor inverted).
float diffusionDepth(float factor)
{
    return (1.0f / max(factor, 1e-3f) - 1.0f) / (kDiffusionPerOpticalDepth * max(frame.look.extinctionPerM, 1e-12f));
}

LightCone beginLightCone(vec3 dir, float originT, float distanceM, ConeTail tail)
{
    LightCone c;
    c.originT = originT;
    vec3 p = dir * originT;
    c.stepM = frame.look.coneStepM;
    uint samples = min(frame.march.coneSamples, 6u);
    bool coarse = frame.march.coneCheapBeyondM > 0.0f && distanceM > frame.march.coneCheapBeyondM;
    if (coarse && samples > 3u)
    {
        // Steps i = 1..n of stepM * i cover stepM * n(n+1)/2: the same length with 3 samples.
        c.stepM *= float(samples * (samples + 1u)) / 12.0f;
        samples = 3u;
    }
    c.detailed = coarse ? 0u : frame.march.fullConeSamples;
    c.live = samples;
    c.tailTransmittance = -1.0f;
    c.tailDepth = 0.0f;
    c.tailTaken = false;
    c.tailMarched = false;
    c.nearMerged = frame.march.coneNearMergeBeyondM > 0u && distanceM > float(frame.march.coneNearMergeBeyondM) && c.detailed > 1u && c.detailed <= samples;
    if (!coarse && c.detailed < samples)
    {
        float h;
        vec2 mapPosM = weatherMapPosition(p, h);
        vec3 uvw;
        vec2 planeM = windowPlanePosition(mapPosM);
        if (lightVolumeCoordinates(frame.lightVolume.nearCascade, planeM, h, uvw))
        {
            c.live = c.detailed;
            vec2 tail = textureLod(lightVolume, uvw, 0.0f).xy;
            c.tailTransmittance = tail.x;
            c.tailDepth = diffusionDepth(tail.y);
        }
        else if (lightVolumeCoordinates(frame.lightVolume.farCascade, planeM, h, uvw))
        {
            c.live = c.detailed;
            vec2 tail = textureLod(lightVolumeFar, uvw, 0.0f).xy;
            c.tailTransmittance = tail.x;
            c.tailDepth = diffusionDepth(tail.y);
        }
        else if (tail.valid && distanceM > frame.lightReuse.coneTailReuseBeyondM && abs(originT - tail.originT) < frame.lightReuse.coneTailReuseM)
        {
            c.live = c.detailed;
            c.tailDepth = tail.depth;
            c.tailTaken = true;
        }
        else
            c.tailMarched = true;
    }
    c.next = 0u;
    c.coveredM = 0.0f;
    c.depth = 0.0f;
    return c;
}

// True when the cone has no density lookup left (its optical depth is final).
bool lightConeDone(LightCone c)
{
    return c.next > c.live || (c.next == c.live && (c.tailTransmittance >= 0.0f || c.tailTaken));
}

// Where the cone's next density lookup goes, whether it is cheap, and the metres it stands for.
vec3 lightConeSamplePoint(LightCone c, vec3 dir, vec3 lightDir, out bool cheap, out float lengthM)
{
    vec3 origin = dir * c.originT;
    if (c.next == 0u && c.nearMerged)
    {
        // Steps 1..detailed of stepM * i cover stepM * n(n+1)/2.
        lengthM = c.stepM * float(c.detailed * (c.detailed + 1u) / 2u);
        cheap = false;
        return coneSamplePoint(origin, lightDir, 0u, lengthM, lengthM);
    }
    if (c.next < c.live)
    {
        lengthM = c.stepM * float(c.next + 1u);
        cheap = c.next >= c.detailed || c.depth * frame.look.extinctionPerM > 0.3f;
        return coneSamplePoint(origin, lightDir, c.next, c.coveredM + lengthM, lengthM);
    }
    lengthM = kConeLongSampleSpan * c.coveredM;  // light_cone.glsl says why
    cheap = true;
    return origin + lightDir * (kConeLongSampleAt * c.coveredM);
}

void lightConeAdd(inout LightCone c, float density, float lengthM)
{
    c.depth += density * lengthM;
    if (c.next >= c.detailed)
        c.tailDepth += density * lengthM;
    if (c.next < c.live)
        c.coveredM += lengthM;
    c.next = c.next == 0u && c.nearMerged ? c.detailed : c.next + 1u;
}

// Optical depth toward the light of a finished cone, for the octaves (exponential attenuation).
float lightConeOpticalDepth(LightCone c)
{
    // The volume holds transmittance (light_volume.h says why); 1e-7: below it, no light reaches.
    if (c.tailTransmittance >= 0.0f)
        return c.depth * frame.look.extinctionPerM - log(max(c.tailTransmittance, 1e-7f));
    if (c.tailTaken)
        return (c.depth + c.tailDepth) * frame.look.extinctionPerM;
    return c.depth * frame.look.extinctionPerM;
}

// Optical depth toward the light of a finished cone, for the diffuse term (diffusionFactor). Marched, the
// same as lightConeOpticalDepth; from the volume, its far samples' depth comes from their interpolated
// diffusion factor, not from their transmittance: the diffuse term keeps light where the transmittance
// is gone (tens of optical depths into a cumulus), and the transmittance of texels that deep, interpolated,
// is that of the least deep one (its interior came out up to 2x too bright against the marched cone).
float lightConeDiffusionDepth(LightCone c)
{
    if (c.tailTransmittance >= 0.0f)
        return (c.depth + c.tailDepth) * frame.look.extinctionPerM;
    return lightConeOpticalDepth(c);
}

// Light scattered toward the eye per unit incident radiance: multiple-scattering octaves (Wrenninge
// 2013, Hillaire 2016) of a two-lobe phase function, with Beer-powder darkening seen away from the light.
// The octaves beyond the last carry the rest of the geometric series, b^N / (1 - b) of the energy, as one
// diffuse term: isotropic phase, attenuated not exponentially but as light diffusing through a
// conservative cloud (diffusionFactor of `diffusionDepth`, light_cone.glsl). Without it a few octaves lose
// most of the light that a thick cloud scatters many times: sunlit faces came out 2-3x darker than the
// path-traced reference, and the light deep in a cumulus fell to nothing (exp(-tau a^N)) where the
// reference keeps a few per cent.
// No octave beyond the first is attenuated more than that diffusing light: light scattered once already is
// part of the diffuse field, and exp(-tau a^o) (a^o = 0.5, 0.25) fell below it from tau ~1 on. With it the
// brightness hung on the octave count: 3 octaves instead of 2 took 10 % off the mean luminance of the
// cumulus seen from among them (0.77 of the reference's instead of 0.86), as the third octave took energy
// from the diffuse term and lost it by tau 10; now 2 and 3 octaves agree within 2 %.
// The powder factor E(d)/e^-d = 2 (1 - e^-2d) is taken on the local optical depth over ~100 m (as Nubis
// does with the sample density), so thin wisps and crevices darken while sunlit faces do not.
float multipleScattering(float opticalDepth, float diffusionDepth, float cosTheta, float localOpticalDepth)
{
    float a = 1.0f;
    float b = 1.0f;
    float c = 1.0f;
    float sum = 0.0f;
    float diffusion = diffusionFactor(diffusionDepth);
    int octaves = int(frame.look.octaves);
    for (int o = 0; o < octaves; ++o)
    {
        float phase = phaseTwoLobeHG(frame.look.phaseForwardG * c, frame.look.phaseBackG * c, frame.look.phaseForwardWeight, cosTheta);
        sum += b * phase * (o == 0 ? exp(-opticalDepth) : max(exp(-opticalDepth * a), diffusion));
        a *= frame.look.octaveAttenuation;
        b *= frame.look.octaveContribution;
        c *= frame.look.octaveEccentricity;
    }
    sum += b / max(1.0f - frame.look.octaveContribution, 0.05f) * (0.25f / 3.14159265f) * diffusion;
    float powder = 1.0f - exp(-2.0f * localOpticalDepth);  // 0.5 beerPowder(d) / e^-d
    float powderWeight = frame.look.powderStrength * saturate1(0.5f - 0.5f * cosTheta);
    return sum * mix(1.0f, powder, powderWeight);
}

// Ambient light: sky above (brighter toward the top of the cloud) and ground bounce below. Low in a thick
// cloud the sky is seen only through the cloud above (kSkyAmbientAtBase of it at the base). The ground
// sends E albedo / pi up, over the lower half of the sphere only, from ground that is largely in the
// shadow of the cloud above it (kGroundBounceShare: half a sphere, ~1/3 lit). With the earlier 0.35 and
// 1 the undersides of a cumulus seen from below were as bright as its sunlit towers; the path-traced
// reference has them at ~0.4 of the towers (means of the lowest and highest fifth, 64 samples per pixel;
// its few-sample renders read darker there, 0.28 at 8).
const float kSkyAmbientAtBase = 0.05f;
const float kGroundBounceShare = 0.15f;
vec3 ambientLight(float heightFraction)
{
    vec3 sky = frame.ambient.skyRadiance * mix(kSkyAmbientAtBase, 1.0f, heightFraction);
    vec3 ground = frame.ambient.groundIrradiance * (kGroundBounceShare * frame.ambient.groundAlbedo / 3.14159265f) *
                  (1.0f - heightFraction);
    return frame.look.ambientStrength * (sky + ground);
}

// The view march's step near the eye (m); steps grow with distance beyond it (marchClouds). A function, not
// a variable held through the march's loop.
float marchBaseStepM()
{
    return clamp((frame.shell.highestTopM - frame.shell.lowestBaseM) / 64.0f, 30.0f, 250.0f);
}

// Below this view transmittance the march stops and the ray counts as opaque.
const float kMarchOpaqueTransmittance = 0.01f;
// What a march iteration's one density lookup is for.
const int MARCH_SEARCH = 0;   // cheap samples with double steps until a cloud is hit
const int MARCH_FULL = 1;     // full view samples inside a cloud
const int MARCH_BISECT = 2;   // finding the surface of a cloud entered with a long step
const int MARCH_CONE = 3;     // the light cone of a lit view sample

// March from tEnter to tExit: cheap samples with double steps until a cloud is hit (jumping over
// stretches the weather's column bounds show empty), full samples inside, back to cheap after 6 empty
// full samples; step length grows with distance; blue-noise start offset; stop when the transmittance
// falls below kMarchOpaqueTransmittance (docs/model.md); the caller then takes the ray as opaque.
// `frontM` (0 on entry): where the opacity first reaches kCloudFrontOpacity (cloud_path.glsl), found inside
// the step that crosses it from the step's extinction; stays 0 when it never does.
// Every iteration takes exactly one density lookup, whichever part of the march it serves (a state:
// search, full view sample, surface bisection, light cone). The 32 rays of a GPU subgroup are in
// different parts at once; written as nested loops, the subgroup ran each part's lookups one after the
// other (a lane in the light cone made the others wait 2-7 lookups), here they share one.
// `lookups` counts the loop's iterations (density lookups and skip checks): what the ray cost
// (shaders/shared/march_order.h).
void marchClouds(vec3 dir, float tEnter, float tExit, inout vec3 radiance, inout float transmittance,
                 inout float depthWeighted, inout float frontM, out uint lookups)
{
    // The light direction and its angle to the ray come from the uniforms where they are used, not from
    // variables held through the loop (each would hold a register all the way).
    float baseStep = marchBaseStepM();
    // Steps grow geometrically with distance, just fast enough to reach tExit within the step budget
    // (long grazing paths through a layer get 1-10% steps; short ones keep the base step).
    float ratio = max(tExit, 1.0f) / max(tEnter + baseStep, baseStep);
    float growth = clamp(pow(ratio, 1.0f / float(frame.march.maxViewSteps)) - 1.0f, 0.005f, 0.015f);
    // Blue-noise start offset read at the ray's earth-fixed direction (world_jitter.glsl), not at its
    // pixel: the noise stays on the clouds when the view turns, and channels agree. Decorrelated per
    // frame by the golden ratio for accumulated full renders (frame.sequence.frameIndex; 0 in reprojected frames, so
    // that a pixel marched again gives the same value and a still view converges to the full render).
    ivec2 jitterTexel = worldJitterTexel(toNoiseFrame(dir), frame.march.jitterTexelRad);
    float jitter = fract(texelFetch(blueNoise, jitterTexel, 0).x + 0.61803399f * float(frame.sequence.frameIndex));
    float t = tEnter + jitter * max(baseStep, tEnter * growth);
    int state = MARCH_SEARCH;
    // Empty-space skipping in the search (empty_space.glsl): the stretch tried next, where the last
    // stretch that may hold cloud ends (searched step by step until then), and whether the last view
    // sample lay outside every layer. Inside one (in the gaps of a cumulus field, or with the eye in a
    // deck) a check fails for sure, as the bounds hold that layer, and would only cost its fetch; so the
    // first check waits for the first sample.
    bool skipping = (frame.image.flags & FRAME_FLAG_NO_SKIPPING) == 0u;
    float skipStretchM = 0.0f;
    float recheckT = tEnter;
    bool outsideLayers = false;
    // MARCH_FULL: the empty full samples in a row; MARCH_BISECT: the halvings left (one variable: each
    // variable carried through the loop holds a register all the way: BENCHMARKS.md).
    int stateCount = 0;
    // The budget counts full samples; cheap samples (no detail, no light march) may take as many again.
    // View samples in the low 16 bits, full samples in the high 16 (one register).
    uint samples = 0u;
    // The last sample that found no cloud. A bisection narrows [lastEmptyT, t] down to a cloud's surface:
    // lastEmptyT stays empty, t in the cloud.
    float lastEmptyT = tEnter;
    bool afterEmpty = true;     // the view sample before this one found no cloud
    // The radiance is summed as three scalars, not as a colour: every lit sample's light is the key light
    // at the ray's first lit sample (at litFirstT; < 0: none yet) times what its octaves pass
    // (directSum), plus the ambient light, linear in the height fraction (ambientSum, ambientHeightSum).
    // The key light and its far shadow (far_shadow.glsl) are then taken once, after the loop: inside it
    // the far shadow's lookups spilled registers and slowed the march (BENCHMARKS.md).
    float litFirstT = -1.0f;
    float directSum = 0.0f;
    float ambientSum = 0.0f;
    float ambientHeightSum = 0.0f;
    // The lit view sample whose light cone is being marched. During a bisection these three hold the sample
    // at t instead (its density, rain rate and height fraction): the two are never needed at once,
    // and each variable carried through the loop holds a register all the way (BENCHMARKS.md).
    float litSigmaS = 0.0f;
    float litSigmaE = 0.0f;
    float litHeightFraction = 0.0f;
    float litStepM = 0.0f;  // the step it stands for
    LightCone cone = LightCone(0.0f, 0.0f, 1u, 0u, 0u, 0.0f, 0.0f, -1.0f, 0.0f, false, false, false);
    ConeTail coneTail = ConeTail(0.0f, 0.0f, false);
    // The last cone marched here (not taken over): where it started and its optical depth (the diffuse
    // term's: lightConeDiffusionDepth; one register, so the octaves of the deep samples that take it take
    // that too, where the volume lit it a little deeper than its transmittance says); deep lit samples
    // within frame.lightReuse.deepLightReuseM metres of it take that light.
    float lastConeT = 0.0f;
    float lastConeDepth = -1.0f;
    // The step of the last view sample: a bisection moves the sample to the surface it finds but keeps
    // the step length it was taken with.
    float dt = baseStep;
    // 13 lookups at most per view sample (itself, 5 bisection, 6 cone, the long one).
    uint lookupBudget = 13u * 2u * frame.march.maxViewSteps;
    // `lookups` counts the iterations: it is the loop's counter too.
    for (lookups = 0u; lookups < lookupBudget;)
    {
        bool viewSample = state == MARCH_SEARCH || state == MARCH_FULL;
        uint viewSamples = samples & 0xffffu;
        uint fullSamples = samples >> 16u;
        if (viewSample && (viewSamples >= 2u * frame.march.maxViewSteps || fullSamples >= frame.march.maxViewSteps || t >= tExit))
            break;
        ++lookups;
        if (viewSample)
            dt = max(marchBaseStepM(), t * growth);
        if (state == MARCH_SEARCH && skipping && outsideLayers && t >= recheckT)
        {
            // Jump over a stretch the column bounds show empty (at least 4 search steps), doubling it
            // while that holds; a stretch that may hold cloud is searched step by step, and the next one
            // tried beyond it is half as long.
            float stretchM = max(skipStretchM, 8.0f * dt);
            float t1 = min(t + stretchM, tExit);
            if (noCloudBetween(dir, t, t1))
            {
                lastEmptyT = t1;
                afterEmpty = true;
                t = t1;
                skipStretchM = 2.0f * stretchM;
                continue;
            }
            recheckT = t1;
            skipStretchM = 0.5f * stretchM;
        }
        // Deep in a cloud, where little of what lies behind reaches the eye, the base shape without detail
        // erosion (frame.march.detailMinTransmittance: the view transmittance below which; 0: never).
        bool deep = transmittance < frame.march.detailMinTransmittance;
        vec3 q = dir * t;
        bool cheap = state == MARCH_SEARCH || deep;
        float coneLengthM = 0.0f;
        if (state == MARCH_BISECT)
            q = dir * (0.5f * (lastEmptyT + t));
        else if (state == MARCH_CONE)
            q = lightConeSamplePoint(cone, dir, keyLightDirection(), cheap, coneLengthM);
        DensitySample ds = cloudDensity(q, cheap, t);
        if (viewSample)
            outsideLayers = !ds.inLayer;

        if (state == MARCH_SEARCH)
        {
            samples += 1u;
            if (ds.density > 0.0f)
            {
                state = MARCH_FULL;
                stateCount = 0;
                t = max(tEnter, t - dt);
            }
            else
            {
                lastEmptyT = t;
                afterEmpty = true;
                t += 2.0f * dt;
            }
            continue;
        }
        if (state == MARCH_FULL)
        {
            samples += 0x10001u;
            if (ds.density <= 0.0f)
            {
                lastEmptyT = t;
                afterEmpty = true;
                if (++stateCount >= 6)
                    state = MARCH_SEARCH;
                t += deep ? dt * frame.march.deepStepFactor : dt;
                continue;
            }
            if (afterEmpty && t - lastEmptyT > 60.0f)
            {
                // Entering a cloud with a long step: find its surface (as this sample sees the cloud: with
                // detail erosion unless deep) by bisection, so that the sunlit skin (a mean free path is
                // ~20 m) is lit and not a point up to a step inside it.
                litSigmaS = ds.density;
                litSigmaE = ds.rainMmH;
                litHeightFraction = ds.heightFraction;
                stateCount = 5;
                state = MARCH_BISECT;
                continue;
            }
        }
        if (state == MARCH_BISECT)
        {
            float mid = 0.5f * (lastEmptyT + t);
            if (ds.density > 0.0f)
            {
                t = mid;
                litSigmaS = ds.density;
                litSigmaE = ds.rainMmH;
                litHeightFraction = ds.heightFraction;
            }
            else
                lastEmptyT = mid;
            if (--stateCount > 0)
                continue;
            ds = DensitySample(litSigmaS, litSigmaE, litHeightFraction, true);
        }
        if (state != MARCH_CONE)
        {
            // A lit view sample (full, or at the surface a bisection found): start its light cone.
            stateCount = 0;
            bool firstInCloud = afterEmpty;
            afterEmpty = false;
            litSigmaS = ds.density * frame.look.extinctionPerM;
            // Rain makes bases dark: precipitation adds absorption near the base (docs/model.md).
            float rainAbsorption = rainAbsorptionFactor(ds.rainMmH, ds.heightFraction);
            litSigmaE = litSigmaS * (1.0f + rainAbsorption);
            litHeightFraction = ds.heightFraction;
            // Inside a cloud a step covers at most frame.march.maxStepOpticalDepth of optical depth at this sample's
            // extinction, so that the sunlit skin, a mean free path deep, gets its samples. The sample at
            // a surface is thin (the bisection ends where the density starts), so its step counts the
            // full-density extinction; while the view transmittance is above 0.5, at least half of it
            // (the eroded skin is thin too, and what the eye sees). Thinner cloud behind that keeps its
            // long steps. Deep samples may stand for a longer step (frame.march.deepStepFactor).
            litStepM = dt;
            if (frame.march.maxStepOpticalDepth > 0.0f)
            {
                float floorSigma = firstInCloud          ? frame.look.extinctionPerM
                                   : transmittance > 0.5f ? 0.5f * frame.look.extinctionPerM
                                                          : 0.0f;
                litStepM = min(litStepM, frame.march.maxStepOpticalDepth / max(litSigmaE, floorSigma));
            }
            if (deep)
                litStepM *= frame.march.deepStepFactor;
            if (litFirstT < 0.0f)
                litFirstT = t;
            // Light the step where the eye sees it: at its mean depth weighted by the transmittance from
            // its start, 1/s - L e^-sL / (1 - e^-sL) (L/2 for a clear step, one mean free path for a
            // dense one).
            float stepDepth = litSigmaE * litStepM;
            float lightDepthM = stepDepth < 1e-3f ? 0.5f * litStepM
                                                  : 1.0f / litSigmaE - litStepM / (exp(stepDepth) - 1.0f);
            float litT = t + lightDepthM;
            if (deep && lastConeDepth >= 0.0f && abs(litT - lastConeT) < frame.lightReuse.deepLightReuseM)
            {
                // Behind a view transmittance below frame.march.detailMinTransmittance the light of the last cone, finished.
                cone = LightCone(litT, 0.0f, 0u, 0u, 0u, 0.0f, 0.0f, exp(-lastConeDepth),
                                 lastConeDepth / max(frame.look.extinctionPerM, 1e-12f), false, false, false);
            }
            else
                cone = beginLightCone(dir, litT, t, coneTail);
            state = MARCH_CONE;
        }
        else
            lightConeAdd(cone, ds.density, coneLengthM);
        if (!lightConeDone(cone))
            continue;
        if (cone.tailMarched)
            coneTail = ConeTail(cone.originT, cone.tailDepth, true);
        float lightDepth = lightConeOpticalDepth(cone);
        float diffusionDepth = lightConeDiffusionDepth(cone);
        if (cone.live > 0u)
        {
            lastConeT = cone.originT;
            lastConeDepth = diffusionDepth;
        }
        float cosTheta = dot(dir, keyLightDirection());
        float weight = transmittance * litSigmaS * integrateScattering(vec3(1.0f), litSigmaE, litStepM).x;
        directSum += weight * multipleScattering(lightDepth, diffusionDepth, cosTheta, litSigmaS * 100.0f);
        ambientSum += weight;
        ambientHeightSum += weight * litHeightFraction;
        float next = transmittance * exp(-litSigmaE * litStepM);
        depthWeighted += (transmittance - next) * t;
        if (frontM == 0.0f && next <= 1.0f - kCloudFrontOpacity)
            frontM = t + clamp(log(transmittance / (1.0f - kCloudFrontOpacity)) / max(litSigmaE, 1e-12f), 0.0f, litStepM);
        transmittance = next;
        if (transmittance < kMarchOpaqueTransmittance)
            break;
        t += litStepM;
        state = MARCH_FULL;
    }
    if (litFirstT >= 0.0f)
    {
        vec3 p = dir * litFirstT;
        vec3 keyLight = keyLightAt(p, keyLightDirection()) * farShadowTransmittance(p, keyLightDirection(), lightConeReachM());
        radiance += keyLight * directSum + ambientLight(0.0f) * (ambientSum - ambientHeightSum) +
                    ambientLight(1.0f) * ambientHeightSum;
    }
}
