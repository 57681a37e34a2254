// SPDX-License-Identifier: MIT
// Atmosphere lookups and integrators that read the LUTs: used by the atmosphere passes and by the
// lead's composite and cloud passes. Requires shaders/shared/atmosphere_params.h,
// shaders/lib/atmosphere.glsl and shaders/lib/phase.glsl to be included first.
//
// Unlike the other shaders/lib files this one calls texture(): the CPU reference
// (skyservice/sky/atmosphere_reference.cpp) compiles it as C++ with a bilinear sampler2D emulation, as
// Bruneton's tests do with their texture types, so the CPU and the GPU run the same integrators.
//
// Frames: directions are unit vectors in the eye's east-north-up frame; positions are relative to the
// earth centre in ENU axes (the eye is at (0, 0, camRM)). Irradiances are at the top of the atmosphere
// (renderer units); the results are radiances in those units per steradian.
// Sources: Hillaire 2020 (multiple-scattering LUT, sky-view LUT, energy-conserving step integration
// from Hillaire 2015 "Physically Based and Unified Volumetric Rendering in Frostbite").

vec3 atmosphereRgb(vec4 v)
{
    return vec3(v.x, v.y, v.z);
}

// Transmittance from rM to the top of the atmosphere along a ray of zenith cosine muSun. Rays that hit
// the ground are looked up as if they grazed the horizon: use transmittanceToLight for lights.
vec3 sampleTransmittance(sampler2D transmittanceLut, IN(AtmosphereParams) p, float rM, float muSun)
{
    return atmosphereRgb(texture(transmittanceLut, transmittanceLutUv(p, rM, muSun)));
}

// Transmittance to a light of the given angular radius, zero once the disk has set behind the earth.
vec3 transmittanceToLight(sampler2D transmittanceLut, IN(AtmosphereParams) p, float rM, float mu,
                          float angularRadiusRad)
{
    return sampleTransmittance(transmittanceLut, p, rM, mu) * lightVisibility(p, rM, mu, angularRadiusRad);
}

// Multiple-scattering transfer Psi_ms (Hillaire 2020 eq. 10) per unit light irradiance.
vec3 sampleMultiscatter(sampler2D multiscatterLut, IN(AtmosphereParams) p, float rM, float muLight)
{
    return atmosphereRgb(texture(multiscatterLut, multiscatterLutUv(p, rM, muLight)));
}

// 1 - exp(-x) over x per channel, without the cancellation of 1 - exp(-x) for tiny x.
vec3 atmosphereOneMinusExpOverX(vec3 x)
{
    vec3 direct = (vec3(1.0f) - exp(-x)) / max(x, vec3(1e-9f));
    vec3 series = vec3(1.0f) - 0.5f * x;
    return mix(direct, series, step(x, vec3(1e-3f)));
}

// The part of the ray originM + t dirEnu that lies in the atmosphere: [tStart, tEnd], ending at the
// ground when hitsGround. Returns false when the ray misses the atmosphere.
bool clipRayToAtmosphere(IN(AtmosphereParams) p, vec3 originM, vec3 dirEnu, OUT(float) tStart, OUT(float) tEnd,
                         OUT(bool) hitsGround)
{
    float top = p.radii.y;
    float r = length(originM);
    float mu = dot(originM, dirEnu) / r;
    tStart = 0.0f;
    tEnd = 0.0f;
    hitsGround = false;
    if (r > top)
    {
        float c = atmosphereDiffOfSquares(r, top);
        float b = r * mu;
        float disc = b * b - c;
        if (mu >= 0.0f || disc < 0.0f)
            return false;
        tStart = c / (sqrt(disc) - b);
        vec3 entry = originM + tStart * dirEnu;
        r = top;
        mu = dot(entry, dirEnu) / top;
    }
    hitsGround = rayIntersectsGround(p, r, mu);
    tEnd = tStart + distanceToAtmosphereExit(p, r, mu);
    return tEnd > tStart;
}

