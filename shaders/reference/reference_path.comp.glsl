// SPDX-License-Identifier: MIT
// Reference path tracer of the clouds (skyservice/render/reference_renderer.h): the real-time model's
// density (cloud_density.glsl: the same weather window, noise textures and layers), lit by the sun and the
// moon through the atmosphere's transmittance, the sky (sky-view LUT) and the ground, with every order of
// scattering. One invocation per pixel carries its path on for at most ref.control.z loop iterations, keeps
// it in the path buffer for the next dispatch, adds the samples it finished to the pixel's running sums and
// writes the average so far in the march's format (premultiplied cloud radiance, alpha = 1 - transmittance,
// the distance of the first collision), which the real-time composite then draws.
//
// A path: delta tracking to the next real collision (reference_media.glsl); at each one the path weight
// takes the albedo, next-event estimation adds one light (sun or moon, drawn by irradiance) through the
// clouds' ratio-tracked transmittance, and the next direction is drawn from the phase function. Every
// step of either tracking is one iteration of one loop (a state machine, REFERENCE_MODE_*), so that the
// work of a dispatch can be bounded. A path
// that leaves the clouds downward meets a Lambertian ground (frame.ambient.groundAlbedo), one that leaves upward
// takes the sky-view LUT's radiance in its direction (the LUT is made for the eye's altitude: the air
// above the clouds as the eye sees it). The eye ray's own first collision makes the alpha and depth; a ray
// that meets no cloud adds nothing (the composite draws the sky and ground behind).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require  // [[unroll]] in cloud_density.glsl

#include "shaders/shared/frame_params.h"
#include "shaders/shared/weather_window.h"
#include "shaders/shared/atmosphere_params.h"
#include "shaders/shared/light_volume.h"
#include "shaders/shared/column_bounds.h"
#include "shaders/shared/reference_params.h"
#include "shaders/lib/shell.glsl"
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/phase.glsl"
#include "shaders/lib/phase_sampling.glsl"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/window_warp.glsl"

layout(local_size_x = WORKGROUP_SIZE_2D, local_size_y = WORKGROUP_SIZE_2D) in;

layout(push_constant) uniform PushBlock { ReferencePush ref; };
layout(binding = 0, std140) PARAMS_BLOCK FrameBlock { FrameParams frame; };
layout(binding = 1, std140) PARAMS_BLOCK AtmosphereBlock { AtmosphereParams atmosphere; };
layout(binding = 2) uniform sampler2DArray weatherWindow;
layout(binding = 3) uniform sampler3D baseNoise;
layout(binding = 4) uniform sampler3D detailNoise;
layout(binding = 5) uniform sampler2D curlNoise;
layout(binding = 6) uniform sampler2D transmittanceLut;
layout(binding = 7) uniform sampler2D skyViewLut;
layout(binding = 8) uniform usampler2D columnBounds;
// Running sums over the samples finished: radiance (rgb) and first collisions of the eye ray (a); the
// distances of those collisions (m).
layout(binding = 9, rgba32f) uniform image2D radianceSum;
layout(binding = 10, r32f) uniform image2D depthSum;
layout(binding = 11, rgba16f) uniform writeonly image2D cloudOut;
layout(binding = 12, r32f) uniform writeonly image2D depthOut;
// Counters (shaders/shared/reference_params.h ReferenceCounters): the host dispatches again while a pixel
// is unfinished, up to its bound.
layout(binding = 13, std430) buffer StatsBlock { ReferenceCounters stats; };
layout(binding = 14, std430) buffer PathBlock { ReferencePathState paths[]; };
// The layer bounds of the window's columns (shaders/shared/reference_params.h): the tracking's majorants.
layout(binding = 15) uniform sampler2D layerBounds;

#include "shaders/lib/atmosphere_sampling.glsl"
#include "shaders/clouds/cloud_density.glsl"
#include "shaders/clouds/light_cone.glsl"
#include "shaders/clouds/key_light.glsl"
#include "shaders/clouds/empty_space.glsl"
#include "shaders/clouds/high_cloud.glsl"
#include "shaders/clouds/view_ray.glsl"
#include "shaders/clouds/cloud_path.glsl"
#include "shaders/reference/reference_media.glsl"

