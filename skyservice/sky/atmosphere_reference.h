// SPDX-License-Identifier: MIT
// CPU reference of the atmosphere passes, for tests and for comparing GPU output pixel by pixel.
//
// The LUTs and the sky-view texels are computed by the same shaders/lib/*.glsl code as the GPU passes,
// compiled as C++ with a bilinear sampler2D emulation (Bruneton's approach): differences against the
// GPU are then float rounding and the rgba16f storage only. referenceSkyRadiance() is independent of
// the LUT parameterisations: single scattering by direct quadrature (transmittance to the light
// integrated for every sample) plus the multiple-scattering term from the CPU LUT.
#pragma once

#include "shaders/shared/atmosphere_params.h"

#include <vector>

namespace sky
{

/// A view of a CPU image sampled like a Vulkan sampler with linear filtering at texel centres
/// (addressing: clamp to edge, or repeat in u). Cheap to copy; the texels belong to a CpuTexture2D.
struct CpuSampler2D
{
    const glm::vec4* texels = nullptr;  ///< row-major, width * height
    int width = 0;
    int height = 0;
    bool repeatU = false;  ///< wrap u (the sky-view LUT's azimuth), clamp v

    /// Bilinear sample at normalised coordinates uv.
    glm::vec4 sample(glm::vec2 uv) const;
};

/// A CPU image (row-major RGBA float).
struct CpuTexture2D
{
    int width = 0;
    int height = 0;
    bool repeatU = false;
    std::vector<glm::vec4> texels;

    CpuSampler2D sampler() const { return {texels.data(), width, height, repeatU}; }
    const glm::vec4& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

/// The atmosphere with its two precomputed LUTs, as the GPU passes would produce them.
struct AtmosphereReference
{
    AtmosphereParams params{};
    CpuTexture2D transmittance;  ///< TRANSMITTANCE_LUT_WIDTH x TRANSMITTANCE_LUT_HEIGHT
    CpuTexture2D multiscatter;   ///< MULTISCATTER_LUT_SIZE^2
};

/// Builds the transmittance and multiple-scattering LUTs on the CPU (about 0.1 s).
AtmosphereReference createAtmosphereReference(const AtmosphereParams& params);

/// One sky-view LUT texel (x in [0, SKY_VIEW_LUT_WIDTH), y in [0, SKY_VIEW_LUT_HEIGHT)), as
/// sky_view_lut.comp.glsl computes it.
glm::vec3 skyViewTexel(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants, int x, int y);

/// The whole sky-view LUT (about 0.5 s on one core; REPEAT in u).
CpuTexture2D computeSkyViewLut(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants);

/// sampleSkyView() of shaders/lib/atmosphere_sampling.glsl on a CPU LUT.
glm::vec3 sampleSkyViewCpu(const AtmosphereReference& atmosphere, const CpuTexture2D& skyView, glm::vec3 viewDirEnu,
                           float camRM);

/// computeSkyRadiance() of atmosphere_sampling.glsl (what a sky-view texel holds) for any direction.
glm::vec3 skyRadianceLut(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants,
                         glm::vec3 viewDirEnu);

/**
 * Brute-force sky radiance (no sun or moon disk) seen from constants.sunDirection.w along viewDirEnu:
 * single scattering of both lights with the transmittance to the light integrated directly, plus the
 * multiple-scattering term from the CPU LUT, plus the lit ground with SKY_VIEW_FLAG_GROUND.
 *
 * @param[in] steps quadrature steps along the view ray (e.g. 400; 40 per light ray).
 **********************************************************************/
glm::vec3 referenceSkyRadiance(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants,
                               glm::vec3 viewDirEnu, int steps);

/// Aerial perspective between the eye at camPosM (from the earth centre, ENU axes) and a surface distanceM
/// along dirEnu, integrated directly (integrateScattering of atmosphere_sampling.glsl, ATMOSPHERE_AERIAL_STEPS
/// steps) on the CPU LUTs: seen = surface * transmittance + inscatter. The renderer reads the same from
/// the aerial-perspective LUT (aerialLutTexelCpu).
void aerialPerspectiveCpu(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants,
                          glm::vec3 camPosM, glm::vec3 dirEnu, float distanceM, glm::vec3& inscatter,
                          glm::vec3& transmittance);

/// What texel (x, y, slice) of the aerial-perspective LUT should hold (aerial_perspective_lut.comp.glsl):
/// the ray integral from the eye (constants.sunDirection.w from the centre) along the texel's direction
/// to its slice distance, with `steps` quadrature steps on the CPU LUTs.
void aerialLutTexelCpu(const AtmosphereReference& atmosphere, const SkyViewPushConstants& constants, int x, int y,
                       int slice, int steps, glm::vec3& inscatter, glm::vec3& transmittance);

/// Transmittance from rM along muSun to the top, looked up in the CPU LUT (sampleTransmittance()).
glm::vec3 sampleTransmittanceCpu(const AtmosphereReference& atmosphere, float rM, float muSun);

}  // namespace sky