// Single scattering of both lights plus Hillaire's multiple-scattering term along the ray from originM
// over [0, tMaxM] (clipped to the atmosphere), in `steps` steps packed towards the origin
// (t ~ (i / steps)^2). inscatter is the radiance scattered towards the origin, transmittance the
// transmittance from the origin to the end of the segment.
// Phase functions of a view direction for the sun and the moon (constant along the ray).
struct ViewPhases
{
    float rayleighSun;
    float mieSun;
    float rayleighMoon;
    float mieMoon;
};

ViewPhases viewPhases(IN(AtmosphereParams) p, vec3 dirEnu, vec3 sunDirEnu, vec3 moonDirEnu)
{
    ViewPhases v;
    float nuSun = dot(dirEnu, sunDirEnu);
    float nuMoon = dot(dirEnu, moonDirEnu);
    float g = p.mieExtinction.w;
    v.rayleighSun = rayleighPhase(nuSun);
    v.rayleighMoon = rayleighPhase(nuMoon);
    v.mieSun = miePhaseCornetteShanks(g, nuSun);
    v.mieMoon = miePhaseCornetteShanks(g, nuMoon);
    return v;
}

// One step of length dt whose middle is at pos (m from the earth's centre): adds the light scattered
// toward the eye (single scattering of the sun and the moon plus the multiple-scattering LUT) seen
// through `transmittance`, then attenuates `transmittance` over the step (Hillaire 2015: source * T
// integrated analytically over the step).
void scatteringStep(sampler2D transmittanceLut, sampler2D multiscatterLut, IN(AtmosphereParams) p, vec3 pos, float dt,
                    ViewPhases ph, vec3 sunDirEnu, vec3 sunIrradiance, vec3 moonDirEnu, vec3 moonIrradiance,
                    INOUT(vec3) inscatter, INOUT(vec3) transmittance)
{
    float r = length(pos);
    float altitude = r - p.radii.x;
    float muSun = dot(pos, sunDirEnu) / r;
    float muMoon = dot(pos, moonDirEnu) / r;

    vec3 rayleigh = rayleighScatteringAt(p, altitude);
    vec3 mie = mieScatteringAt(p, altitude);
    vec3 extinction = extinctionAt(p, altitude);
    vec3 sunLight = transmittanceToLight(transmittanceLut, p, r, muSun, p.radii.z);
    vec3 moonLight = transmittanceToLight(transmittanceLut, p, r, muMoon, p.radii.w);
    vec3 multiSun = sampleMultiscatter(multiscatterLut, p, r, muSun);
    vec3 multiMoon = sampleMultiscatter(multiscatterLut, p, r, muMoon);
    vec3 source = sunIrradiance * (sunLight * (rayleigh * ph.rayleighSun + mie * ph.mieSun) + (rayleigh + mie) * multiSun) +
                  moonIrradiance *
                      (moonLight * (rayleigh * ph.rayleighMoon + mie * ph.mieMoon) + (rayleigh + mie) * multiMoon);

    vec3 opticalDepth = extinction * dt;
    inscatter += transmittance * source * dt * atmosphereOneMinusExpOverX(opticalDepth);
    transmittance *= exp(-opticalDepth);
}

void integrateScattering(sampler2D transmittanceLut, sampler2D multiscatterLut, IN(AtmosphereParams) p,
                         vec3 originM, vec3 dirEnu, float tMaxM, int steps, vec3 sunDirEnu, vec3 sunIrradiance,
                         vec3 moonDirEnu, vec3 moonIrradiance, OUT(vec3) inscatter, OUT(vec3) transmittance)
{
    inscatter = vec3(0.0f);
    transmittance = vec3(1.0f);
    float tStart;
    float tEnd;
    bool hitsGround;
    if (!clipRayToAtmosphere(p, originM, dirEnu, tStart, tEnd, hitsGround))
        return;
    tEnd = min(tEnd, tMaxM);
    if (tEnd <= tStart)
        return;
    float segment = tEnd - tStart;
    ViewPhases ph = viewPhases(p, dirEnu, sunDirEnu, moonDirEnu);
    float tPrev = tStart;
    for (int i = 1; i <= steps; ++i)
    {
        float s = float(i) / float(steps);
        float t = tStart + segment * s * s;
        float dt = t - tPrev;
        vec3 pos = originM + (0.5f * (t + tPrev)) * dirEnu;
        tPrev = t;
        scatteringStep(transmittanceLut, multiscatterLut, p, pos, dt, ph, sunDirEnu, sunIrradiance, moonDirEnu,
                       moonIrradiance, inscatter, transmittance);
    }
}

