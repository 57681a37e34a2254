// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_setup.h"

#include "skyservice/render/light_volume.h"
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

// A part with every member zero, the unused ones included: the light volume compares frames bytewise.
template <typename Part>
Part zeroed()
{
    Part p;
    std::memset(&p, 0, sizeof p);
    return p;
}

vec3 f3(const glm::dvec3& v) { return vec3(float(v.x), float(v.y), float(v.z)); }

double halton(uint32_t index, uint32_t base)
{
    double f = 1.0, r = 0.0;
    for (uint32_t i = index; i > 0; i /= base)
    {
        f /= base;
        r += f * double(i % base);
    }
    return r;
}

CameraParams cameraParams(const CameraFrame& cam, const ViewTangents& tangents)
{
    CameraParams c = zeroed<CameraParams>();
    c.rightEnu = f3(cam.rightEnu);
    c.halfWidthTan = float(tangents.halfWidth);
    c.upEnu = f3(cam.upEnu);
    c.halfHeightTan = float(tangents.halfHeight);
    // The ray through the image centre (frame_params.h): an off-centre frustum shifts it from the view
    // axis. A centred one keeps the axis itself, untouched by any arithmetic (the same bytes as always).
    glm::dvec3 centreRay = cam.forwardEnu;
    if (tangents.centreX != 0.0 || tangents.centreY != 0.0)
        centreRay += tangents.centreX * cam.rightEnu + tangents.centreY * cam.upEnu;
    c.centreRayEnu = f3(centreRay);
    c.eyeAltitudeM = float(cam.eye.altitudeM);
    return c;
}

EarthParams earthParams(const CameraFrame& cam)
{
    EarthParams e = zeroed<EarthParams>();
    e.radiusM = float(cam.localEarthRadiusM);
    e.centreToEyeM = float(cam.localEarthRadiusM + cam.eye.altitudeM);
    return e;
}

WindowParams windowParams(const WeatherWindow& window, const EyeOnWindow& e)
{
    WindowParams w = zeroed<WindowParams>();
    w.eyeOnPlaneM = vec2(float(e.offsetM.x), float(e.offsetM.y));
    w.warpRadiusM = float(window.warpRadiusM);
    w.halfExtentM = float(window.halfExtentM);
    w.eastAxis = vec2(float(e.eastAxis.x), float(e.eastAxis.y));
    w.northAxis = vec2(float(e.northAxis.x), float(e.northAxis.y));
    return w;
}

// Layer k of the window (the anvil slab at MAX_CLOUD_LAYERS): its altitude band, its noise offset in
// double (eye ECEF minus the wind drift, modulo a common period) and its wind shear.
CloudLayerParams layerParams(const FrameInputs& in, int k)
{
    const WindowSummary& sum = *in.summary;
    const bool anvil = k == MAX_CLOUD_LAYERS;
    const LayerSummary& l = anvil ? sum.anvil : sum.layers[size_t(k)];
    CloudLayerParams p = zeroed<CloudLayerParams>();
    p.lowestBaseM = l.empty() ? 1e9f : l.minBaseM;
    p.highestTopM = l.empty() ? -1e9f : l.maxTopM;
    p.anvilAmount = anvil || l.empty() ? 0.0f : l.anvilAmount;
    const glm::dvec2 wind = anvil ? sum.upperWindEnuMS : l.meanWindEnuMS;
    const glm::dvec3 driftEcef = in.driftEnuToEcef * glm::dvec3(wind * in.animationTimeS, 0.0);
    const glm::dvec3 o = in.camera->eyeEcefM - driftEcef;
    const double modulus = noiseOffsetModulusM(*in.quality);
    p.noiseOffsetM = vec3(float(positiveFmod(o.x, modulus)), float(positiveFmod(o.y, modulus)),
                          float(positiveFmod(o.z, modulus)));
    // Wind shear: the top of a layer leans downwind of its base by the wind difference to the upper
    // level over 30 s (our choice: a 20 m/s difference leans a tower top 600 m; more than that makes
    // a field of small clouds read as streaks).
    const glm::dvec2 shear = anvil ? glm::dvec2(0.0) : (sum.upperWindEnuMS - wind) * 30.0;
    p.topShearM = vec2(float(shear.x), float(shear.y));
    return p;
}

