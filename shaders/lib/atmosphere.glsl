// SPDX-License-Identifier: MIT
// Atmosphere math without textures (CPU-tested, docs/style.md §8): ray distances to the atmosphere and ground
// spheres, density profiles, transmittance by quadrature, LUT parameterisations and phase functions.
// Sources: Bruneton 2017 "Precomputed Atmospheric Scattering: a New Implementation" (functions.glsl:
// distances, transmittance LUT mapping, Cornette-Shanks, sun visibility), Hillaire 2020 "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique" (multiple-scattering and sky-view LUTs).
// Requires shaders/shared/atmosphere_params.h. A radius r is the distance from the earth centre (m),
// mu the cosine of the angle between a ray and the local zenith at its origin.
//
// Float precision: r^2 is ~4e13 at the earth's radius, where float32 resolves ~2.4e6 m^2, so every
// difference of squares is written (a - b)(a + b): a - b is exact for a and b within a factor of 2
// (Sterbenz), and roots are taken in the form that does not cancel (Numerical Recipes 5.6).

#ifndef SKY_PI
#define SKY_PI 3.14159265358979f
#endif

// a^2 - b^2 without cancellation.
float atmosphereDiffOfSquares(float a, float b)
{
    return (a - b) * (a + b);
}

// Distance from r along mu to the top atmosphere boundary (the far root). r may lie above the top, in
// which case this is the exit distance of a ray that enters it (or 0 when it misses).
float distanceToTopBoundary(IN(AtmosphereParams) p, float r, float mu)
{
    SKY_ASSERT(r > 0.0f);
    float c = atmosphereDiffOfSquares(p.radii.y, r);  // top^2 - r^2
    float b = r * mu;
    float disc = max(b * b + c, 0.0f);
    float s = sqrt(disc);
    // Far root t = -b + s; when b > 0 it cancels, so use t = c / (b + s) there.
    float t = b > 0.0f ? c / (b + s) : s - b;
    return max(t, 0.0f);
}

// True when the ray from r along mu hits the ground sphere.
bool rayIntersectsGround(IN(AtmosphereParams) p, float r, float mu)
{
    float c = atmosphereDiffOfSquares(r, p.radii.x);  // r^2 - R^2
    float b = r * mu;
    return mu < 0.0f && b * b - c >= 0.0f;
}

// Distance from r along mu to the ground (the near root); meaningful when rayIntersectsGround.
float distanceToBottomBoundary(IN(AtmosphereParams) p, float r, float mu)
{
    float c = max(atmosphereDiffOfSquares(r, p.radii.x), 0.0f);
    float b = r * mu;
    float s = sqrt(max(b * b - c, 0.0f));
    // Near root t = -b - s cancels when |b| ~ s (steep rays close to the ground): t = c / (s - b).
    float denom = s - b;
    return denom > 0.0f ? c / denom : 0.0f;
}

// Distance to where the ray leaves the atmosphere: the ground if it hits it, otherwise the top.
float distanceToAtmosphereExit(IN(AtmosphereParams) p, float r, float mu)
{
    return rayIntersectsGround(p, r, mu) ? distanceToBottomBoundary(p, r, mu) : distanceToTopBoundary(p, r, mu);
}

// Cosine of the zenith angle of the horizon seen from r (<= 0).
float horizonMu(IN(AtmosphereParams) p, float r)
{
    return -sqrt(max(atmosphereDiffOfSquares(r, p.radii.x), 0.0f)) / r;
}

// Altitude above the ground sphere of the point at distance t along the ray from r along mu, computed
// as (r_t^2 - R^2) / (r_t + R) with r_t^2 - R^2 = (r^2 - R^2) + t (t + 2 r mu): no cancellation.
float altitudeAlongRay(IN(AtmosphereParams) p, float r, float mu, float t)
{
    float bottom = p.radii.x;
    float r2MinusR2 = atmosphereDiffOfSquares(r, bottom) + t * (t + 2.0f * r * mu);
    float rt = sqrt(max(r * r + t * (t + 2.0f * r * mu), 0.0f));
    return max(r2MinusR2 / (rt + bottom), 0.0f);
}

// Densities relative to the bottom value (Rayleigh, Mie: exponential; ozone: tent, Bruneton's demo).
float rayleighDensity(IN(AtmosphereParams) p, float altitudeM)
{
    return exp(-max(altitudeM, 0.0f) / p.rayleighScattering.w);
}

float mieDensity(IN(AtmosphereParams) p, float altitudeM)
{
    return exp(-max(altitudeM, 0.0f) / p.mieScattering.w);
}

