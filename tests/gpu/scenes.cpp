// SPDX-License-Identifier: MIT
#include "tests/gpu/scenes.h"

#include "shaders/shared/atmosphere_params.h"
#include "skyservice/sky/atmosphere.h"
#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

namespace sky::testscenes
{

QualitySettings testQuality()
{
    QualitySettings q;
    q.maxViewSteps = 64;
    q.lightSamples = 4;
    q.octaves = 2;
    q.lightVolumeMinRays = 0;  // the light volume at test sizes too, as on a GPU at 1080p
    return q;
}

int64_t parseTime(const std::string& iso)
{
    int64_t t = 0;
    std::string error;
    if (!parseIso8601Utc(iso, t, error))
        throw std::runtime_error(error);
    return t;
}

int64_t timeOfSunElevation(double latDeg, double lonDeg, const std::string& startIso, double elevationDeg)
{
    int64_t t = parseTime(startIso);
    for (int minute = 0; minute < 12 * 60; ++minute, t += 60)
        if (computeSunMoon(t, latDeg, lonDeg, 0.0).sun.elevationDeg <= elevationDeg)
            return t;
    return t;
}

WeatherSnapshot clearSky()
{
    WeatherSnapshot w;
    w.grid = {-90.0, 0.0, 1.0, 1.0, 181, 360};
    return w;
}

WeatherSnapshot uniformLayer(float coverage, CloudType type, float baseM, float topM)
{
    WeatherSnapshot w = clearSky();
    size_t n = w.grid.cellCount();
    CloudLayerFields l;
    l.name = "test";
    l.coverage.assign(n, coverage);
    l.baseAltitudeM.assign(n, baseM);
    l.topAltitudeM.assign(n, topM);
    l.type.assign(n, uint8_t(type));
    l.precipitationMmH.assign(n, 0.0f);
    l.windEastMS.assign(n, 5.0f);
    l.windNorthMS.assign(n, 0.0f);
    w.layers.push_back(l);
    return w;
}

WeatherSnapshot isolatedCell(double latDeg, double lonDeg, double radiusM, CloudType type, float baseM, float topM)
{
    WeatherSnapshot w;
    w.grid = {latDeg - 0.5, lonDeg - 0.5, 0.01, 0.01, 101, 101};
    size_t n = w.grid.cellCount();
    CloudLayerFields l;
    l.name = "cell";
    l.coverage.assign(n, 0.0f);
    l.baseAltitudeM.assign(n, baseM);
    l.topAltitudeM.assign(n, topM);
    l.type.assign(n, uint8_t(type));
    l.precipitationMmH.assign(n, 0.0f);
    l.windEastMS.assign(n, 0.0f);
    l.windNorthMS.assign(n, 0.0f);
    for (uint32_t i = 0; i < w.grid.nLat; ++i)
        for (uint32_t j = 0; j < w.grid.nLon; ++j)
        {
            double dy = (w.grid.lat0Deg + i * w.grid.dLatDeg - latDeg) * 111320.0;
            double dx = (w.grid.lon0Deg + j * w.grid.dLonDeg - lonDeg) * 111320.0 * std::cos(latDeg * M_PI / 180.0);
            double r = std::hypot(dx, dy) / radiusM;
            l.coverage[w.grid.index(i, j)] = r < 1.0 ? float(1.0 - r * r * r) : 0.0f;
        }
    w.layers.push_back(l);
    return w;
}

ViewRequest lookUp(double latDeg, double lonDeg, double altM, double pitchDeg, const std::string& timeIso)
{
    ViewRequest v;
    v.pose = {latDeg, lonDeg, altM, 0.0, pitchDeg, 0.0};
    v.fovYDeg = 60.0;
    v.width = 320;
    v.height = 180;
    v.unixTimeS = parseTime(timeIso);
    return v;
}

ViewRequest lookDown(double latDeg, double lonDeg, double altM, int64_t unixTimeS)
{
    ViewRequest v;
    v.pose = {latDeg, lonDeg, altM, 270.0, -35.0, 0.0};
    v.fovYDeg = 50.0;
    v.width = 320;
    v.height = 180;
    v.unixTimeS = unixTimeS;
    return v;
}

ViewRequest cumulonimbusView(const std::string& timeIso)
{
    ViewRequest v;
    double lat = kBuiltinCumulonimbusLatDeg;
    double lon = kBuiltinCumulonimbusLonDeg - 40000.0 / (111320.0 * std::cos(lat * M_PI / 180.0));
    v.pose = {lat, lon, 4500.0, 90.0, 6.0, 0.0};  // above the cumulus field, as in the showcase
    v.fovYDeg = 60.0;
    v.width = 320;
    v.height = 180;
    v.unixTimeS = parseTime(timeIso);
    return v;
}

ViewRequest builtinCumulonimbus320(Renderer& r)
{
    setWeather(r, makeBuiltinWeather(0));
    return cumulonimbusView("2026-06-21T15:00:00Z");  // 320x180
}

ImageStats cloudStats(const RenderResult& r, uint32_t rowEnd)
{
    ImageStats s;
    size_t pixels = size_t(r.width) * std::min(r.height, rowEnd);
    double lum = 0, red = 0, blue = 0, display = 0, opaque = 0;
    for (size_t i = 0; i < pixels; ++i)
    {
        float c[4];
        for (int k = 0; k < 4; ++k)
        {
            c[k] = glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + size_t(k)]);
            float lin = glm::unpackHalf1x16(r.linearRgbaHalf[i * 4 + size_t(k)]);
            if (!std::isfinite(c[k]) || !std::isfinite(lin) || c[k] < 0.0f || lin < 0.0f)
                s.allFinite = false;
        }
        display += (0.2126 * r.displayRgba8[i * 4] + 0.7152 * r.displayRgba8[i * 4 + 1] +
                    0.0722 * r.displayRgba8[i * 4 + 2]) / 255.0;
        s.maxAlpha = std::max(s.maxAlpha, c[3]);
        ++s.skyPixels;  // views in the tests look above the horizon
        if (c[3] > 0.5f)
        {
            ++s.cloudPixels;
            lum += double(0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]) / double(c[3]);
            red += double(c[0] / c[3]);
            blue += double(c[2] / c[3]);
        }
        if (c[3] > 0.95f)
        {
            ++s.opaquePixels;
            opaque += double(0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]) / double(c[3]);
        }
    }
    if (s.cloudPixels)
    {
        s.meanCloudLuminance = lum / s.cloudPixels;
        s.meanCloudRed = red / s.cloudPixels;
        s.meanCloudBlue = blue / s.cloudPixels;
    }
    s.meanDisplayLuminance = display / double(pixels);
    if (s.opaquePixels)
        s.meanOpaqueLuminance = opaque / s.opaquePixels;
    return s;
}