float luminanceOf(vec3 c)
{
    return dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
}

float phaseAt(float nu)
{
    return referencePhase(int(ref.phase.x), vec3(frame.look.phaseForwardG, frame.look.phaseBackG, frame.look.phaseForwardWeight), ref.phase.y, nu);
}

// The irradiance of a light arriving at `p` from direction `l` through the atmosphere (no clouds).
vec3 lightThroughAir(vec3 p, vec3 l, vec3 topIrradiance, float angularRadiusRad)
{
    vec3 pc = p + vec3(0.0f, 0.0f, frame.earth.centreToEyeM);
    float r = length(pc);
    return topIrradiance * transmittanceToLight(transmittanceLut, atmosphere, r, dot(pc, l) / r, angularRadiusRad);
}

// Next-event estimation at `p`: one light, drawn in proportion to its irradiance there; `direction` is
// its direction, `irradiance` what arrives through the air divided by the probability of the draw (the
// clouds' transmittance is tracked after).
void sampleLight(vec3 p, INOUT(uint) rng, out vec3 direction, out vec3 irradiance)
{
    direction = ref.testLight.xyz;
    irradiance = vec3(1.0f);
    if (!referenceFlag(REFERENCE_FLAG_UNIT_LIGHT))
    {
        vec3 sun = lightThroughAir(p, frame.light.sunDirectionEnu, frame.light.sunIrradiance, atmosphere.radii.z);
        vec3 moon = lightThroughAir(p, frame.light.moonDirectionEnu, frame.light.moonIrradiance, atmosphere.radii.w);
        float sunWeight = luminanceOf(sun);
        float moonWeight = luminanceOf(moon);
        float pickSun = sunWeight + moonWeight > 0.0f ? sunWeight / (sunWeight + moonWeight) : 1.0f;
        bool sunPicked = randomFloat(rng) < pickSun;
        direction = sunPicked ? frame.light.sunDirectionEnu : frame.light.moonDirectionEnu;
        irradiance = sunPicked ? sun / max(pickSun, 1e-30f) : moon / max(1.0f - pickSun, 1e-30f);
    }
}

// Radiance of the sky in direction d, as the eye sees it (zero for the test light).
vec3 skyRadiance(vec3 d)
{
    if (referenceFlag(REFERENCE_FLAG_UNIT_LIGHT))
        return vec3(0.0f);
    return sampleSkyView(skyViewLut, atmosphere, d, frame.earth.centreToEyeM);
}

float groundAlbedo()
{
    return referenceFlag(REFERENCE_FLAG_UNIT_LIGHT) ? 0.0f : frame.ambient.groundAlbedo;
}

// The eye ray of a sample: a random point of the pixel, or a cosine-distributed direction about the
// vertical (REFERENCE_FLAG_HEMISPHERE).
vec3 cameraRay(ivec2 pixel, INOUT(uint) rng)
{
    float u1 = randomFloat(rng);
    float u2 = randomFloat(rng);
    if (referenceFlag(REFERENCE_FLAG_HEMISPHERE))
    {
        vec3 up = vec3(0.0f, 0.0f, referenceFlag(REFERENCE_FLAG_HEMISPHERE_DOWN) ? -1.0f : 1.0f);
        return sampleCosineDirection(up, u1, u2);
    }
    return viewRayDirection(vec2(pixel) + vec2(u1, u2));
}

// A pixel's path as the loop works on it (ReferencePathState unpacked).
struct Path
{
    vec3 o;           // start of the ray being tracked
    float weight;
    vec3 d;           // the path's direction
    float hitT;       // the eye ray's first collision (m; < 0: none)
    vec3 l;           // the shadow ray's direction
    float shadowT;    // its transmittance so far
    vec3 pending;     // what it adds if it gets through
    vec3 radiance;    // the sample's radiance so far
    uint rng;
    uint events;      // scattering events (cloud and ground)
    uint mode;
    uint samplesDone;
    Tracker k;
};

