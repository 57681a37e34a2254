// SPDX-License-Identifier: MIT
// The medium of the reference path tracer: extinction and albedo at a point (the real-time model's
// cloudDensity, or the test slab), the majorant over a stretch of ray, the stretches of a ray inside the
// cloud shell, delta tracking to the next real collision and ratio tracking of the transmittance
// (Woodcock et al. 1965; Novák et al. 2014, "Residual Ratio Tracking for Estimating Attenuation in
// Participating Media"). Points are eye ENU metres, the earth's centre at (0, 0, -frame.earth.centreToEyeM).
// Included by reference_path.comp.glsl after cloud_density.glsl and empty_space.glsl.

// A stretch of ray tried for empty-space skipping first (m); it doubles while the column bounds show
// the stretches empty, as the march's search does.
const float REFERENCE_STRETCH_M = 1000.0f;

bool referenceFlag(uint flag)
{
    return (ref.control.w & flag) != 0u;
}

struct Medium
{
    float extinctionPerM;
    float albedo;  // single-scattering albedo
};

// Altitude (m) of the point `p`, free of float cancellation (cloud_density.glsl weatherMapPosition).
float altitudeAt(vec3 p)
{
    float h;
    weatherMapPosition(p, h);
    return h;
}

Medium mediumAt(vec3 p)
{
    if (referenceFlag(REFERENCE_FLAG_SLAB))
    {
        float h = altitudeAt(p);
        bool inside = h >= ref.slab.x && h <= ref.slab.y;
        return Medium(inside ? ref.slab.z : 0.0f, ref.slab.w);
    }
    // The real-time march's density at full detail; the detail erosion fades with the distance from the
    // eye as it does there (frame.march), so that both draw the same clouds.
    DensitySample s = cloudDensity(p, false, length(p));
    float rain = rainAbsorptionFactor(s.rainMmH, s.heightFraction);
    return Medium(s.density * frame.look.extinctionPerM * (1.0f + rain), 1.0f / (1.0f + rain));
}

// An upper bound of the extinction (1/m) on the stretch [t0, t1] of the ray (o, d): the layer bounds
// (layerBounds, shaders/shared/reference_params.h) of the columns it crosses, summed over the layers whose
// altitude ranges it reaches (cloudDensity sums the layers a point lies in).
float majorantOn(vec3 o, vec3 d, float t0, float t1)
{
    if (referenceFlag(REFERENCE_FLAG_SLAB))
        return ref.slab.z;
    float h0;
    float h1;
    vec2 m0 = weatherMapPosition(o + d * t0, h0);
    vec2 m1 = weatherMapPosition(o + d * t1, h1);
    // The altitude along a straight line is convex in t: lowest at an end or at the point nearest the
    // earth's centre.
    vec2 h = vec2(min(h0, h1), max(h0, h1));
    float tNearest = -dot(o + vec3(0.0f, 0.0f, frame.earth.centreToEyeM), d);
    if (tNearest > t0 && tNearest < t1)
        h.x = min(h.x, altitudeAt(o + d * tNearest));
    ivec2 i0;
    ivec2 i1;
    columnBoundsCover(m0, m1, i0, i1);
    vec4 columns = max(max(texelFetch(layerBounds, i0, 0), texelFetch(layerBounds, ivec2(i1.x, i0.y), 0)),
                       max(texelFetch(layerBounds, ivec2(i0.x, i1.y), 0), texelFetch(layerBounds, i1, 0)));
    float bound = 0.0f;
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        if (h.y < frame.layers[k].lowestBaseM || h.x > frame.layers[k].highestTopM)
            continue;
        bound += k == MAX_CLOUD_LAYERS ? ref.phase.w : columns[k];
    }
    return bound * frame.look.extinctionPerM;
}

// The shell that holds every cloud: the slab, or the window's lowest base to its highest top.
vec2 shellAltitudes()
{
    return referenceFlag(REFERENCE_FLAG_SLAB) ? vec2(ref.slab.x, ref.slab.y) : vec2(frame.shell.lowestBaseM, frame.shell.highestTopM);
}