CloudShellParams shellParams(const WindowSummary& sum, const QualitySettings& q)
{
    float minBase = 1e9f, maxTop = -1e9f;
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        const LayerSummary& l = k < MAX_CLOUD_LAYERS ? sum.layers[size_t(k)] : sum.anvil;
        if (l.empty())
            continue;
        minBase = std::min(minBase, l.minBaseM);
        maxTop = std::max(maxTop, l.maxTopM);
    }
    if (maxTop < minBase)
        minBase = maxTop = 0.0f;  // no volumetric cloud: an empty shell, never marched
    CloudShellParams s = zeroed<CloudShellParams>();
    s.lowestBaseM = minBase;
    s.highestTopM = maxTop;
    s.maxMarchDistanceM = float(q.maxDistanceM);
    s.highCloudAltitudeM = q.highCloud ? sum.highAltitudeM : 0.0f;
    return s;
}

SunMoonParams sunMoonParams(const FrameInputs& in)
{
    SunMoonParams l = zeroed<SunMoonParams>();
    l.sunDirectionEnu = f3(in.sunMoon->sun.directionEnu);
    l.sunAngularRadiusRad = float(0.004675);  // solar angular radius 0.2679 deg (IAU)
    l.sunIrradiance = f3(in.sunIrradiance);
    l.moonDirectionEnu = f3(in.sunMoon->moon.directionEnu);
    l.moonIrradiance = f3(in.sunIrradiance * moonIrradianceRelativeToSun(in.sunMoon->moonPhaseAngleDeg));
    return l;
}

EnuToEcefParams enuToEcefParams(const glm::dmat3& m)  // columns east, north, up
{
    EnuToEcefParams r = zeroed<EnuToEcefParams>();
    r.row0 = f3(glm::dvec3(m[0][0], m[1][0], m[2][0]));
    r.row1 = f3(glm::dvec3(m[0][1], m[1][1], m[2][1]));
    r.row2 = f3(glm::dvec3(m[0][2], m[1][2], m[2][2]));
    return r;
}

NoisePeriodParams noisePeriodParams(const QualitySettings& q)
{
    NoisePeriodParams n = zeroed<NoisePeriodParams>();
    n.baseM = float(q.baseNoisePeriodM);
    n.detailM = float(q.detailNoisePeriodM);
    n.curlM = float(q.curlNoisePeriodM);
    n.highCloudM = float(q.highNoisePeriodM);
    return n;
}

CloudLookParams lookParams(const QualitySettings& q)
{
    CloudLookParams l = zeroed<CloudLookParams>();
    l.extinctionPerM = float(q.extinctionPerM);
    l.detailErosion = float(q.detailErosion);
    l.ambientStrength = float(q.ambientStrength);
    l.octaves = q.octaves;
    l.octaveAttenuation = float(q.octaveAttenuation);
    l.octaveContribution = float(q.octaveContribution);
    l.octaveEccentricity = float(q.octaveEccentricity);
    l.powderStrength = float(q.powderStrength);
    l.phaseForwardG = float(q.phaseForwardG);
    l.phaseBackG = float(q.phaseBackG);
    l.phaseForwardWeight = float(q.phaseForwardWeight);
    l.coneStepM = float(q.coneStepM);
    return l;
}

AmbientParams ambientParams(const FrameInputs& in)
{
    AmbientParams a = zeroed<AmbientParams>();
    a.skyRadiance = f3(in.ambientSkyRadiance);
    a.groundAlbedo = float(in.groundAlbedo);
    a.groundIrradiance = f3(in.groundIrradiance);
    return a;
}

uint32_t frameFlags(const FrameInputs& in, const RenderTuning& t)
{
    const QualitySettings& q = *in.quality;
    const FrameOutputs& out = in.outputs;
    uint32_t flags = 0;
    if (!q.detail)
        flags |= FRAME_FLAG_NO_DETAIL;
    if (!q.highCloud)
        flags |= FRAME_FLAG_NO_HIGH_CLOUD;
    if (!in.request->linearOutput)
        flags |= FRAME_FLAG_NO_LINEAR_OUTPUT;
    if (q.reprojected)
        flags |= FRAME_FLAG_REPROJECTED;
    if (!t.emptySpaceSkipping)
        flags |= FRAME_FLAG_NO_SKIPPING;
    if (t.marchLookupTotals)
        flags |= FRAME_FLAG_LOOKUP_TOTALS;
    // The composite's optional outputs (frame_outputs.h).
    if (out.sky)
        flags |= FRAME_FLAG_SKY_LAYER;
    if (out.cloudLayer)
        flags |= FRAME_FLAG_CLOUD_LAYER;
    if (out.depthLayer)
        flags |= FRAME_FLAG_DEPTH_LAYER;
    if (q.reprojected && (out.cloud || out.depth))
        flags |= FRAME_FLAG_WRITE_CLOUD;
    return flags;
}