Path loadPath(uint index)
{
    ReferencePathState s = paths[index];
    return Path(s.origin.xyz, s.origin.w, s.direction.xyz, s.direction.w, s.light.xyz, s.light.w, s.pending.rgb,
                s.radiance.rgb, s.control.x, s.control.y, s.control.z, s.control.w,
                Tracker(s.tracker.x, s.tracker.y, s.tracker.z, s.tracker.w, s.stretch.x));
}

void storePath(uint index, Path p)
{
    paths[index] = ReferencePathState(vec4(p.o, p.weight), vec4(p.d, p.hitT), vec4(p.l, p.shadowT),
                                      vec4(p.pending, 0.0f), vec4(p.radiance, 0.0f),
                                      vec4(p.k.t, p.k.stretchEnd, p.k.majorant, p.k.shellEnd),
                                      vec4(p.k.stretchM, 0.0f, 0.0f, 0.0f),
                                      uvec4(p.rng, p.events, p.mode, p.samplesDone));
}

// The sums of the samples finished in this dispatch.
struct Sums
{
    vec3 radiance;
    float collisions;
    float distanceM;
};

// The sample is done: into the sums, and on to the next one (or idle).
void endSample(INOUT(Path) p, INOUT(Sums) sums)
{
    sums.radiance += p.radiance;
    if (p.hitT >= 0.0f)
    {
        sums.collisions += 1.0f;
        sums.distanceM += p.hitT;
    }
    p.samplesDone += 1u;
    p.mode = p.samplesDone >= ref.control.y ? REFERENCE_MODE_IDLE : REFERENCE_MODE_START;
}

// A new ray from p.o along p.d after a scattering event (Russian roulette once the weight is small: rain
// absorption, ground bounces; unbiased).
void continuePath(INOUT(Path) p, INOUT(Sums) sums)
{
    p.events += 1u;
    if (p.events >= ref.limits.x)
    {
        atomicAdd(stats.pathsTruncated, 1u);
        endSample(p, sums);
        return;
    }
    if (p.weight < 0.2f)
    {
        if (randomFloat(p.rng) * 0.2f >= p.weight)
        {
            endSample(p, sums);
            return;
        }
        p.weight = 0.2f;
    }
    p.k = startTracker();
    p.mode = REFERENCE_MODE_TRACK;
}

// The shadow ray is done (its transmittance final): its light, then the next direction, from the phase
// function at a cloud, cosine-distributed at the ground. Returns the loop iterations the phase sampling took.
uint afterShadow(INOUT(Path) p, INOUT(Sums) sums)
{
    p.radiance += p.pending * p.shadowT;
    uint iterations = 0u;
    if (p.mode == REFERENCE_MODE_SHADOW)
    {
        int model = int(ref.phase.x);
        float nu = sampleReferencePhaseCos(model, vec3(frame.look.phaseForwardG, frame.look.phaseBackG, frame.look.phaseForwardWeight), ref.phase.y, p.rng);
        iterations = model == REFERENCE_PHASE_HG_DRAINE ? 32u : 0u;  // sampleDraineCos's loop at most
        p.d = directionAround(p.d, nu, 2.0f * SKY_PI * randomFloat(p.rng));
    }
    else
    {
        vec3 up = normalize(p.o + vec3(0.0f, 0.0f, frame.earth.centreToEyeM));
        p.weight *= groundAlbedo();
        p.d = sampleCosineDirection(up, randomFloat(p.rng), randomFloat(p.rng));
    }
    continuePath(p, sums);
    return iterations;
}