std::vector<SkyProbe> cpuSkyProbes(Renderer& r, const ViewRequest& view, int count)
{
    CameraFrame cam = computeCameraFrame(view.pose);
    SunMoon sm = computeSunMoon(view.unixTimeS, cam.eye.latDeg, cam.eye.lonDeg, cam.eye.altitudeM);
    double R = cam.localEarthRadiusM;
    AtmosphereReference ref = createAtmosphereReference(makeEarthAtmosphere(R));
    glm::dvec3 sun = glm::dvec3(ref.params.solarIrradiance.x, ref.params.solarIrradiance.y, ref.params.solarIrradiance.z);
    SkyViewPushConstants c;
    std::memset(&c, 0, sizeof c);
    c.sunDirection = vec4(glm::vec3(sm.sun.directionEnu), float(R + cam.eye.altitudeM));
    c.sunIrradiance = vec4(glm::vec3(sun), 0.0f);
    c.moonDirection = vec4(glm::vec3(sm.moon.directionEnu), 0.0f);
    c.moonIrradiance = vec4(glm::vec3(sun * moonIrradianceRelativeToSun(sm.moonPhaseAngleDeg)), 0.0f);
    c.flags = uvec4(SKY_VIEW_FLAG_GROUND, 0u, 0u, 0u);
    CpuTexture2D lut = computeSkyViewLut(ref, c);
    (void)r;

    std::vector<SkyProbe> probes;
    double tanHalf = std::tan(view.fovYDeg * M_PI / 360.0);
    double aspect = double(view.width) / double(view.height);
    for (int k = 0; k < count * 4 && int(probes.size()) < count; ++k)
    {
        int x = int((uint32_t(k) * 97u + 13u) % view.width);
        int y = int((uint32_t(k) * 61u + 7u) % view.height);
        double nx = (x + 0.5) / view.width * 2.0 - 1.0, ny = (y + 0.5) / view.height * 2.0 - 1.0;
        glm::dvec3 d = glm::normalize(cam.forwardEnu + nx * tanHalf * aspect * cam.rightEnu - ny * tanHalf * cam.upEnu);
        if (glm::dot(d, sm.sun.directionEnu) > std::cos(3.0 * M_PI / 180.0) ||
            glm::dot(d, sm.moon.directionEnu) > std::cos(3.0 * M_PI / 180.0))
            continue;
        SkyProbe p;
        p.x = x;
        p.y = y;
        p.radiance = sampleSkyViewCpu(ref, lut, glm::vec3(d), float(R + cam.eye.altitudeM));
        probes.push_back(p);
    }
    return probes;
}

}  // namespace sky::testscenes