// One texel of the multiple-scattering LUT (Hillaire 2020 §5.5): second-order light L2 and the transfer
// f_ms gathered over MULTISCATTER_SQRT_DIRECTIONS^2 directions with an isotropic phase, including the
// ground's Lambertian bounce, then Psi_ms = L2 / (1 - f_ms) for unit light irradiance.
vec3 computeMultiscatterTexel(sampler2D transmittanceLut, IN(AtmosphereParams) p, vec2 uv)
{
    float r;
    float muS;
    multiscatterLutRMuS(p, uv, r, muS);
    vec3 originM = vec3(0.0f, 0.0f, r);
    vec3 sunDir = vec3(0.0f, sqrt(max(1.0f - muS * muS, 0.0f)), muS);
    vec3 albedo = atmosphereRgb(p.groundAlbedo);
    float isotropic = phaseIsotropic();
    vec3 secondOrder = vec3(0.0f);
    vec3 transfer = vec3(0.0f);
    int n = MULTISCATTER_SQRT_DIRECTIONS;
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            // Stratified uniform directions over the sphere: cos(zenith) uniform in [-1, 1].
            float cosZenith = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
            float azimuth = 2.0f * SKY_PI * (float(j) + 0.5f) / float(n);
            float sinZenith = sqrt(max(1.0f - cosZenith * cosZenith, 0.0f));
            vec3 dir = vec3(sinZenith * cos(azimuth), sinZenith * sin(azimuth), cosZenith);

            bool hitsGround = rayIntersectsGround(p, r, cosZenith);
            float tEnd = distanceToAtmosphereExit(p, r, cosZenith);
            vec3 lum = vec3(0.0f);
            vec3 lumTransfer = vec3(0.0f);
            vec3 transmittance = vec3(1.0f);
            float tPrev = 0.0f;
            for (int k = 1; k <= ATMOSPHERE_MULTISCATTER_STEPS; ++k)
            {
                float s = float(k) / float(ATMOSPHERE_MULTISCATTER_STEPS);
                float t = tEnd * s * s;
                float dt = t - tPrev;
                vec3 pos = originM + (0.5f * (t + tPrev)) * dir;
                tPrev = t;
                float rp = length(pos);
                float altitude = rp - p.radii.x;
                float muSp = dot(pos, sunDir) / rp;
                vec3 scattering = rayleighScatteringAt(p, altitude) + mieScatteringAt(p, altitude);
                vec3 opticalDepth = extinctionAt(p, altitude) * dt;
                vec3 weight = transmittance * dt * atmosphereOneMinusExpOverX(opticalDepth);
                vec3 sunLight = transmittanceToLight(transmittanceLut, p, rp, muSp, p.radii.z);
                lum += weight * scattering * sunLight * isotropic;
                lumTransfer += weight * scattering;
                transmittance *= exp(-opticalDepth);
            }
            if (hitsGround)
            {
                vec3 ground = originM + tEnd * dir;
                float muGround = clamp(dot(ground, sunDir) / p.radii.x, -1.0f, 1.0f);
                vec3 sunLight = transmittanceToLight(transmittanceLut, p, p.radii.x, muGround, p.radii.z);
                lum += transmittance * sunLight * max(muGround, 0.0f) * albedo / SKY_PI;
            }
            secondOrder += lum;
            transfer += lumTransfer;
        }
    }
    // Uniform sphere sampling with the isotropic phase: the integral over directions times 1/(4 pi) is
    // the plain mean over the samples.
    float invCount = 1.0f / float(n * n);
    secondOrder *= invCount;
    transfer *= invCount * isotropic * 4.0f * SKY_PI;
    return secondOrder / max(vec3(1.0f) - transfer, vec3(1e-3f));
}