float ozoneDensity(IN(AtmosphereParams) p, float altitudeM)
{
    return max(0.0f, 1.0f - abs(altitudeM - p.ozoneLayer.x) / p.ozoneLayer.y);
}

// Ground fog (groundFog: a band of uniform extinction, none when z is 0): its extinction (1/m) at an
// altitude. The band's edges ramp over a tenth of its thickness (at most 20 m): a step would alias
// between the LUTs' altitude rows.
float groundFogExtinction(IN(AtmosphereParams) p, float altitudeM)
{
    if (p.groundFog.z <= 0.0f)
        return 0.0f;
    float edge = clamp(0.1f * (p.groundFog.y - p.groundFog.x), 1.0f, 20.0f);
    return p.groundFog.z * smoothstep(p.groundFog.x - edge, p.groundFog.x, altitudeM) *
           (1.0f - smoothstep(p.groundFog.y, p.groundFog.y + edge, altitudeM));
}

// Extinction coefficient (1/m) at an altitude.
vec3 extinctionAt(IN(AtmosphereParams) p, float altitudeM)
{
    vec3 rayleigh = vec3(p.rayleighScattering.x, p.rayleighScattering.y, p.rayleighScattering.z);
    vec3 mie = vec3(p.mieExtinction.x, p.mieExtinction.y, p.mieExtinction.z);
    vec3 ozone = vec3(p.ozoneAbsorption.x, p.ozoneAbsorption.y, p.ozoneAbsorption.z);
    return rayleigh * rayleighDensity(p, altitudeM) + mie * mieDensity(p, altitudeM) +
           ozone * ozoneDensity(p, altitudeM) + vec3(groundFogExtinction(p, altitudeM));
}

// Rayleigh and Mie scattering coefficients (1/m) at an altitude.
vec3 rayleighScatteringAt(IN(AtmosphereParams) p, float altitudeM)
{
    return vec3(p.rayleighScattering.x, p.rayleighScattering.y, p.rayleighScattering.z) *
           rayleighDensity(p, altitudeM);
}

// The fog's droplets scatter what they take (albedo 1), with the aerosol's forward-peaked phase function.
vec3 mieScatteringAt(IN(AtmosphereParams) p, float altitudeM)
{
    return vec3(p.mieScattering.x, p.mieScattering.y, p.mieScattering.z) * mieDensity(p, altitudeM) +
           vec3(groundFogExtinction(p, altitudeM));
}

// Optical depth (dimensionless, per channel) from r along mu over [0, length], trapezoidal rule on a
// quadratic grid t = length * (i / steps)^2: densities fall off fastest near the start of upward and
// grazing rays, so the samples are packed there.
vec3 opticalDepthAlongRay(IN(AtmosphereParams) p, float r, float mu, float lengthM, int steps)
{
    vec3 sum = vec3(0.0f);
    float tPrev = 0.0f;
    vec3 ePrev = extinctionAt(p, altitudeAlongRay(p, r, mu, 0.0f));
    for (int i = 1; i <= steps; ++i)
    {
        float s = float(i) / float(steps);
        float t = lengthM * s * s;
        vec3 e = extinctionAt(p, altitudeAlongRay(p, r, mu, t));
        sum += 0.5f * (e + ePrev) * (t - tPrev);
        ePrev = e;
        tPrev = t;
    }
    return sum;
}

// Transmittance from r along mu to the top atmosphere boundary (the ray must not hit the ground).
vec3 transmittanceToTop(IN(AtmosphereParams) p, float r, float mu, int steps)
{
    return exp(-opticalDepthAlongRay(p, r, mu, distanceToTopBoundary(p, r, mu), steps));
}

// Fraction of a light disk of the given angular radius above the horizon seen from r, where mu is the
// cosine of the light's zenith angle: a smoothstep across the disk (Bruneton's GetTransmittanceToSun).
float lightVisibility(IN(AtmosphereParams) p, float r, float mu, float angularRadiusRad)
{
    float sinHorizon = p.radii.x / r;
    float cosHorizon = horizonMu(p, r);
    float halfWidth = sinHorizon * angularRadiusRad;
    return smoothstep(-halfWidth, halfWidth, mu - cosHorizon);
}

// --- LUT parameterisations -------------------------------------------------------------------------
// Texel centres sit at (i + 0.5) / size: these map [0,1] onto the first and last centre so that the
// extreme values are sampled exactly (Bruneton's GetTextureCoordFromUnitRange).
float unitRangeToTexCoord(float x, float size)
{
    return 0.5f / size + x * (1.0f - 1.0f / size);
}

