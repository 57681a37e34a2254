// SPDX-License-Identifier: MIT
#include "skyservice/render/atmosphere_passes.h"

#include "skyservice/vk/programs.h"

#include "shaders/shared/atmosphere_params.h"
#include "skyservice/sky/atmosphere.h"
#include "skyservice/sky/atmosphere_reference.h"

#include <cmath>
#include <cstring>

namespace sky
{
namespace
{

// The LUTs depend on the ground radius; the osculating radius changes by ~21 km from equator to pole,
// and the sky by < 0.1% per km of it (atmosphere.h), so the atmosphere's ground radius is the eye's
// osculating radius rounded to 1 km, and the LUTs are rebuilt when that rounded value changes. Rounding
// (not "rebuild when it moved 1 km from the last build") makes the sky a function of the eye alone:
// two display channels, or a flight and a one-shot render, at the same pose get the same bytes.
constexpr double kLutRadiusStepM = 1000.0;
double atmosphereGroundRadiusM(const CameraFrame& camera)
{
    return kLutRadiusStepM * std::round(camera.localEarthRadiusM / kLutRadiusStepM);
}

glm::dvec3 toD(const glm::vec3& v) { return glm::dvec3(v.x, v.y, v.z); }

// The sky-view and aerial-perspective LUTs are kept while their inputs are bit for bit the same, but an
// eye in flight turns its ENU axes, so the sun's and moon's ENU directions change every frame (~1e-6 rad
// at 250 m/s): the directions the LUTs are built for are rounded to 2^-14 per component (6e-5 rad,
// 0.0035 degrees; a sky-view texel is 1-2 degrees, and the disks are drawn at the exact directions) and
// the moon's angular radius to 1e-5 of itself, so level flight at 250 m/s keeps the LUTs for ~30 frames. Rounding, not "rebuild when it moved enough": the sky
// stays a function of this frame's inputs alone (channels and one-shot renders get the same bytes).
vec3 lutDirection(const glm::dvec3& d)
{
    const double step = 1.0 / 16384.0;
    glm::dvec3 q = glm::round(d / step) * step;
    double n = glm::length(q);
    return n > 0.0 ? vec3(q / n) : vec3(0.0f, 0.0f, 1.0f);
}

AtmosphereParams frameAtmosphere(double radiusM, const SunMoon& sunMoon, const ViewRequest& view)
{
    AtmosphereParams p = makeEarthAtmosphere(radiusM);
    if (view.visibilityM > 0.0)
        setHazeVisibility(p, view.visibilityM);
    setGroundFog(p, view.fogBaseM, view.fogTopM, view.fogVisibilityM);
    double moonRadiusRad = moonAngularRadiusRad(sunMoon.moon.distanceM);
    p.radii.w = float(std::round(moonRadiusRad * 1e8) * 1e-8);  // 1e-5 of ~4.5e-3 rad
    return p;
}

}  // namespace

SkyStatus createAtmospherePass(const Context& ctx, MemoryTracker& memory, AtmospherePass& a)
{
    SKY_TRY(createProgram(ctx, a.transmittanceProgram, "transmittance_lut"));
    SKY_TRY(createProgram(ctx, a.multiscatterProgram, "multiscatter_lut"));
    SKY_TRY(createProgram(ctx, a.skyViewProgram, "sky_view_lut"));
    SKY_TRY(createProgram(ctx, a.aerialPerspectiveProgram, "aerial_perspective_lut"));
    ImageDesc d;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.width = TRANSMITTANCE_LUT_WIDTH;
    d.height = TRANSMITTANCE_LUT_HEIGHT;
    SKY_TRY(createImage(ctx, memory, a.transmittanceLut, d, "transmittance LUT"));
    d.width = d.height = MULTISCATTER_LUT_SIZE;
    SKY_TRY(createImage(ctx, memory, a.multiscatterLut, d, "multiple-scattering LUT"));
    d.width = SKY_VIEW_LUT_WIDTH;
    d.height = SKY_VIEW_LUT_HEIGHT;
    SKY_TRY(createImage(ctx, memory, a.skyViewLut, d, "sky-view LUT"));
    d.viewType = VK_IMAGE_VIEW_TYPE_3D;
    d.width = AERIAL_LUT_WIDTH;
    d.height = AERIAL_LUT_HEIGHT;
    d.depth = AERIAL_LUT_SLICES;
    SKY_TRY(createImage(ctx, memory, a.aerialInscatterLut, d, "aerial-perspective LUT (in-scattering)"));
    SKY_TRY(createImage(ctx, memory, a.aerialTransmittanceLut, d, "aerial-perspective LUT (transmittance)"));
    OneShot shot;
    SKY_TRY(beginOneShot(ctx, shot));
    for (Image* img : {&a.transmittanceLut, &a.multiscatterLut, &a.skyViewLut, &a.aerialInscatterLut,
                       &a.aerialTransmittanceLut})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(ctx, shot);
}

void destroyAtmospherePass(const Context& ctx, MemoryTracker& memory, AtmospherePass& a)
{
    for (Image* img : {&a.transmittanceLut, &a.multiscatterLut, &a.skyViewLut, &a.aerialInscatterLut,
                       &a.aerialTransmittanceLut})
        destroyImage(ctx, memory, *img);
    for (Program* p : {&a.transmittanceProgram, &a.multiscatterProgram, &a.skyViewProgram, &a.aerialPerspectiveProgram})
        destroyProgram(ctx, *p);
}

void forgetAtmosphereLuts(AtmospherePass& a)
{
    a.radiusM = 0;
    a.skyViewInputsValid = false;
}

LightingEstimate estimateLighting(AtmospherePass& a, const CameraFrame& camera, const SunMoon& sunMoon,
                                  const WindowSummary& summary)
{
    LightingEstimate e;
    const double R = atmosphereGroundRadiusM(camera);
    if (a.cpuRadiusM != R)
    {
        a.cpu = createAtmosphereReference(makeEarthAtmosphere(R));
        a.cpuRadiusM = R;
    }
    const AtmosphereParams& p = a.cpu.params;
    e.sunIrradiance = toD(glm::vec3(p.solarIrradiance.x, p.solarIrradiance.y, p.solarIrradiance.z));
    e.groundAlbedo = double(p.groundAlbedo.x);

    // Sky radiance seen from the middle of the cloud layers, averaged over the upper hemisphere.
    float cloudAltitudeM = 2000.0f;
    for (const LayerSummary& l : summary.layers)
        if (!l.empty())
        {
            cloudAltitudeM = 0.5f * (l.minBaseM + l.maxTopM);
            break;
        }
    SkyViewPushConstants c;
    std::memset(&c, 0, sizeof c);
    glm::dvec3 moonIrr = e.sunIrradiance * moonIrradianceRelativeToSun(sunMoon.moonPhaseAngleDeg);
    c.sunDirection = vec4(glm::vec3(sunMoon.sun.directionEnu), float(R) + cloudAltitudeM);
    c.sunIrradiance = vec4(glm::vec3(e.sunIrradiance), 0.0f);
    c.moonDirection = vec4(glm::vec3(sunMoon.moon.directionEnu), 0.0f);
    c.moonIrradiance = vec4(glm::vec3(moonIrr), 0.0f);
    c.flags = uvec4(0u);
    glm::dvec3 sum(0.0);
    int count = 0;
    for (int row : {SKY_VIEW_LUT_HEIGHT / 10, SKY_VIEW_LUT_HEIGHT / 5, SKY_VIEW_LUT_HEIGHT / 3})
        for (int col = 0; col < SKY_VIEW_LUT_WIDTH; col += SKY_VIEW_LUT_WIDTH / 8)
        {
            sum += toD(skyViewTexel(a.cpu, c, col, row));
            ++count;
        }
    e.ambientSkyRadiance = sum / double(count);

    // Irradiance on the ground: direct sun and moon through the atmosphere plus the sky (pi * radiance).
    auto direct = [&](const glm::dvec3& dir, const glm::dvec3& irradiance) {
        if (dir.z <= 0.0)
            return glm::dvec3(0.0);
        return irradiance * toD(sampleTransmittanceCpu(a.cpu, float(R), float(dir.z))) * dir.z;
    };
    e.groundIrradiance = direct(sunMoon.sun.directionEnu, e.sunIrradiance) +
                         direct(sunMoon.moon.directionEnu, moonIrr) + M_PI * e.ambientSkyRadiance;

    // Exposure: a white cloud facing the light maps to ~1.2 before tone mapping. The light is measured
    // at cloud level at normal incidence (a horizontal ground sees almost nothing at sunset, a cloud's
    // side sees the whole red sun), plus the sky. Below the floor (deep twilight, moonlight) the picture
    // is allowed to go dark, as the eye sees it.
    auto normalIncidence = [&](const glm::dvec3& dir, const glm::dvec3& irradiance) {
        float mu = float(std::max(dir.z, -0.2));
        return irradiance * toD(sampleTransmittanceCpu(a.cpu, float(R) + cloudAltitudeM, mu));
    };
    glm::dvec3 keyLight = normalIncidence(sunMoon.sun.directionEnu, e.sunIrradiance) +
                          normalIncidence(sunMoon.moon.directionEnu, moonIrr);
    double whiteRadiance =
        glm::dot(0.6 * keyLight + M_PI * e.ambientSkyRadiance, glm::dvec3(0.2126, 0.7152, 0.0722)) / M_PI;
    const double kNightFloorRadiance = 2e-6;
    // Rounded to 1/512 of a stop (0.14 %, below an 8-bit display step): the LUTs hold pre-exposed radiance,
    // and an exposure that drifts by 1e-7 every frame of a flight would rebuild them every frame.
    double exposure = 1.2 / std::max(whiteRadiance, kNightFloorRadiance);
    e.exposure = std::exp2(std::round(std::log2(exposure) * 512.0) / 512.0);
    return e;
}

void recordAtmosphere(const PassFrame& f, AtmospherePass& a, const CameraFrame& camera, const SunMoon& sunMoon,
                      const FrameInputs& in)
{
    VkCommandBuffer cmd = f.cmd;
    const VkSampler clamp = f.samplers.linearClamp;
    const double R = atmosphereGroundRadiusM(camera);
    AtmosphereParams p = frameAtmosphere(R, sunMoon, *in.request);
    std::memcpy(f.atmosphereUniforms.mapped, &p, sizeof p);
    // The transmittance and multiple-scattering LUTs depend on the radius, the haze and the fog. The last
    // haze and fog they were made with are the sky-view LUT's (made in the same call as they are, after them).
    const bool hazeChanged =
        std::memcmp(&p.mieScattering, &a.skyViewAtmosphere.mieScattering, 2 * sizeof(vec4)) != 0 ||
        std::memcmp(&p.groundFog, &a.skyViewAtmosphere.groundFog, sizeof(vec4)) != 0;
    const bool rebuild = a.radiusM != R || hazeChanged;
    if (rebuild)
    {
        dispatch(f.ctx, cmd, a.transmittanceProgram, TRANSMITTANCE_LUT_WIDTH, TRANSMITTANCE_LUT_HEIGHT, 1, nullptr, 0,
                 {DescriptorInfo(f.atmosphereUniforms), DescriptorInfo(a.transmittanceLut)});
        computeBarrier(cmd);
        dispatch(f.ctx, cmd, a.multiscatterProgram, MULTISCATTER_LUT_SIZE, MULTISCATTER_LUT_SIZE, 1, nullptr, 0,
                 {DescriptorInfo(f.atmosphereUniforms), DescriptorInfo(a.multiscatterLut),
                  DescriptorInfo(a.transmittanceLut, clamp)});
        computeBarrier(cmd);
        a.radiusM = R;
    }
    SkyViewPushConstants c;
    std::memset(&c, 0, sizeof c);
    c.sunDirection = vec4(lutDirection(sunMoon.sun.directionEnu), float(R + camera.eye.altitudeM));
    c.sunIrradiance = vec4(glm::vec3(in.sunIrradiance), 0.0f);
    c.moonDirection = vec4(lutDirection(sunMoon.moon.directionEnu), 0.0f);
    c.moonIrradiance =
        vec4(glm::vec3(in.sunIrradiance * moonIrradianceRelativeToSun(sunMoon.moonPhaseAngleDeg)), 0.0f);
    c.flags = uvec4(SKY_VIEW_FLAG_GROUND, 0u, 0u, 0u);
    // The sky-view and aerial-perspective LUTs are pure functions of these inputs and of the two LUTs above: a frame whose
    // inputs are bit for bit the last one's (a still eye, or one flying level, with the time frozen; the
    // frames of an accumulation) keeps it. Exact comparison, so the picture never depends on the past.
    if (!rebuild && a.skyViewInputsValid && std::memcmp(&c, &a.skyViewPush, sizeof c) == 0 &&
        std::memcmp(&p, &a.skyViewAtmosphere, sizeof p) == 0)
        return;
    a.skyViewPush = c;
    a.skyViewAtmosphere = p;
    a.skyViewInputsValid = true;
    dispatch(f.ctx, cmd, a.skyViewProgram, SKY_VIEW_LUT_WIDTH, SKY_VIEW_LUT_HEIGHT, 1, c,
             {DescriptorInfo(f.atmosphereUniforms), DescriptorInfo(a.skyViewLut),
              DescriptorInfo(a.transmittanceLut, clamp), DescriptorInfo(a.multiscatterLut, clamp)});
    dispatch(f.ctx, cmd, a.aerialPerspectiveProgram, AERIAL_LUT_WIDTH, AERIAL_LUT_HEIGHT, 1, c,
             {DescriptorInfo(f.atmosphereUniforms), DescriptorInfo(a.aerialInscatterLut),
              DescriptorInfo(a.transmittanceLut, clamp), DescriptorInfo(a.multiscatterLut, clamp),
              DescriptorInfo(a.aerialTransmittanceLut)});
}

}  // namespace sky