// Number of sky-view steps for a ray segment: Hillaire's 30 to 60, growing with the length up to 150 km.
int skyViewStepCount(float lengthM)
{
    float x = clamp(lengthM / 150000.0f, 0.0f, 1.0f);
    return int(mix(float(ATMOSPHERE_SKY_VIEW_MIN_STEPS), float(ATMOSPHERE_SKY_VIEW_MAX_STEPS), x));
}

// Sky radiance (everything but the sun and moon disks) seen from camRM along dirEnu: what one texel of
// the sky-view LUT holds. Rays that hit the earth carry the in-scattered light up to the ground and,
// with includeGround, the lit ground (Lambertian albedo, direct light only) attenuated by the air.
vec3 computeSkyRadiance(sampler2D transmittanceLut, sampler2D multiscatterLut, IN(AtmosphereParams) p, float camRM,
                        vec3 dirEnu, vec3 sunDirEnu, vec3 sunIrradiance, vec3 moonDirEnu, vec3 moonIrradiance,
                        bool includeGround)
{
    vec3 originM = vec3(0.0f, 0.0f, camRM);
    float tStart;
    float tEnd;
    bool hitsGround;
    if (!clipRayToAtmosphere(p, originM, dirEnu, tStart, tEnd, hitsGround))
        return vec3(0.0f);
    vec3 inscatter;
    vec3 transmittance;
    integrateScattering(transmittanceLut, multiscatterLut, p, originM, dirEnu, tEnd, skyViewStepCount(tEnd - tStart),
                        sunDirEnu, sunIrradiance, moonDirEnu, moonIrradiance, inscatter, transmittance);
    if (includeGround && hitsGround)
    {
        vec3 up = normalize(originM + tEnd * dirEnu);
        float muSun = dot(up, sunDirEnu);
        float muMoon = dot(up, moonDirEnu);
        vec3 irradiance =
            sunIrradiance * transmittanceToLight(transmittanceLut, p, p.radii.x, muSun, p.radii.z) * max(muSun, 0.0f) +
            moonIrradiance * transmittanceToLight(transmittanceLut, p, p.radii.x, muMoon, p.radii.w) *
                max(muMoon, 0.0f);
        inscatter += transmittance * irradiance * atmosphereRgb(p.groundAlbedo) / SKY_PI;
    }
    return inscatter;
}

// The sky-view LUT's value for a view direction. camRM must be the camera distance the LUT was computed
// for (the horizon row depends on it). Below the horizon the LUT holds the air between the eye and the
// ground (plus the ground itself when the pass ran with SKY_VIEW_FLAG_GROUND); the horizon is a
// discontinuity that bilinear filtering softens over about one row (< 0.01 degree of zenith angle).
// The LUT sampler must use REPEAT in u (azimuth wraps at north). sampleSkyViewAt takes the direction's
// zenith angle, acos(viewDirEnu.z), and enuAzimuth(viewDirEnu) for callers that need them again.
vec3 sampleSkyViewAt(sampler2D skyViewLut, IN(AtmosphereParams) p, float camRM, float viewZenithRad, float azimuthRad)
{
    return atmosphereRgb(texture(skyViewLut, skyViewLutUv(p, camRM, viewZenithRad, azimuthRad)));
}

vec3 sampleSkyView(sampler2D skyViewLut, IN(AtmosphereParams) p, vec3 viewDirEnu, float camRM)
{
    float zenith = acos(clamp(viewDirEnu.z, -1.0f, 1.0f));
    return sampleSkyViewAt(skyViewLut, p, camRM, zenith, enuAzimuth(viewDirEnu));
}

