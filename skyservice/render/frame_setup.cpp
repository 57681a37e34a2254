// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_setup.h"

#include "skyservice/render/view_frustum.h"
#include "skyservice/sky/atmosphere.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace sky
{
namespace
{

vec4 v4(const glm::dvec3& v, double w) { return vec4(float(v.x), float(v.y), float(v.z), float(w)); }

double positiveFmod(double x, double m)
{
    double r = std::fmod(x, m);
    return r < 0 ? r + m : r;
}

bool divides(double period, double modulus)
{
    double q = modulus / period;
    return period > 0 && std::fabs(q - std::round(q)) < 1e-9;
}

}  // namespace

// 16 high-cloud periods (384 km by default): the computed large-scale fields (shaders/lib/large_scale.glsl,
// cloud_shape.glsl largeScaleFbm) have whole cycles per modulus, and every
// noise period must divide it; float offsets of a few hundred kilometres keep ~0.03 m resolution.
double noiseOffsetModulusM(const QualitySettings& q) { return NOISE_OFFSET_MODULUS_HIGH_PERIODS * q.highNoisePeriodM; }

bool validateNoisePeriods(const QualitySettings& q, std::string& error)
{
    double m = noiseOffsetModulusM(q);
    // The high-cloud shader also uses 1/8 and 1/2 of its period.
    for (double p : {q.baseNoisePeriodM, q.detailNoisePeriodM, q.curlNoisePeriodM,
                     q.highNoisePeriodM / 8.0})
        if (!divides(p, m))
        {
            error = "noise period " + std::to_string(p) + " m does not divide " + std::to_string(m) +
                    " m (16 high-cloud periods): clouds would jump when the offsets wrap";
            return false;
        }
    return true;
}

FrameParams makeFrameParams(const FrameInputs& in)
{
    const CameraFrame& cam = *in.camera;
    const QualitySettings& q = *in.quality;
    const RenderTuning defaults;
    const RenderTuning& t = in.tuning ? *in.tuning : defaults;
    const ViewRequest& req = *in.request;
    const WindowSummary& sum = *in.summary;

    FrameParams f;
    std::memset(&f, 0, sizeof f);
    const ViewTangents tangents = viewTangents(req);
    f.cameraRight = v4(cam.rightEnu, tangents.halfWidth);
    f.cameraUp = v4(cam.upEnu, tangents.halfHeight);
    // The ray through the image centre (frame_params.h): an off-centre frustum shifts it from the view
    // axis. A centred one keeps the axis itself, untouched by any arithmetic (the same bytes as always).
    glm::dvec3 centreRay = cam.forwardEnu;
    if (tangents.centreX != 0.0 || tangents.centreY != 0.0)
        centreRay += tangents.centreX * cam.rightEnu + tangents.centreY * cam.upEnu;
    f.cameraForward = v4(centreRay, cam.eye.altitudeM);
    double R = cam.localEarthRadiusM;
    f.earth = vec4(float(R), float(R + cam.eye.altitudeM), float(in.window->warpRadiusM), float(in.window->halfExtentM));
    const EyeOnWindow& e = in.eyeOnWindow;
    f.windowOffsetM = vec4(float(e.offsetM.x), float(e.offsetM.y), 0.0f, 0.0f);
    f.windowAxes = vec4(float(e.eastAxis.x), float(e.eastAxis.y), float(e.northAxis.x), float(e.northAxis.y));

    float minBase = 1e9f, maxTop = -1e9f;
    for (int k = 0; k < MAX_CLOUD_LAYERS; ++k)
    {
        const LayerSummary& l = sum.layers[size_t(k)];
        if (l.empty())
        {
            f.layerRangeM[k] = vec4(1e9f, -1e9f, 0.0f, 0.0f);
            continue;
        }
        f.layerRangeM[k] = vec4(l.minBaseM, l.maxTopM, l.anvilAmount, 0.0f);
        minBase = std::min(minBase, l.minBaseM);
        maxTop = std::max(maxTop, l.maxTopM);
    }
    f.layerRangeM[MAX_CLOUD_LAYERS] =
        sum.anvil.empty() ? vec4(1e9f, -1e9f, 0.0f, 0.0f) : vec4(sum.anvil.minBaseM, sum.anvil.maxTopM, 0.0f, 0.0f);
    if (!sum.anvil.empty())
    {
        minBase = std::min(minBase, sum.anvil.minBaseM);
        maxTop = std::max(maxTop, sum.anvil.maxTopM);
    }
    if (maxTop < minBase)
        minBase = maxTop = 0.0f;  // no volumetric cloud: an empty shell, never marched
    f.shell = vec4(minBase, maxTop, float(q.maxDistanceM), q.highCloud ? sum.highAltitudeM : 0.0f);

    f.sunDirection = v4(in.sunMoon->sun.directionEnu, 0.004675);  // solar angular radius 0.2679 deg (IAU)
    f.sunIrradiance = v4(in.sunIrradiance, 0.0);
    f.moonDirection = v4(in.sunMoon->moon.directionEnu, 0.0);
    f.moonIrradiance = v4(in.sunIrradiance * moonIrradianceRelativeToSun(in.sunMoon->moonPhaseAngleDeg), 0.0);

    const glm::dmat3& m = cam.enuToEcef;  // columns east, north, up
    f.enuToEcef0 = v4(glm::dvec3(m[0][0], m[1][0], m[2][0]), 0.0);
    f.enuToEcef1 = v4(glm::dvec3(m[0][1], m[1][1], m[2][1]), 0.0);
    f.enuToEcef2 = v4(glm::dvec3(m[0][2], m[1][2], m[2][2]), 0.0);

    // Noise offsets in double: eye ECEF minus the wind drift of each layer, modulo a common period.
    double modulus = noiseOffsetModulusM(q);
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        glm::dvec2 wind = k < MAX_CLOUD_LAYERS ? sum.layers[size_t(k)].meanWindEnuMS : sum.upperWindEnuMS;
        glm::dvec3 driftEcef = in.driftEnuToEcef * glm::dvec3(wind * in.animationTimeS, 0.0);
        glm::dvec3 o = cam.eyeEcefM - driftEcef;
        f.layerNoiseOffsetM[k] = vec4(float(positiveFmod(o.x, modulus)), float(positiveFmod(o.y, modulus)),
                                      float(positiveFmod(o.z, modulus)), 0.0f);
        // Wind shear: the top of a layer leans downwind of its base by the wind difference to the upper
        // level over 30 s (our choice: a 20 m/s difference leans a tower top 600 m; more than that makes
        // a field of small clouds read as streaks).
        glm::dvec2 shear = k < MAX_CLOUD_LAYERS ? (sum.upperWindEnuMS - wind) * 30.0 : glm::dvec2(0.0);
        f.layerShearM[k] = vec4(float(shear.x), float(shear.y), 0.0f, 0.0f);
    }
    f.noiseScale = vec4(float(q.baseNoisePeriodM), float(q.detailNoisePeriodM), float(q.curlNoisePeriodM),
                        float(q.highNoisePeriodM));
    f.cloudLook = vec4(float(q.extinctionPerM), float(q.detailErosion), float(q.ambientStrength), float(q.octaves));
    f.lightingTerms = vec4(float(q.octaveAttenuation), float(q.octaveContribution), float(q.octaveEccentricity),
                           float(q.powderStrength));
    f.phaseTerms = vec4(float(q.phaseForwardG), float(q.phaseBackG), float(q.phaseForwardWeight), float(q.coneStepM));
    f.ambientSky = v4(in.ambientSkyRadiance, in.groundAlbedo);
    f.ambientGround = v4(in.groundIrradiance, 0.0);
    f.exposure = vec4(float(in.exposure), float(in.animationTimeS), 0.0f, 0.0f);
    uint32_t flags = 0;
    if (!q.detail)
        flags |= FRAME_FLAG_NO_DETAIL;
    if (!q.highCloud)
        flags |= FRAME_FLAG_NO_HIGH_CLOUD;
    if (!req.linearOutput)
        flags |= FRAME_FLAG_NO_LINEAR_OUTPUT;
    if (q.reprojected)
        flags |= FRAME_FLAG_REPROJECTED;
    if (!t.emptySpaceSkipping)
        flags |= FRAME_FLAG_NO_SKIPPING;
    if (t.marchLookupTotals)
        flags |= FRAME_FLAG_LOOKUP_TOTALS;
    f.image = uvec4(req.width, req.height, 0u, flags);
    f.march = uvec4(q.maxViewSteps, q.lightSamples, uint32_t(std::clamp(t.coneNearMergeBeyondM, 0.0, 1e9)), 0u);
    f.marchLod = vec4(float(t.detailFadeStartM), float(std::max(t.detailFadeEndM, t.detailFadeStartM + 1.0)),
                      float(std::max(t.lightLodDistanceM, 0.0)), float(q.fullConeSamples));
    f.detailLod = vec4(float(t.detailMinTransmittance), float(std::max(t.deepStepFactor, 1.0)),
                       float(std::max(t.maxStepOpticalDepth, 0.0)), float(std::max(t.deepLightReuseM, 0.0)));
    // One jitter texel: a pixel's height at the view axis (2 tan(fovY/2) / height when centred), so that
    // channels of one wall with the same vertical extent and height share the texels.
    f.worldJitter = vec4(float(2.0 * tangents.halfHeight / double(req.height)), 0.0f, 0.0f, 0.0f);
    f.reprojection = uvec4(1u, 0u, 0u, 0u);  // full resolution unless the renderer's reprojected path says otherwise
    return f;
}

}  // namespace sky
