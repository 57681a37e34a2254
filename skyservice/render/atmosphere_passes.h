// SPDX-License-Identifier: MIT
// Host side of the atmosphere: the LUT images and passes (AtmospherePass), and the CPU estimate of the
// light that reaches the clouds (ambient sky, ground irradiance, exposure).
#pragma once

#include "shaders/shared/atmosphere_params.h"
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/sky/atmosphere_reference.h"
#include "skyservice/vk/programs.h"

namespace sky
{

/// The atmosphere's LUTs, the programs that build them, and what they were last built for: the
/// transmittance and multiple-scattering LUTs depend on the ground radius alone, the sky-view and
/// aerial-perspective LUTs on the frame's sun, moon and eye altitude (kept while those are bit for bit
/// the last frame's).
struct AtmospherePass
{
    Program transmittanceProgram, multiscatterProgram, skyViewProgram, aerialPerspectiveProgram;
    Image transmittanceLut, multiscatterLut, skyViewLut;
    Image aerialInscatterLut, aerialTransmittanceLut;  ///< 3D, AERIAL_LUT_* (atmosphere_params.h)
    double radiusM = 0;  ///< bottom radius the transmittance/multiscatter LUTs were built for (0: none)
    /// The inputs the sky-view and aerial LUTs were last built from (recordAtmosphere reuses them when equal).
    SkyViewPushConstants skyViewPush{};
    AtmosphereParams skyViewAtmosphere{};
    bool skyViewInputsValid = false;
    AtmosphereReference cpu;  ///< CPU copy of the atmosphere LUTs, for the lighting estimate
    double cpuRadiusM = -1;   ///< ground radius `cpu` was built for
};

struct LightingEstimate
{
    glm::dvec3 sunIrradiance{1.0};        ///< top-of-atmosphere solar irradiance (renderer units)
    glm::dvec3 ambientSkyRadiance{0.0};   ///< mean sky radiance over the upper hemisphere at cloud level
    glm::dvec3 groundIrradiance{0.0};     ///< sun + sky irradiance on the ground
    double groundAlbedo = 0.3;
    double exposure = 1.0;                ///< multiplier before tone mapping
};

/// Loads the LUT programs and creates the LUT images (layout GENERAL).
SkyStatus createAtmospherePass(const Context& ctx, MemoryTracker& memory, AtmospherePass& pass);
void destroyAtmospherePass(const Context& ctx, MemoryTracker& memory, AtmospherePass& pass);
/// Forgets what the LUTs hold: the next frame builds them all (after a failed frame, whose LUT passes
/// may never have run).
void forgetAtmosphereLuts(AtmospherePass& pass);

/// CPU estimate of the lighting for this frame (double precision, a few hundred atmosphere samples).
LightingEstimate estimateLighting(AtmospherePass& pass, const CameraFrame& camera, const SunMoon& sunMoon,
                                  const WindowSummary& summary);

/// Writes the frame's atmosphere uniforms (f.atmosphereUniforms) and records the transmittance and
/// multiple-scattering LUTs (when the earth radius, haze or fog changed) and the sky-view and
/// aerial-perspective LUTs for this frame (when their inputs changed).
void recordAtmosphere(const PassFrame& f, AtmospherePass& pass, const CameraFrame& camera, const SunMoon& sunMoon,
                      const FrameInputs& in);

}  // namespace sky