float texCoordToUnitRange(float u, float size)
{
    return (u - 0.5f / size) / (1.0f - 1.0f / size);
}

// Transmittance LUT (Bruneton 2017 §4.1): x from the distance to the top boundary between its minimum
// and maximum for that r, y from rho = sqrt(r^2 - R^2) / H, H = sqrt(top^2 - R^2).
vec2 transmittanceLutUv(IN(AtmosphereParams) p, float r, float mu)
{
    float bottom = p.radii.x;
    float top = p.radii.y;
    float h = sqrt(atmosphereDiffOfSquares(top, bottom));
    float rho = sqrt(max(atmosphereDiffOfSquares(r, bottom), 0.0f));
    float d = distanceToTopBoundary(p, r, mu);
    float dMin = top - r;
    float dMax = rho + h;
    float xMu = dMax > dMin ? (d - dMin) / (dMax - dMin) : 0.0f;
    float xR = rho / h;
    return vec2(unitRangeToTexCoord(clamp(xMu, 0.0f, 1.0f), float(TRANSMITTANCE_LUT_WIDTH)),
                unitRangeToTexCoord(clamp(xR, 0.0f, 1.0f), float(TRANSMITTANCE_LUT_HEIGHT)));
}

void transmittanceLutRMu(IN(AtmosphereParams) p, vec2 uv, OUT(float) r, OUT(float) mu)
{
    float bottom = p.radii.x;
    float top = p.radii.y;
    float xMu = texCoordToUnitRange(uv.x, float(TRANSMITTANCE_LUT_WIDTH));
    float xR = texCoordToUnitRange(uv.y, float(TRANSMITTANCE_LUT_HEIGHT));
    float h = sqrt(atmosphereDiffOfSquares(top, bottom));
    float rho = h * xR;
    r = sqrt(rho * rho + bottom * bottom);
    float dMin = top - r;
    float dMax = rho + h;
    float d = dMin + xMu * (dMax - dMin);
    // Law of cosines: top^2 = r^2 + d^2 + 2 r d mu, and top^2 - r^2 = H^2 - rho^2.
    mu = d == 0.0f ? 1.0f : (atmosphereDiffOfSquares(h, rho) - d * d) / (2.0f * r * d);
    mu = clamp(mu, -1.0f, 1.0f);
}

// Multiple-scattering LUT (Hillaire 2020 §5.5): x = sun zenith cosine in [-1, 1], y = altitude fraction.
vec2 multiscatterLutUv(IN(AtmosphereParams) p, float r, float muS)
{
    float altitudeFraction = (r - p.radii.x) / (p.radii.y - p.radii.x);
    return vec2(unitRangeToTexCoord(clamp(0.5f + 0.5f * muS, 0.0f, 1.0f), float(MULTISCATTER_LUT_SIZE)),
                unitRangeToTexCoord(clamp(altitudeFraction, 0.0f, 1.0f), float(MULTISCATTER_LUT_SIZE)));
}

void multiscatterLutRMuS(IN(AtmosphereParams) p, vec2 uv, OUT(float) r, OUT(float) muS)
{
    float x = clamp(texCoordToUnitRange(uv.x, float(MULTISCATTER_LUT_SIZE)), 0.0f, 1.0f);
    float y = clamp(texCoordToUnitRange(uv.y, float(MULTISCATTER_LUT_SIZE)), 0.0f, 1.0f);
    muS = 2.0f * x - 1.0f;
    // Keep r strictly inside the shell so that rays from the top texel row still see some atmosphere.
    r = p.radii.x + clamp(y, 0.0f, 1.0f) * (p.radii.y - p.radii.x);
    r = clamp(r, p.radii.x + 1.0f, p.radii.y - 1.0f);
}

// Sky-view LUT (Hillaire 2020 §5.3, absolute azimuth): v in [0, 0.5) covers zenith to horizon with the
// zenith angle growing as 1 - (1 - 2v)^2, v in [0.5, 1] covers horizon to nadir as (2v - 1)^2, so rows
// crowd at the horizon on both sides. u = azimuth / 2 pi, clockwise from north (east = 0.25), linear and
// periodic: the LUT is written at texel centres and sampled with REPEAT in u.
// zenithHorizonRad is the zenith angle of the horizon seen from r (>= pi / 2).
float skyViewHorizonZenith(IN(AtmosphereParams) p, float r)
{
    float cosBeta = sqrt(max(atmosphereDiffOfSquares(r, p.radii.x), 0.0f)) / r;
    return SKY_PI - acos(clamp(cosBeta, 0.0f, 1.0f));
}

