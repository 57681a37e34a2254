// SPDX-License-Identifier: MIT
#include "skyservice/sky/atmosphere.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

// Layout checks for the structs shared with GLSL (docs/style.md §7): std140/std430 match the C++ layout only
// while every member is a 16-byte vector.
static_assert(sizeof(AtmosphereParams) == 9 * 16, "AtmosphereParams must stay 9 vec4");
static_assert(offsetof(AtmosphereParams, radii) == 5 * 16, "AtmosphereParams.radii moved");
static_assert(offsetof(AtmosphereParams, solarIrradiance) == 7 * 16, "AtmosphereParams.solarIrradiance moved");
static_assert(sizeof(SkyViewPushConstants) == 5 * 16, "SkyViewPushConstants must stay 5 vec4");
static_assert(offsetof(SkyViewPushConstants, flags) == 4 * 16, "SkyViewPushConstants.flags moved");

namespace sky
{

AtmosphereParams makeEarthAtmosphere(double bottomRadiusM)
{
    AtmosphereParams p{};
    // Rayleigh: Bruneton 2017 demo, beta = 1.24062e-6 / lambda(um)^4 at 680, 550, 440 nm; the same
    // values are Hillaire 2020 Table 1. Scale height 8 km.
    p.rayleighScattering = vec4(5.802e-6f, 13.558e-6f, 33.1e-6f, 8000.0f);
    // Mie: Bruneton 2017 demo, Angstrom beta 5.328e-3 over a 1.2 km scale height gives an extinction
    // of 4.44e-6 /m, single-scattering albedo 0.9 gives the scattering; Cornette-Shanks g = 0.8.
    p.mieScattering = vec4(3.996e-6f, 3.996e-6f, 3.996e-6f, 1200.0f);
    p.mieExtinction = vec4(4.44e-6f, 4.44e-6f, 4.44e-6f, 0.8f);
    // Ozone: Hillaire 2020 Table 1 (from Bruneton's demo: 300 Dobson units, Serdyuchenko cross
    // sections), a tent peaking at 25 km, zero at 10 and 40 km.
    p.ozoneAbsorption = vec4(0.650e-6f, 1.881e-6f, 0.085e-6f, 0.0f);
    p.ozoneLayer = vec4(25000.0f, 15000.0f, 0.0f, 0.0f);
    // Sun angular radius 0.004675 rad (Bruneton 2017 demo); moon: mean radius over mean distance.
    p.radii = vec4(float(bottomRadiusM), float(bottomRadiusM + kAtmosphereThicknessM), 0.004675f,
                   float(moonAngularRadiusRad(384400e3)));
    // Ground albedo 0.1 (Bruneton 2017 demo).
    p.groundAlbedo = vec4(0.1f, 0.1f, 0.1f, 0.0f);
    // Solar spectral irradiance at 680, 550, 440 nm (W m^-2 nm^-1): Bruneton 2017 demo, from the
    // ASTM G-173 extraterrestrial spectrum.
    p.solarIrradiance = vec4(1.474f, 1.8504f, 1.91198f, 0.0f);
    return p;
}

void setHazeVisibility(AtmosphereParams& p, double visibilityM)
{
    // Beyond kVisibilityOpticalDepth / Rayleigh(550 nm) the air is clearer than clean air: no aerosol.
    const double rayleigh550 = double(p.rayleighScattering.y);
    const double extinction = std::max(kVisibilityOpticalDepth / visibilityM - rayleigh550, 0.0);
    const double albedo = double(p.mieScattering.x) / double(p.mieExtinction.x);
    const float e = float(extinction), s = float(extinction * albedo);
    p.mieExtinction = vec4(e, e, e, p.mieExtinction.w);
    p.mieScattering = vec4(s, s, s, p.mieScattering.w);
}

void setGroundFog(AtmosphereParams& p, double baseM, double topM, double visibilityM)
{
    if (!(visibilityM > 0.0) || !(topM > baseM))
    {
        p.groundFog = vec4(0.0f);
        return;
    }
    p.groundFog = vec4(float(baseM), float(topM), float(kVisibilityOpticalDepth / visibilityM), 0.0f);
}

double moonIrradianceRelativeToSun(double phaseAngleDeg)
{
    double i = std::fabs(phaseAngleDeg);
    double moonMagnitude = -12.73 + 0.026 * i + 4e-9 * i * i * i * i;
    const double sunMagnitude = -26.74;
    return std::pow(10.0, -0.4 * (moonMagnitude - sunMagnitude));
}

double moonAngularRadiusRad(double distanceM)
{
    return std::asin(kMoonRadiusM / distanceM);
}

}  // namespace sky
