// SPDX-License-Identifier: MIT
#include "skyservice/render/shadow_map.h"

#include "skyservice/render/frame_timestamps.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstddef>
#include <cstring>

static_assert(sizeof(ShadowMapPush) == 3 * 16, "ShadowMapPush must stay 3 vec4");
static_assert(offsetof(ShadowMapPush, grid) == 16, "ShadowMapPush.grid moved");
static_assert(offsetof(ShadowMapPush, params) == 32, "ShadowMapPush.params moved");

namespace sky
{
namespace
{

nlohmann::json latLonJson(const ShadowMapGeometry& g, double eastM, double northM)
{
    double lat = 0, lon = 0;
    g.toLatLon(glm::dvec2(eastM, northM), lat, lon);
    return {{"latDeg", lat}, {"lonDeg", lon}, {"eastingM", eastM}, {"northingM", northM}};
}

nlohmann::json directionJson(const CelestialPosition& body)
{
    const glm::dvec3& d = body.directionEnu;
    return {{"directionEnu", {d.x, d.y, d.z}}, {"azimuthDeg", body.azimuthDeg}, {"elevationDeg", body.elevationDeg}};
}

// The highest cloud whose shadow the map holds (anvils and cirrus stay below): its shadow moves the most
// when the light turns.
constexpr double kHighestShadowCasterM = 20000.0;

/// Where the shadow of a cloud kHighestShadowCasterM up falls, relative to the point below it (metres, ENU).
glm::dvec2 shadowOffsetM(const glm::dvec3& lightEnu)
{
    return -kHighestShadowCasterM * glm::dvec2(lightEnu.x, lightEnu.y) / std::max(lightEnu.z, 0.05);
}

ShadowMapDrawing drawingFor(const ShadowMapInputs& in, const ViewRequest& request, const QualitySettings& quality,
                            const CameraFrame& camera, const SunMoon& sunMoon)
{
    ShadowMapDrawing d;
    d.valid = true;
    d.sizeTexels = request.shadowMapSize;
    d.extentM = request.shadowMapExtentM;
    d.quality = quality;
    d.tuning = in.tuning;
    d.weatherVersion = in.weatherVersion;
    d.weatherValidTimeUnixS = in.weatherValidTimeUnixS;
    d.window = in.window;
    d.unixTimeS = request.unixTimeS;
    d.eyeEcefM = camera.eyeEcefM;
    d.lightIsMoon = moonIsKeyLight(sunMoon);
    d.lightEnu = d.lightIsMoon ? sunMoon.moon.directionEnu : sunMoon.sun.directionEnu;
    return d;
}

/// True when `last` may stand for `next` (ShadowMapDrawing says when).
bool sameMap(const ShadowMapDrawing& last, const ShadowMapDrawing& next)
{
    if (!last.valid || last.sizeTexels != next.sizeTexels || last.extentM != next.extentM ||
        !(last.quality == next.quality) || !(last.tuning == next.tuning) || last.weatherVersion != next.weatherVersion ||
        last.weatherValidTimeUnixS != next.weatherValidTimeUnixS || last.window != next.window || last.unixTimeS != next.unixTimeS || last.lightIsMoon != next.lightIsMoon)
        return false;
    const double texelM = next.extentM / double(next.sizeTexels);
    const double shadowShiftM = glm::length(shadowOffsetM(next.lightEnu) - shadowOffsetM(last.lightEnu));
    return shadowShiftM < 0.5 * texelM && glm::length(next.eyeEcefM - last.eyeEcefM) < next.extentM / 64.0;
}

}  // namespace

glm::dvec2 ShadowMapGeometry::planePositionM(double column, double row) const
{
    double half = 0.5 * extentM;
    return glm::dvec2(column * texelSizeM() - half, half - row * texelSizeM());
}

void ShadowMapGeometry::toLatLon(const glm::dvec2& eastNorthM, double& latDeg, double& lonDeg) const
{
    const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
    double azi = 0, rk = 0;
    projection.Reverse(centreLatDeg, centreLonDeg, eastNorthM.x, eastNorthM.y, latDeg, lonDeg, azi, rk);
}

glm::dvec2 ShadowMapGeometry::fromLatLon(double latDeg, double lonDeg) const
{
    const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
    double x = 0, y = 0, azi = 0, rk = 0;
    projection.Forward(centreLatDeg, centreLonDeg, latDeg, lonDeg, x, y, azi, rk);
    return glm::dvec2(x, y);
}

bool moonIsKeyLight(const SunMoon& sunMoon) { return sunMoon.sun.directionEnu.z < -0.07; }

bool validateShadowMapRequest(const ViewRequest& request, const QualitySettings& quality, std::string& error)
{
    if (!request.shadowMap)
        return true;
    if (request.shadowMapSize < 8 || request.shadowMapSize > 8192)
    {
        error = "shadow map size " + std::to_string(request.shadowMapSize) + " outside 8..8192 texels";
        return false;
    }
    double maxExtentM = 2.0 * quality.windowHalfExtentM;
    if (!(request.shadowMapExtentM >= 100.0 && request.shadowMapExtentM <= maxExtentM))
    {
        error = "shadow map extent " + std::to_string(request.shadowMapExtentM) + " m outside 100.." +
                std::to_string(maxExtentM) + " m (the weather window must cover it)";
        return false;
    }
    if (quality.shadowSteps < 1 || quality.shadowSteps > 1024)
    {
        error = "shadow map steps " + std::to_string(quality.shadowSteps) + " outside 1..1024";
        return false;
    }
    return true;
}

nlohmann::json shadowMapMetadata(const ShadowMapGeometry& g, const SunMoon& sunMoon, double earthRadiusM,
                                 int64_t unixTimeS, int64_t weatherValidTimeUnixS)
{
    double half = 0.5 * g.extentM;
    bool moon = moonIsKeyLight(sunMoon);
    nlohmann::json j;
    j["projection"] = "azimuthal equidistant centred on the eye, on the local osculating sphere (radius "
                      "earthRadiusM) at altitude 0; plane to lat/lon by GeographicLib::AzimuthalEquidistant "
                      "on WGS84 (geodesic distance and azimuth from the centre), as the weather window";
    j["centre"] = {{"latDeg", g.centreLatDeg}, {"lonDeg", g.centreLonDeg}};
    j["sizeTexels"] = g.sizeTexels;
    j["extentM"] = g.extentM;
    j["texelSizeM"] = g.texelSizeM();
    j["earthRadiusM"] = earthRadiusM;
    j["texelConvention"] = "column i from the west edge, row j from the north edge (top row first); the centre "
                           "of texel (i, j) is at easting (i + 0.5) * texelSizeM - extentM / 2, northing "
                           "extentM / 2 - (j + 0.5) * texelSizeM";
    j["corners"] = {{"northWest", latLonJson(g, -half, half)},
                    {"northEast", latLonJson(g, half, half)},
                    {"southEast", latLonJson(g, half, -half)},
                    {"southWest", latLonJson(g, -half, -half)}};
    j["cornersAre"] = "outer corners of the grid (texel edges), not texel centres";
    j["sun"] = directionJson(sunMoon.sun);
    j["keyLight"] = moon ? "moon" : "sun";
    j["keyLightDirection"] = directionJson(moon ? sunMoon.moon : sunMoon.sun);
    j["directionFrame"] = "unit vector east, north, up at the centre; elevation geometric (no refraction)";
    j["validTime"] = formatIso8601Utc(unixTimeS);
    j["weatherValidTime"] = formatIso8601Utc(weatherValidTimeUnixS);
    j["values"] = "transmittance of the key light through every cloud layer (volumetric and cirrus), 1 = clear, "
                  "0 = full shadow or the light below the local horizon";
    return j;
}

SkyStatus createShadowMapPass(const Context& ctx, ShadowMapPass& pass)
{
    return createProgram(ctx, pass.program, "shadow_map");
}

void destroyShadowMapPass(const Context& ctx, MemoryTracker& memory, ShadowMapPass& pass)
{
    destroyImage(ctx, memory, pass.image);
    destroyImage(ctx, memory, pass.transmittance);
    destroyProgram(ctx, pass.program);
}

SkyStatus ensureShadowMapImages(ShadowMapPass& pass, ImageChanges& changes, uint32_t size)
{
    if (hasSize(pass.image, size, size))
        return SkyStatus::success();
    ImageDesc d;
    d.width = d.height = size;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    SKY_TRY(makeImage(changes, pass.image, d, "cloud shadow map"));
    d.format = VK_FORMAT_R32_SFLOAT;
    return makeImage(changes, pass.transmittance, d, "cloud shadow map transmittance (float)");
}

namespace
{

void drawShadowMap(const PassFrame& f, FrameContext& frame, const ShadowMapPass& pass, const ShadowMapInputs& in,
                   const ViewRequest& request, const QualitySettings& quality, const CameraFrame& camera,
                   const SunMoon& sunMoon, ShadowMapDrawing& drawing)
{
    const uint32_t size = request.shadowMapSize;
    ShadowMapGeometry g;
    g.centreLatDeg = camera.eye.latDeg;
    g.centreLonDeg = camera.eye.lonDeg;
    g.sizeTexels = size;
    g.extentM = request.shadowMapExtentM;

    ShadowMapPush push;
    std::memset(&push, 0, sizeof push);
    const glm::dvec3& light = moonIsKeyLight(sunMoon) ? sunMoon.moon.directionEnu : sunMoon.sun.directionEnu;
    push.lightDirection = vec4(float(light.x), float(light.y), float(light.z), 0.0f);
    push.grid = vec4(float(g.texelSizeM()), float(0.5 * g.extentM), 0.0f, 0.0f);
    push.params = uvec4(size, quality.shadowSteps, 0u, 0u);

    VkCommandBuffer cmd = f.cmd;
    const Samplers& s = f.samplers;
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, frame.timestamps, kTsShadowBegin);
    dispatch(f.ctx, cmd, pass.program, size, size, 1, push,
             {DescriptorInfo(f.frameUniforms), DescriptorInfo(in.weatherWindow, s.linearClamp),
              DescriptorInfo(in.noise.base, s.linearRepeat), DescriptorInfo(in.noise.detail, s.linearRepeat),
              DescriptorInfo(in.noise.curl, s.linearRepeat), DescriptorInfo(pass.image)});
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsShadowEnd);
    {
        // The transmittance as the float texels readers want, converted on the GPU: a same-size NEAREST
        // blit of the red channel is an exact half -> float conversion.
        VkImageBlit blit = {};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.dstSubresource = blit.srcSubresource;
        blit.srcOffsets[1] = {int32_t(size), int32_t(size), 1};
        blit.dstOffsets[1] = blit.srcOffsets[1];
        const Image& source = pass.image;
        const Image& target = pass.transmittance;
        transitionImage(cmd, source, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        transitionImage(cmd, target, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        vkCmdBlitImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target.image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        transitionImage(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        transitionImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    }
    drawing.metadata = shadowMapMetadata(g, sunMoon, camera.localEarthRadiusM, request.unixTimeS,
                                         in.weatherValidTimeUnixS);
    ShadowMapReference& ref = drawing.reference;
    ref.centreLatDeg = g.centreLatDeg;
    ref.centreLonDeg = g.centreLonDeg;
    ref.extentM = g.extentM;
    const double half = 0.5 * g.extentM;
    const glm::dvec2 corners[4] = {{-half, half}, {half, half}, {half, -half}, {-half, -half}};  // NW NE SE SW
    for (int i = 0; i < 4; ++i)
        g.toLatLon(corners[i], ref.cornerLatDeg[i], ref.cornerLonDeg[i]);
    ref.keyLightIsMoon = moonIsKeyLight(sunMoon);
    const CelestialPosition& key = ref.keyLightIsMoon ? sunMoon.moon : sunMoon.sun;
    ref.keyLightAzimuthDeg = key.azimuthDeg;
    ref.keyLightElevationDeg = key.elevationDeg;
}

}  // namespace

void recordShadowMap(const PassFrame& f, FrameContext& frame, ShadowMapPass& pass, const ShadowMapInputs& in,
                     const ViewRequest& request, const QualitySettings& quality, const CameraFrame& camera,
                     const SunMoon& sunMoon, ShadowMapReadback& readback, RenderResult& facts)
{
    const uint32_t size = request.shadowMapSize;
    ShadowMapDrawing next = drawingFor(in, request, quality, camera, sunMoon);
    ShadowMapDrawing& drawn = pass.drawn;
    const ReadbackRegion reserved = readback.transmittance;
    readback = ShadowMapReadback{};
    readback.recorded = true;
    readback.redrawn = !sameMap(drawn, next);
    if (readback.redrawn)
    {
        next.id = drawn.id + 1;
        drawShadowMap(f, frame, pass, in, request, quality, camera, sunMoon, next);
        drawn = std::move(next);
    }
    if (request.copyToHost)
    {
        // A reused map is copied once into each frame context's buffer, not every frame (4 MiB at 1024²).
        readback.transmittance = reserved;
        const bool held = frame.shadowMapIdHeld == drawn.id && frame.shadowMapHeldOffset == reserved.offset;
        if (!held)
        {
            queueImageReadback(frame, pass.transmittance, reserved);
            ++pass.transmittanceCopies;
            frame.shadowMapIdHeld = drawn.id;
            frame.shadowMapHeldOffset = reserved.offset;
        }
        if ((request.readback & kReadShadowDetail) != 0)
            readback.detail = addImageReadback(frame, pass.image);
    }
    facts.shadowMapSize = size;
    facts.shadowMap = drawn.metadata;
    facts.shadowReference = drawn.reference;
    facts.shadowMapId = drawn.id;
    facts.shadowMapRedrawn = readback.redrawn;
}

ReadbackRegion reserveShadowMapReadback(const ShadowMapPass& pass, FrameContext& frame, const ViewRequest& request)
{
    return request.copyToHost ? reserveImageReadback(frame, pass.transmittance) : ReadbackRegion{};
}

void collectShadowMap(const Context& ctx, const FrameContext& frame, const ShadowMapReadback& readback,
                      RenderResult& result)
{
    if (!readback.recorded)
        return;
    uint64_t ts[2] = {0, 0};
    if (!readback.redrawn)
        result.gpuMs["shadowMap"] = 0.0;
    else if (ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(ctx.device, frame.timestamps, kTsShadowBegin, 2, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
        result.gpuMs["shadowMap"] = double(ts[1] - ts[0]) * ctx.timestampPeriodNs * 1e-6;
    const uint8_t* mapped = static_cast<const uint8_t*>(frame.readback.mapped);
    result.shadowTransmittance.resize(size_t(readback.transmittance.bytes) / sizeof(float));
    if (readback.transmittance.bytes > 0)
        std::memcpy(result.shadowTransmittance.data(), mapped + readback.transmittance.offset,
                    readback.transmittance.bytes);
    result.shadowOpticalDepth.clear();
    if (readback.detail.bytes > 0)
    {
        const size_t texels = size_t(readback.detail.bytes) / 8;
        std::vector<uint16_t> halves(texels * 4);
        std::memcpy(halves.data(), mapped + readback.detail.offset, readback.detail.bytes);
        result.shadowOpticalDepth.resize(texels);
        for (size_t i = 0; i < texels; ++i)
            result.shadowOpticalDepth[i] = glm::unpackHalf1x16(halves[i * 4 + 1]);
    }
}

}  // namespace sky