// Starts the shadow ray toward a light drawn at p.o; `factor` is what multiplies the light's irradiance
// there (weight x phase, or weight x albedo x cos / pi at the ground).
uint startShadow(INOUT(Path) p, INOUT(Sums) sums, uint mode, vec3 normal, bool atGround)
{
    vec3 e;
    sampleLight(p.o, p.rng, p.l, e);
    float factor = atGround ? p.weight * groundAlbedo() / SKY_PI * max(dot(normal, p.l), 0.0f)
                            : p.weight * phaseAt(dot(p.d, p.l));
    p.pending = factor * e;
    p.shadowT = 1.0f;
    p.mode = mode;
    p.k = startTracker();
    if (p.pending == vec3(0.0f))
    {
        p.shadowT = 0.0f;
        return afterShadow(p, sums);
    }
    return 0u;
}

// The tracked ray left the clouds (no collision): the path meets the sky, the ground, or (the eye ray) nothing.
uint escape(INOUT(Path) p, INOUT(Sums) sums)
{
    if (p.mode != REFERENCE_MODE_TRACK)
        return afterShadow(p, sums);
    if (p.events == 0u)
    {
        endSample(p, sums);  // the eye ray met no cloud: the composite draws what lies behind
        return 0u;
    }
    float tGround = groundDistance(p.o, p.d);
    if (tGround < 0.0f)
    {
        p.radiance += p.weight * skyRadiance(p.d);
        endSample(p, sums);
        return 0u;
    }
    if (groundAlbedo() <= 0.0f)
    {
        endSample(p, sums);
        return 0u;
    }
    // A Lambertian ground under the clouds: its direct light, then a cosine-distributed bounce.
    vec3 g = p.o + p.d * tGround;
    vec3 up = normalize(g + vec3(0.0f, 0.0f, frame.earth.centreToEyeM));
    p.o = g + up * 0.01f;
    return startShadow(p, sums, REFERENCE_MODE_GROUND_SHADOW, up, true);
}