// The mapping's v in [0, 1] (before the texel-centre mapping) of a view zenith angle seen from r, and back.
float skyViewUnitV(IN(AtmosphereParams) p, float r, float viewZenithRad)
{
    float zenithHorizon = skyViewHorizonZenith(p, r);
    float beta = SKY_PI - zenithHorizon;
    if (viewZenithRad < zenithHorizon)
    {
        float coord = clamp(viewZenithRad / zenithHorizon, 0.0f, 1.0f);
        return 0.5f * (1.0f - sqrt(1.0f - coord));
    }
    float coord = beta > 0.0f ? clamp((viewZenithRad - zenithHorizon) / beta, 0.0f, 1.0f) : 0.0f;
    return 0.5f + 0.5f * sqrt(coord);
}

float skyViewZenithOfUnitV(IN(AtmosphereParams) p, float r, float v)
{
    float zenithHorizon = skyViewHorizonZenith(p, r);
    float beta = SKY_PI - zenithHorizon;
    if (v < 0.5f)
    {
        float coord = 1.0f - 2.0f * v;
        return zenithHorizon * (1.0f - coord * coord);
    }
    float coord = 2.0f * v - 1.0f;
    return zenithHorizon + beta * coord * coord;
}

vec2 skyViewLutUv(IN(AtmosphereParams) p, float r, float viewZenithRad, float azimuthRad)
{
    float u = fract(azimuthRad / (2.0f * SKY_PI));
    return vec2(u, unitRangeToTexCoord(skyViewUnitV(p, r, viewZenithRad), float(SKY_VIEW_LUT_HEIGHT)));
}

void skyViewLutDirection(IN(AtmosphereParams) p, float r, vec2 uv, OUT(float) viewZenithRad,
                         OUT(float) azimuthRad)
{
    float v = clamp(texCoordToUnitRange(uv.y, float(SKY_VIEW_LUT_HEIGHT)), 0.0f, 1.0f);
    viewZenithRad = skyViewZenithOfUnitV(p, r, v);
    azimuthRad = uv.x * 2.0f * SKY_PI;
}

// Aerial-perspective LUT (atmosphere_params.h): slice k holds the air between the eye and the distance
// d_k = AERIAL_LUT_MAX_DISTANCE_M ((k + 1) / AERIAL_LUT_SLICES)^2 (slices crowd near the eye, where
// haze changes fastest with distance). aerialSliceOfDistance is the continuous slice index of a
// distance: -1 at the eye, k at d_k.
float aerialSliceDistanceM(float k)
{
    float s = (k + 1.0f) / float(AERIAL_LUT_SLICES);
    return AERIAL_LUT_MAX_DISTANCE_M * s * s;
}

float aerialSliceOfDistance(float distanceM)
{
    return sqrt(max(distanceM, 0.0f) / AERIAL_LUT_MAX_DISTANCE_M) * float(AERIAL_LUT_SLICES) - 1.0f;
}

// Unit ENU vector from a zenith angle and an azimuth clockwise from north.
vec3 enuDirectionFromAngles(float zenithRad, float azimuthRad)
{
    float s = sin(zenithRad);
    return vec3(s * sin(azimuthRad), s * cos(azimuthRad), cos(zenithRad));
}

// Azimuth clockwise from north in [0, 2 pi) of an ENU direction (0 for the zenith).
float enuAzimuth(vec3 dirEnu)
{
    // GLSL leaves atan(0, 0) undefined (NaN on some drivers): the straight-up pixel needs a value.
    if (abs(dirEnu.x) + abs(dirEnu.y) < 1e-20f)
        return 0.0f;
    float a = atan(dirEnu.x, dirEnu.y);
    return a < 0.0f ? a + 2.0f * SKY_PI : a;
}

// --- Phase functions (normalised over the sphere; nu = cosine of the scattering angle) --------------
float rayleighPhase(float nu)
{
    return 3.0f / (16.0f * SKY_PI) * (1.0f + nu * nu);
}

// Cornette & Shanks 1992, as used by Bruneton 2017 for aerosols.
float miePhaseCornetteShanks(float g, float nu)
{
    float g2 = g * g;
    float k = 3.0f / (8.0f * SKY_PI) * (1.0f - g2) / (2.0f + g2);
    float denom = max(1.0f + g2 - 2.0f * g * nu, 1e-6f);
    return k * (1.0f + nu * nu) / (denom * sqrt(denom));
}