// The next stretch of the ray (o, d) inside the shell beyond tFrom (m along the ray): false when there is
// none before the ground or the march's distance limit.
bool nextShellStretch(vec3 o, vec3 d, float tFrom, out float tEnter, out float tExit)
{
    vec3 q = o + d * tFrom;
    vec3 qc = q + vec3(0.0f, 0.0f, frame.earth.centreToEyeM);
    float r = length(qc);
    float h = altitudeAt(q);
    vec2 shell = shellAltitudes();
    float a;
    float b;
    if (!rayShellInterval(dot(qc, d) / r, h, shell.x, shell.y, frame.earth.radiusM, frame.shell.maxMarchDistanceM, a, b))
        return false;
    tEnter = tFrom + a;
    tExit = tFrom + b;
    return true;
}

// Distance along (o, d) to the ground, or < 0 when the ray misses it.
float groundDistance(vec3 o, vec3 d)
{
    vec3 oc = o + vec3(0.0f, 0.0f, frame.earth.centreToEyeM);
    float r = length(oc);
    return rayGroundDistance(r, dot(oc, d) / r, altitudeAt(o), frame.earth.radiusM);
}

// The state of a tracked ray (delta or ratio tracking), kept in ReferencePathState between dispatches.
struct Tracker
{
    float t;          // where the ray stands (m along it)
    float stretchEnd; // end of the current stretch of constant majorant
    float majorant;   // 1/m; 0: the next stretch is to be found
    float shellEnd;   // end of the current stretch inside the shell (< t: find the next one)
    float stretchM;   // length of the next stretch tried for skipping
};

Tracker startTracker()
{
    return Tracker(0.0f, 0.0f, 0.0f, -1.0f, REFERENCE_STRETCH_M);
}

// The least a stretch step moves the ray on (m): 1 cm, or 1e-6 t (~8 float spacings of t) where t + 1 cm
// rounds back to t (beyond 262 km): a step that stands still would find the same stretch again forever.
float minimumAdvance(float t)
{
    return max(0.01f, 1e-6f * t);
}

// What a step toward the next stretch found.
const int STRETCH_ENTERED = 0;  // a stretch of the shell entered: step again
const int STRETCH_FOUND = 1;    // a stretch that may hold cloud, with its majorant
const int STRETCH_NONE = 2;     // the ray has left the clouds for good
const int STRETCH_SKIPPED = 3;  // an empty stretch passed over (column bounds, zero majorant): step again

// One step toward the next stretch of the ray (o, d) that may hold cloud: each call does one thing, so
// that the caller can count its work (reference_path.comp.glsl).
int stretchStep(vec3 o, vec3 d, INOUT(Tracker) k)
{
    if (k.t >= k.shellEnd)
    {
        float enter;
        float exit;
        // A ray can leave the shell downward and re-enter it further on (a grazing path): a little on.
        if (!nextShellStretch(o, d, k.t + minimumAdvance(k.t), enter, exit))
            return STRETCH_NONE;
        k.t = enter;
        k.shellEnd = exit;
        k.stretchM = REFERENCE_STRETCH_M;
        return STRETCH_ENTERED;
    }
    float t1 = max(min(k.t + k.stretchM, k.shellEnd), k.t + minimumAdvance(k.t));
    bool skipping = !referenceFlag(REFERENCE_FLAG_SLAB) && (frame.image.flags & FRAME_FLAG_NO_SKIPPING) == 0u;
    if (skipping && noCloudOnSegment(o, d, k.t, t1))
    {
        k.t = t1;
        k.stretchM *= 2.0f;
        return STRETCH_SKIPPED;
    }
    k.stretchEnd = t1;
    k.majorant = majorantOn(o, d, k.t, t1);
    k.stretchM = REFERENCE_STRETCH_M;
    if (k.majorant > 0.0f)
        return STRETCH_FOUND;
    k.t = t1;
    return STRETCH_SKIPPED;
}

// One tentative collision: moves the tracker by an exponential step of its majorant; false when the step
// leaves the stretch (the tracker then stands at its end, the next stretch to be found).
bool tentativeCollision(INOUT(Tracker) k, INOUT(uint) rng)
{
    k.t -= log(1.0f - randomFloat(rng)) / k.majorant;
    if (k.t < k.stretchEnd)
        return true;
    k.t = k.stretchEnd;
    k.majorant = 0.0f;
    return false;
}