ImageParams imageParams(const FrameInputs& in, const RenderTuning& t)
{
    ImageParams i = zeroed<ImageParams>();
    i.widthPx = in.request->width;
    i.heightPx = in.request->height;
    i.flags = frameFlags(in, t);
    i.exposure = float(in.exposure);
    return i;
}

// Accumulation: each frame has new march jitter (frame index) and a sub-pixel offset (Halton 2,3).
// Reprojected frames keep the march jitter of frame 0: a pixel marched again gives the same value, so a
// still view converges to exactly the full-resolution image.
SequenceParams sequenceParams(const FrameInputs& in)
{
    const uint32_t k = in.accumulationIndex;
    const bool accumulating = in.accumulationFrames > 1;
    SequenceParams s = zeroed<SequenceParams>();
    s.rayJitterPx = vec2(accumulating ? float(halton(k + 1, 2) - 0.5) : 0.0f,
                         accumulating ? float(halton(k + 1, 3) - 0.5) : 0.0f);
    s.frameIndex = k;
    s.animationTimeS = float(in.animationTimeS);
    return s;
}

MarchParams marchParams(const QualitySettings& q, const RenderTuning& t, const ViewTangents& tangents,
                        uint32_t heightPx)
{
    MarchParams m = zeroed<MarchParams>();
    m.maxViewSteps = q.maxViewSteps;
    m.coneSamples = q.lightSamples;
    m.coneNearMergeBeyondM = uint32_t(std::clamp(t.coneNearMergeBeyondM, 0.0, 1e9));
    // One jitter texel: a pixel's height at the view axis (2 tan(fovY/2) / height when centred), so that
    // channels of one wall with the same vertical extent and height share the texels.
    m.jitterTexelRad = float(2.0 * tangents.halfHeight / double(heightPx));
    m.detailFadeStartM = float(t.detailFadeStartM);
    m.detailFadeEndM = float(std::max(t.detailFadeEndM, t.detailFadeStartM + 1.0));
    m.coneCheapBeyondM = float(std::max(t.lightLodDistanceM, 0.0));
    m.fullConeSamples = q.fullConeSamples;
    m.detailMinTransmittance = float(t.detailMinTransmittance);
    m.deepStepFactor = float(std::max(t.deepStepFactor, 1.0));
    m.maxStepOpticalDepth = float(std::max(t.maxStepOpticalDepth, 0.0));
    return m;
}

LightReuseParams lightReuseParams(const RenderTuning& t)
{
    LightReuseParams r = zeroed<LightReuseParams>();
    r.coneTailReuseM = float(std::max(t.coneTailReuseM, 0.0));
    r.coneTailReuseBeyondM = float(std::max(t.coneTailReuseBeyondM, 0.0));
    r.deepLightReuseM = float(std::max(t.deepLightReuseM, 0.0));
    return r;
}

// Full resolution: every pixel marched, no history.
ReprojectionParams fullResolution()
{
    ReprojectionParams r = zeroed<ReprojectionParams>();
    r.blockPx = 1u;
    return r;
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
    const ViewTangents tangents = viewTangents(req);

    FrameParams f = zeroed<FrameParams>();
    f.camera = cameraParams(cam, tangents);
    f.earth = earthParams(cam);
    f.window = windowParams(*in.window, in.eyeOnWindow);
    f.shell = shellParams(*in.summary, q);
    f.light = sunMoonParams(in);
    f.enuToEcef = enuToEcefParams(cam.enuToEcef);
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
        f.layers[k] = layerParams(in, k);
    f.noisePeriod = noisePeriodParams(q);
    f.look = lookParams(q);
    f.ambient = ambientParams(in);
    f.image = imageParams(in, t);
    f.sequence = sequenceParams(in);
    f.march = marchParams(q, t, tangents, req.height);
    f.lightReuse = lightReuseParams(t);
    f.reprojection = in.reprojection ? *in.reprojection : fullResolution();
    // After the march block is known: the light volume counts the rays it leaves.
    f.lightVolume = placeLightVolume(q, t, f.window.eyeOnPlaneM, f.shell.highestTopM > f.shell.lowestBaseM,
                                     marchedRays(req.width, req.height, f.reprojection.blockPx));
    return f;
}

}  // namespace sky
