// SPDX-License-Identifier: MIT
// The earth's atmosphere as the atmosphere passes see it (shaders/shared/atmosphere_params.h), and the
// brightness of the two lights that illuminate it.
#pragma once

#include "shaders/shared/atmosphere_params.h"

namespace sky
{

/// Height of the top of the atmosphere above the ground sphere (meters): Bruneton's and Hillaire's
/// models end where the air is too thin to matter; 100 km keeps the mesosphere's glow at sunset.
inline constexpr double kAtmosphereThicknessM = 100000.0;

/// Mean radius of the moon (meters), IAU WG on Cartographic Coordinates and Rotational Elements 2015.
inline constexpr double kMoonRadiusM = 1737400.0;

/**
 * The clear-sky earth atmosphere: Rayleigh, Mie and ozone coefficients of Bruneton 2017 / Hillaire
 * 2020 at 680, 550 and 440 nm, on a ground sphere of the given radius.
 *
 * @param[in] bottomRadiusM radius of the ground sphere (meters): the osculating radius at the eye,
 *   CameraFrame::localEarthRadiusM. The top is kAtmosphereThicknessM above it.
 * @return the parameters, ready to upload (std140). The transmittance and multiple-scattering LUTs
 *   depend on them: recompute both when the radius changes by more than about 1 km (they change by
 *   less than 0.1% per km).
 **********************************************************************/
AtmosphereParams makeEarthAtmosphere(double bottomRadiusM);

/// Optical depth at which a black object's contrast against the horizon sky has fallen to 5 % (ln 20):
/// the visibility of air of extinction e (1/m) is this / e (Koschmieder's law with the 5 % threshold of
/// the WMO's meteorological optical range, which reported visibilities are; Koschmieder's 2 % gives 3.912).
inline constexpr double kVisibilityOpticalDepth = 3.0;

/**
 * Sets the haze for a meteorological visibility near the ground: the aerosol (Mie) extinction at the
 * bottom becomes what, added to the Rayleigh extinction at 550 nm, makes kVisibilityOpticalDepth /
 * visibilityM, the same in the three channels (haze is nearly grey), with the model's single-scattering
 * albedo (0.9) and scale height (1.2 km): the haze thins with altitude as the boundary layer's aerosol
 * does. A visibility beyond what clean air's Rayleigh extinction allows (~220 km) leaves no aerosol; the
 * clear atmosphere's own aerosol is a visibility of ~170 km.
 *
 * @param[in,out] p an atmosphere from makeEarthAtmosphere.
 * @param[in] visibilityM > 0 (meters).
 **********************************************************************/
void setHazeVisibility(AtmosphereParams& p, double visibilityM);

/**
 * Adds ground fog: a band from baseM to topM (meters above the bottom of the atmosphere) whose own
 * extinction is kVisibilityOpticalDepth / visibilityM (the visibility inside it, on top of the haze), all
 * of it scattered, with the aerosol's phase function. The atmosphere is a sphere: the fog lies at that
 * height all around the earth, as CIGI's global ground fog does. No fog when visibilityM <= 0 or
 * topM <= baseM.
 **********************************************************************/
void setGroundFog(AtmosphereParams& p, double baseM, double topM, double visibilityM);

/**
 * The moon's irradiance at the top of the atmosphere relative to the sun's, from its phase angle.
 * Apparent magnitude of the moon m = -12.73 + 0.026 |i| + 4e-9 i^4 (Allen's Astrophysical
 * Quantities, i in degrees), of the sun -26.74; ratio = 10^(-0.4 (m - m_sun)).
 *
 * @param[in] phaseAngleDeg sun-moon-earth angle (degrees, [0, 180]; SunMoon::moonPhaseAngleDeg).
 * @return about 2.5e-6 at full moon, falling to ~1e-8 near new moon.
 **********************************************************************/
double moonIrradianceRelativeToSun(double phaseAngleDeg);

/// Angular radius (radians) of the moon seen from distanceM (meters) (0.0045 on average).
double moonAngularRadiusRad(double distanceM);

}  // namespace sky