// Loop iterations a density lookup takes (cloudDensity's loop over the layers), counted against the budget;
// a stretch's majorant takes as many.
const uint DENSITY_ITERATIONS = uint(MAX_CLOUD_LAYERS) + 1u;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(frame.image.widthPx) || pixel.y >= int(frame.image.heightPx))
        return;
    uint index = uint(pixel.y) * frame.image.widthPx + uint(pixel.x);
    bool first = ref.control.x == 0u;
    Path p;
    if (first)
        p = Path(vec3(0.0f), 1.0f, vec3(0.0f, 0.0f, 1.0f), -1.0f, vec3(0.0f, 0.0f, 1.0f), 1.0f, vec3(0.0f),
                 vec3(0.0f), 0u, 0u, REFERENCE_MODE_START, 0u,
                 startTracker());
    else
        p = loadPath(index);
    Sums sums = Sums(vec3(0.0f), 0.0f, 0.0f);

    // One step of the path per iteration, within the budget (the iterations of the loops it calls
    // included), leaving room for the longest step.
    uint budget = ref.control.z - min(ref.control.z, 64u);
    uint steps = 0u;
    uint skipped = 0u;
    for (uint iterations = 0u; iterations < budget && p.mode != REFERENCE_MODE_IDLE;)
    {
        iterations += 1u;
        steps += 1u;
        if (p.mode == REFERENCE_MODE_START)
        {
            // Each sample's own stream: the pixel, the sample and the seed hashed together.
            p.rng = pcgHash(index ^ pcgHash(p.samplesDone ^ pcgHash(floatBitsToUint(ref.phase.z))));
            p.o = vec3(0.0f);
            p.d = cameraRay(pixel, p.rng);
            p.weight = 1.0f;
            p.hitT = -1.0f;
            p.radiance = vec3(0.0f);
            p.events = 0u;
            p.k = startTracker();
            p.mode = REFERENCE_MODE_TRACK;
            continue;
        }
        bool shadow = p.mode != REFERENCE_MODE_TRACK;
        vec3 rayD = shadow ? p.l : p.d;
        if (p.k.majorant <= 0.0f)
        {
            iterations += DENSITY_ITERATIONS;
            int found = stretchStep(p.o, rayD, p.k);
            if (found == STRETCH_SKIPPED)
                skipped += 1u;
            else if (found == STRETCH_NONE)
                iterations += escape(p, sums);
            continue;
        }
        if (!tentativeCollision(p.k, p.rng))
            continue;
        iterations += DENSITY_ITERATIONS;
        vec3 at = p.o + rayD * p.k.t;
        Medium m = mediumAt(at);
        if (m.extinctionPerM > p.k.majorant)
            atomicAdd(stats.majorantExceeded, 1u);
        if (shadow)
        {
            // Ratio tracking, with Russian roulette below 0.05 (a survivor carries 0.05).
            p.shadowT *= max(1.0f - m.extinctionPerM / p.k.majorant, 0.0f);
            if (p.shadowT < 0.05f)
            {
                if (randomFloat(p.rng) * 0.05f >= p.shadowT)
                {
                    p.shadowT = 0.0f;
                    iterations += afterShadow(p, sums);
                    continue;
                }
                p.shadowT = 0.05f;
            }
            continue;
        }
        // Delta tracking: a real collision with probability extinction / majorant.
        if (randomFloat(p.rng) * p.k.majorant >= m.extinctionPerM)
            continue;
        if (p.events == 0u)
            p.hitT = p.k.t;
        p.o = at;
        p.weight *= m.albedo;
        iterations += startShadow(p, sums, REFERENCE_MODE_SHADOW, vec3(0.0f), false);
    }
    storePath(index, p);
    if (p.mode != REFERENCE_MODE_IDLE)
    {
        atomicAdd(stats.pixelsUnfinished, 1u);
        atomicAdd(stats.samplesUnfinished, ref.control.y - p.samplesDone);
    }
    // 64-bit sums in two words: carry when the low word wraps (the old value shows it).
    if (atomicAdd(stats.stepsLow, steps) > 0xFFFFFFFFu - steps)
        atomicAdd(stats.stepsHigh, 1u);
    if (atomicAdd(stats.skippedLow, skipped) > 0xFFFFFFFFu - skipped)
        atomicAdd(stats.skippedHigh, 1u);

    vec4 sum = vec4(sums.radiance, sums.collisions);
    float distanceSum = sums.distanceM;
    if (!first)
    {
        sum += imageLoad(radianceSum, pixel);
        distanceSum += imageLoad(depthSum, pixel).x;
    }
    imageStore(radianceSum, pixel, sum);
    imageStore(depthSum, pixel, vec4(distanceSum, 0.0f, 0.0f, 0.0f));

    // The average so far, and the 2D high-cloud layer in front of or behind it as the march draws it
    // (cloud_march.comp.glsl).
    float n = float(max(p.samplesDone, 1u));
    vec3 cloudRadiance = sum.rgb / n;
    float alpha = sum.a / n;
    float cloudDepth = sum.a > 0.0f ? distanceSum / sum.a : 0.0f;
    vec3 dir = viewRayDirection(vec2(pixel) + 0.5f);
    float hc = frame.camera.eyeAltitudeM;
    HighCloudSample high = sampleHighCloud(dir, dir.z, hc, frame.earth.radiusM);
    if (high.alpha > 0.0f && !referenceFlag(REFERENCE_FLAG_UNIT_LIGHT | REFERENCE_FLAG_HEMISPHERE))
    {
        // The reference writes no depth layer: the fronts only fill the struct.
        CloudPath clouds = CloudPath(cloudRadiance, 1.0f - alpha, alpha * cloudDepth, alpha, 0.0f);
        CloudPath highCloud = CloudPath(high.radiance, 1.0f - high.alpha, high.alpha * high.distanceM, high.alpha, 0.0f);
        CloudPath c = hc > frame.shell.highCloudAltitudeM ? inFrontOf(highCloud, clouds) : inFrontOf(clouds, highCloud);
        cloudRadiance = c.radiance;
        alpha = 1.0f - c.transmittance;
        cloudDepth = c.depthWeight > 1e-4f ? c.depthWeighted / c.depthWeight : 0.0f;
    }
    imageStore(cloudOut, pixel, vec4(cloudRadiance, alpha));
    imageStore(depthOut, pixel, vec4(cloudDepth, 0.0f, 0.0f, 0.0f));
}
