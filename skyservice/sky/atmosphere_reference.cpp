// SPDX-License-Identifier: MIT
#include "skyservice/sky/atmosphere_reference.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{
namespace glsl
{
using namespace glm;
using sampler2D = CpuSampler2D;
vec4 texture(const sampler2D& s, vec2 uv)
{
    return s.sample(uv);
}
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "shaders/lib/atmosphere.glsl"
#include "shaders/lib/phase.glsl"
#include "shaders/lib/atmosphere_sampling.glsl"
#pragma GCC diagnostic pop
}  // namespace glsl

glm::vec3 rgb(const glm::vec4& v)
{
    return glm::vec3(v.x, v.y, v.z);
}

CpuTexture2D makeTexture(int width, int height, bool repeatU)
{
    CpuTexture2D t;
    t.width = width;
    t.height = height;
    t.repeatU = repeatU;
    t.texels.assign(size_t(width) * size_t(height), glm::vec4(0.0f));
    return t;
}

glm::vec2 texelCentre(int x, int y, int width, int height)
{
    return glm::vec2((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
}

}  // namespace

glm::vec4 CpuSampler2D::sample(glm::vec2 uv) const
{
    float x = uv.x * float(width) - 0.5f;
    float y = uv.y * float(height) - 0.5f;
    float x0f = std::floor(x);
    float y0f = std::floor(y);
    float fx = x - x0f;
    float fy = y - y0f;
    auto column = [this](int i) {
        if (repeatU)
            return ((i % width) + width) % width;
        return std::clamp(i, 0, width - 1);
    };
    auto row = [this](int j) { return std::clamp(j, 0, height - 1); };
    int x0 = int(x0f);
    int y0 = int(y0f);
    auto fetch = [&](int i, int j) { return texels[size_t(row(j)) * size_t(width) + size_t(column(i))]; };
    glm::vec4 top = glm::mix(fetch(x0, y0), fetch(x0 + 1, y0), fx);
    glm::vec4 bottom = glm::mix(fetch(x0, y0 + 1), fetch(x0 + 1, y0 + 1), fx);
    return glm::mix(top, bottom, fy);
}

AtmosphereReference createAtmosphereReference(const AtmosphereParams& params)
{
    AtmosphereReference a;
    a.params = params;
    a.transmittance = makeTexture(TRANSMITTANCE_LUT_WIDTH, TRANSMITTANCE_LUT_HEIGHT, false);
    for (int y = 0; y < TRANSMITTANCE_LUT_HEIGHT; ++y)
        for (int x = 0; x < TRANSMITTANCE_LUT_WIDTH; ++x)
        {
            float r;
            float mu;
            glsl::transmittanceLutRMu(params, texelCentre(x, y, TRANSMITTANCE_LUT_WIDTH, TRANSMITTANCE_LUT_HEIGHT), r,
                                      mu);
            glm::vec3 t = glsl::transmittanceToTop(params, r, mu, ATMOSPHERE_TRANSMITTANCE_STEPS);
            a.transmittance.texels[size_t(y * TRANSMITTANCE_LUT_WIDTH + x)] = glm::vec4(t, 1.0f);
        }
    a.multiscatter = makeTexture(MULTISCATTER_LUT_SIZE, MULTISCATTER_LUT_SIZE, false);
    for (int y = 0; y < MULTISCATTER_LUT_SIZE; ++y)
        for (int x = 0; x < MULTISCATTER_LUT_SIZE; ++x)
        {
            glm::vec2 uv = texelCentre(x, y, MULTISCATTER_LUT_SIZE, MULTISCATTER_LUT_SIZE);
            glm::vec3 psi = glsl::computeMultiscatterTexel(a.transmittance.sampler(), params, uv);
            a.multiscatter.texels[size_t(y * MULTISCATTER_LUT_SIZE + x)] = glm::vec4(psi, 1.0f);
        }
    return a;
}

glm::vec3 skyRadianceLut(const AtmosphereReference& a, const SkyViewPushConstants& c, glm::vec3 viewDirEnu)
{
    return glsl::computeSkyRadiance(a.transmittance.sampler(), a.multiscatter.sampler(), a.params, c.sunDirection.w,
                                    viewDirEnu, rgb(c.sunDirection), rgb(c.sunIrradiance), rgb(c.moonDirection),
                                    rgb(c.moonIrradiance), (c.flags.x & SKY_VIEW_FLAG_GROUND) != 0u);
}

glm::vec3 skyViewTexel(const AtmosphereReference& a, const SkyViewPushConstants& c, int x, int y)
{
    float zenith;
    float azimuth;
    glsl::skyViewLutDirection(a.params, c.sunDirection.w, texelCentre(x, y, SKY_VIEW_LUT_WIDTH, SKY_VIEW_LUT_HEIGHT),
                              zenith, azimuth);
    return skyRadianceLut(a, c, glsl::enuDirectionFromAngles(zenith, azimuth));
}

CpuTexture2D computeSkyViewLut(const AtmosphereReference& a, const SkyViewPushConstants& c)
{
    CpuTexture2D lut = makeTexture(SKY_VIEW_LUT_WIDTH, SKY_VIEW_LUT_HEIGHT, true);
    for (int y = 0; y < SKY_VIEW_LUT_HEIGHT; ++y)
        for (int x = 0; x < SKY_VIEW_LUT_WIDTH; ++x)
            lut.texels[size_t(y * SKY_VIEW_LUT_WIDTH + x)] = glm::vec4(skyViewTexel(a, c, x, y), 1.0f);
    return lut;
}

glm::vec3 sampleSkyViewCpu(const AtmosphereReference& a, const CpuTexture2D& skyView, glm::vec3 viewDirEnu,
                           float camRM)
{
    return glsl::sampleSkyView(skyView.sampler(), a.params, viewDirEnu, camRM);
}

glm::vec3 referenceSkyRadiance(const AtmosphereReference& a, const SkyViewPushConstants& c, glm::vec3 viewDirEnu,
                               int steps)
{
    const AtmosphereParams& p = a.params;
    glm::vec3 origin(0.0f, 0.0f, c.sunDirection.w);
    float tStart;
    float tEnd;
    bool hitsGround;
    if (!glsl::clipRayToAtmosphere(p, origin, viewDirEnu, tStart, tEnd, hitsGround))
        return glm::vec3(0.0f);
    const glm::vec3 lightDir[2] = {rgb(c.sunDirection), rgb(c.moonDirection)};
    const glm::vec3 lightIrradiance[2] = {rgb(c.sunIrradiance), rgb(c.moonIrradiance)};
    const float lightRadius[2] = {p.radii.z, p.radii.w};
    const float g = p.mieExtinction.w;
    // Transmittance to a light by direct quadrature, not through the LUT's parameterisation.
    auto lightTransmittance = [&](float r, float mu, int light) {
        glm::vec3 depth = glsl::opticalDepthAlongRay(p, r, mu, glsl::distanceToTopBoundary(p, r, mu), 200);
        return glm::exp(-depth) * glsl::lightVisibility(p, r, mu, lightRadius[light]);
    };
    glm::dvec3 inscatter(0.0);
    glm::vec3 transmittance(1.0f);
    float dt = (tEnd - tStart) / float(steps);
    for (int i = 0; i < steps; ++i)
    {
        glm::vec3 pos = origin + (tStart + (float(i) + 0.5f) * dt) * viewDirEnu;
        float r = glm::length(pos);
        float altitude = r - p.radii.x;
        glm::vec3 rayleigh = glsl::rayleighScatteringAt(p, altitude);
        glm::vec3 mie = glsl::mieScatteringAt(p, altitude);
        glm::vec3 extinction = glsl::extinctionAt(p, altitude);
        glm::vec3 halfStep = glm::exp(-0.5f * dt * extinction);
        glm::vec3 source(0.0f);
        for (int light = 0; light < 2; ++light)
        {
            if (lightIrradiance[light] == glm::vec3(0.0f))
                continue;
            float mu = glm::dot(pos, lightDir[light]) / r;
            float nu = glm::dot(viewDirEnu, lightDir[light]);
            glm::vec3 single = lightTransmittance(r, mu, light) *
                               (rayleigh * glsl::rayleighPhase(nu) + mie * glsl::miePhaseCornetteShanks(g, nu));
            glm::vec3 multiple = (rayleigh + mie) * rgb(a.multiscatter.sampler().sample(glsl::multiscatterLutUv(p, r, mu)));
            source += lightIrradiance[light] * (single + multiple);
        }
        inscatter += glm::dvec3(transmittance * halfStep * source * dt);
        transmittance *= halfStep * halfStep;
    }
    if (hitsGround && (c.flags.x & SKY_VIEW_FLAG_GROUND) != 0u)
    {
        glm::vec3 up = glm::normalize(origin + tEnd * viewDirEnu);
        glm::vec3 irradiance(0.0f);
        for (int light = 0; light < 2; ++light)
        {
            float mu = glm::dot(up, lightDir[light]);
            irradiance += lightIrradiance[light] * lightTransmittance(p.radii.x, mu, light) * std::max(mu, 0.0f);
        }
        inscatter += glm::dvec3(transmittance * irradiance * rgb(p.groundAlbedo) / SKY_PI);
    }
    return glm::vec3(inscatter);
}

void aerialPerspectiveCpu(const AtmosphereReference& a, const SkyViewPushConstants& c, glm::vec3 camPosM,
                          glm::vec3 dirEnu, float distanceM, glm::vec3& inscatter, glm::vec3& transmittance)
{
    glsl::integrateScattering(a.transmittance.sampler(), a.multiscatter.sampler(), a.params, camPosM, dirEnu,
                              distanceM, ATMOSPHERE_AERIAL_STEPS, rgb(c.sunDirection), rgb(c.sunIrradiance),
                              rgb(c.moonDirection), rgb(c.moonIrradiance), inscatter, transmittance);
}

void aerialLutTexelCpu(const AtmosphereReference& a, const SkyViewPushConstants& c, int x, int y, int slice, int steps,
                       glm::vec3& inscatter, glm::vec3& transmittance)
{
    float camRM = c.sunDirection.w;
    float v = glsl::texCoordToUnitRange((float(y) + 0.5f) / float(AERIAL_LUT_HEIGHT), float(AERIAL_LUT_HEIGHT));
    float zenith = glsl::skyViewZenithOfUnitV(a.params, camRM, std::clamp(v, 0.0f, 1.0f));
    float azimuth = (float(x) + 0.5f) / float(AERIAL_LUT_WIDTH) * 2.0f * float(SKY_PI);
    glsl::integrateScattering(a.transmittance.sampler(), a.multiscatter.sampler(), a.params, glm::vec3(0.0f, 0.0f, camRM),
                              glsl::enuDirectionFromAngles(zenith, azimuth), glsl::aerialSliceDistanceM(float(slice)),
                              steps, rgb(c.sunDirection), rgb(c.sunIrradiance), rgb(c.moonDirection),
                              rgb(c.moonIrradiance), inscatter, transmittance);
}

glm::vec3 sampleTransmittanceCpu(const AtmosphereReference& a, float rM, float muSun)
{
    return glsl::sampleTransmittance(a.transmittance.sampler(), a.params, rM, muSun);
}

}  // namespace sky