namespace sky::testscenes
{

glm::dvec3 pixelRayEnu(const CameraFrame& cam, const ViewRequest& view, double xPx, double yPx)
{
    const double tanHalf = std::tan(view.fovYDeg * M_PI / 360.0);
    const double aspect = double(view.width) / double(view.height);
    const double nx = xPx / double(view.width) * 2.0 - 1.0, ny = yPx / double(view.height) * 2.0 - 1.0;
    return glm::normalize(cam.forwardEnu + nx * tanHalf * aspect * cam.rightEnu - ny * tanHalf * cam.upEnu);
}

CloudCentroid cloudCentroid(const RenderResult& r, float minAlpha)
{
    CloudCentroid c;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x)
        {
            const float alpha = glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]);
            if (!(alpha > minAlpha))
                continue;
            ++c.pixels;
            c.weight += double(alpha);
            c.xPx += double(alpha) * (x + 0.5);
            c.yPx += double(alpha) * (y + 0.5);
        }
    if (c.weight > 0.0)
    {
        c.xPx /= c.weight;
        c.yPx /= c.weight;
    }
    return c;
}

double maxCloudAngleDeg(const RenderResult& r, const CameraFrame& cam, const ViewRequest& view,
                        const glm::dvec3& directionEnu, float minAlpha, double limitDeg, uint32_t& beyondLimit)
{
    const glm::dvec3 target = glm::normalize(directionEnu);
    double maxDeg = 0;
    beyondLimit = 0;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x)
        {
            const float alpha = glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]);
            if (!(alpha > minAlpha))
                continue;
            const glm::dvec3 ray = pixelRayEnu(cam, view, x + 0.5, y + 0.5);
            const double deg = std::acos(std::clamp(glm::dot(ray, target), -1.0, 1.0)) * 180.0 / M_PI;
            maxDeg = std::max(maxDeg, deg);
            if (deg > limitDeg)
                ++beyondLimit;
        }
    return maxDeg;
}

}  // namespace sky::testscenes

namespace sky::testscenes
{

WeatherSnapshot highLayer(float coverage, CloudType type, float altitudeM)
{
    WeatherSnapshot w = clearSky();
    size_t n = w.grid.cellCount();
    w.high.coverage.assign(n, coverage);
    w.high.altitudeM.assign(n, altitudeM);
    w.high.type.assign(n, uint8_t(type));
    w.high.windEastMS.assign(n, 20.0f);
    w.high.windNorthMS.assign(n, 0.0f);
    return w;
}

}  // namespace sky::testscenes

namespace sky::testscenes
{

QualitySettings reprojectedQuality()
{
    QualitySettings q = testQuality();
    q.reprojected = true;
    return q;
}

WeatherSnapshot deckBelowWeather() { return uniformLayer(0.8f, CloudType::Stratocumulus, 900.0f, 1900.0f); }

ViewRequest deckFromAboveView()
{
    ViewRequest v = lookUp(45.0, 7.0, 4000.0, -45.0, "2026-06-21T12:00:00Z");
    v.width = 160;
    v.height = 90;
    v.unixTimeS = timeOfSunElevation(45.0, 7.0, "2026-06-21T12:00:00Z", 30.0);
    return v;
}

WeatherSnapshot reprojectionWeather() { return uniformLayer(0.4f, CloudType::Cumulus, 1200.0f, 3000.0f); }

ViewRequest reprojectionView()
{
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 12.0, "2026-06-21T12:00:00Z");
    v.width = 128;
    v.height = 72;
    return v;
}

}  // namespace sky::testscenes