// Radiance of the sun's disk along viewDirEnu before the air in front of it: a linearly limb-darkened
// disk I(m) = 1 - u (1 - m), u = 0.6 (the classic visible-band solar value, e.g. Allen's Astrophysical
// Quantities), normalised so that the disk integrates to sunIrradiance. Zero off the disk or when the
// ray hits the ground. sunDiskRadiance multiplies in the transmittance from the eye.
vec3 sunDiskEmission(IN(AtmosphereParams) p, vec3 viewDirEnu, float camRM, vec3 sunDirEnu, vec3 sunIrradiance)
{
    float angularRadius = p.radii.z;
    float cosAngle = clamp(dot(viewDirEnu, sunDirEnu), -1.0f, 1.0f);
    // Nearly every pixel is far from the disk: reject it on the cosine alone, before the cross product
    // and the atan. Twice the radius leaves a wide margin (cos(2r) = 1 - 4e-5 at the sun's 0.27 degrees,
    // float resolves 6e-8 there), so the pixels near the edge still take the exact angle below.
    if (cosAngle < cos(2.0f * angularRadius))
        return vec3(0.0f);
    float sinAngle = length(cross(viewDirEnu, sunDirEnu));
    float angle = atan(sinAngle, cosAngle);
    if (angle >= angularRadius || rayIntersectsGround(p, camRM, viewDirEnu.z))
        return vec3(0.0f);
    float x = angle / angularRadius;
    float m = sqrt(max(1.0f - x * x, 0.0f));
    float u = 0.6f;
    float limb = (1.0f - u * (1.0f - m)) / (1.0f - u / 3.0f);
    return sunIrradiance * limb / (SKY_PI * angularRadius * angularRadius);
}

// The sun's disk seen from the eye: sunDiskEmission times the transmittance from the eye.
vec3 sunDiskRadiance(sampler2D transmittanceLut, IN(AtmosphereParams) p, vec3 viewDirEnu, float camRM, vec3 sunDirEnu,
                     vec3 sunIrradiance)
{
    vec3 emission = sunDiskEmission(p, viewDirEnu, camRM, sunDirEnu, sunIrradiance);
    if (emission == vec3(0.0f))
        return vec3(0.0f);
    return emission * sampleTransmittance(transmittanceLut, p, camRM, viewDirEnu.z);
}

// Radiance of the moon's disk before the air in front of it: its lit part (where the sun shines on the
// lunar sphere) is uniformly bright (the full moon is nearly flat, Lommel-Seeliger), normalised so that
// the lit part integrates to moonIrradiance (phase already applied by the caller). Zero off the lit
// disk or when the ray hits the ground.
vec3 moonDiskEmission(IN(AtmosphereParams) p, vec3 viewDirEnu, float camRM, vec3 moonDirEnu, vec3 sunDirEnu,
                      vec3 moonIrradiance)
{
    float angularRadius = p.radii.w;
    float cosAngle = dot(viewDirEnu, moonDirEnu);
    vec3 offset = (viewDirEnu - cosAngle * moonDirEnu) / angularRadius;  // position on the disk, moon radii
    float rho2 = dot(offset, offset);
    if (cosAngle <= 0.0f || rho2 >= 1.0f || rayIntersectsGround(p, camRM, viewDirEnu.z))
        return vec3(0.0f);
    vec3 normal = offset - moonDirEnu * sqrt(1.0f - rho2);  // lunar surface normal, facing the eye
    if (dot(normal, sunDirEnu) <= 0.0f)
        return vec3(0.0f);
    float litFraction = max(0.5f * (1.0f - dot(sunDirEnu, moonDirEnu)), 1e-3f);
    return moonIrradiance / (SKY_PI * angularRadius * angularRadius * litFraction);
}

// The moon's disk seen from the eye: moonDiskEmission times the transmittance from the eye.
vec3 moonDiskRadiance(sampler2D transmittanceLut, IN(AtmosphereParams) p, vec3 viewDirEnu, float camRM,
                      vec3 moonDirEnu, vec3 sunDirEnu, vec3 moonIrradiance)
{
    vec3 emission = moonDiskEmission(p, viewDirEnu, camRM, moonDirEnu, sunDirEnu, moonIrradiance);
    if (emission == vec3(0.0f))
        return vec3(0.0f);
    return emission * sampleTransmittance(transmittanceLut, p, camRM, viewDirEnu.z);
}
