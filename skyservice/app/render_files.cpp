// SPDX-License-Identifier: MIT
#include "skyservice/app/render_files.h"

#include "skyservice/output/image_files.h"
#include "skyservice/sky/ephemeris.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

std::vector<float> unpackHalves(const std::vector<uint16_t>& halves)
{
    std::vector<float> out(halves.size());
    for (size_t i = 0; i < halves.size(); ++i)
        out[i] = glm::unpackHalf1x16(halves[i]);
    return out;
}

}  // namespace

nlohmann::json qualityToJson(const QualitySettings& q)
{
    return {{"maxViewSteps", q.maxViewSteps},
            {"lightSamples", q.lightSamples},
            {"octaves", q.octaves},
            {"extinctionPerM", q.extinctionPerM},
            {"detailErosion", q.detailErosion},
            {"ambientStrength", q.ambientStrength},
            {"powderStrength", q.powderStrength},
            {"phaseForwardG", q.phaseForwardG},
            {"phaseBackG", q.phaseBackG},
            {"baseNoisePeriodM", q.baseNoisePeriodM},
            {"detailNoisePeriodM", q.detailNoisePeriodM},
            {"windowHalfExtentM", q.windowHalfExtentM},
            {"maxDistanceM", q.maxDistanceM},
            {"noiseSeed", q.noiseSeed},
            {"detail", q.detail},
            {"highCloud", q.highCloud}};
}

bool writeShadowMapFiles(const std::string& prefix, const RenderResult& result, std::string& error)
{
    const uint32_t n = result.shadowMapSize;
    if (n == 0)
        return true;
    std::vector<ExrChannel> channels = {
        {"Y", ExrPixelType::Float, result.shadowTransmittance.data(), 1},
        {"opticalDepth", ExrPixelType::Float, result.shadowOpticalDepth.data(), 1},
    };
    if (!writeExr(prefix + "-shadow.exr", n, n, channels, error, {{"skyShadowMap", result.shadowMap.dump()}}))
        return false;
    ImageRgba8 png;
    png.width = png.height = n;
    png.pixels.resize(size_t(n) * n * 4);
    for (size_t i = 0; i < size_t(n) * n; ++i)
    {
        auto grey = uint8_t(std::lround(255.0f * std::clamp(result.shadowTransmittance[i], 0.0f, 1.0f)));
        png.pixels[i * 4 + 0] = png.pixels[i * 4 + 1] = png.pixels[i * 4 + 2] = grey;
        png.pixels[i * 4 + 3] = 255;
    }
    return writePng(prefix + "-shadow.png", png, error);
}

bool writeRenderFiles(const std::string& prefix, const ViewRequest& request, const RenderResult& result,
                      const RenderFacts& facts, std::string& error)
{
    ImageRgba8 png;
    png.width = result.width;
    png.height = result.height;
    png.pixels = result.displayRgba8;
    if (!writePng(prefix + ".png", png, error))
        return false;

    // The EXR needs the linear frame, which a render makes only when asked (ViewRequest::linearOutput).
    const bool exr = !result.linearRgbaHalf.empty();
    if (exr)
    {
        std::vector<float> cloud = unpackHalves(result.cloudRgbaHalf);
        std::vector<float> linear = unpackHalves(result.linearRgbaHalf);
        std::vector<ExrChannel> channels = {
            {"R", ExrPixelType::Half, cloud.data() + 0, 4},
            {"G", ExrPixelType::Half, cloud.data() + 1, 4},
            {"B", ExrPixelType::Half, cloud.data() + 2, 4},
            {"A", ExrPixelType::Half, cloud.data() + 3, 4},
            {"Z", ExrPixelType::Float, result.cloudDepthM.data(), 1},
            {"sky.R", ExrPixelType::Half, linear.data() + 0, 4},
            {"sky.G", ExrPixelType::Half, linear.data() + 1, 4},
            {"sky.B", ExrPixelType::Half, linear.data() + 2, 4},
        };
        // The depth layer's front (its weighted distance is Z), when the render drew it.
        if (result.depthLayerM.size() == result.cloudDepthM.size() * 2 && !result.cloudDepthM.empty())
            channels.push_back({"ZFront", ExrPixelType::Float, result.depthLayerM.data(), 2});
        if (!writeExr(prefix + ".exr", result.width, result.height, channels, error))
            return false;
    }

    nlohmann::json j;
    j["view"] = {{"lat", request.pose.latDeg},         {"lon", request.pose.lonDeg},
                 {"alt", request.pose.altitudeM},      {"heading", request.pose.headingDeg},
                 {"pitch", request.pose.pitchDeg},     {"roll", request.pose.rollDeg},
                 {"width", request.width},             {"height", request.height},
                 {"time", facts.timeIso}};
    j["units"] = {{"lat", "degrees"}, {"lon", "degrees"}, {"alt", "metres above the WGS84 ellipsoid"},
                  {"heading", "degrees clockwise from north"}, {"pitch", "degrees, + nose up"},
                  {"roll", "degrees, + right wing down"}};
    // The frustum as the socket API and the CLI take it: fov, or the four half-angles of an off-centre one.
    if (request.frustum.asymmetric)
    {
        const Frustum& f = request.frustum;
        j["view"].update({{"left", f.leftDeg}, {"right", f.rightDeg}, {"up", f.upDeg}, {"down", f.downDeg}});
        j["units"]["left"] = j["units"]["right"] = j["units"]["up"] = j["units"]["down"] =
            "degrees from the view axis to that image edge, + outwards";
    }
    else
    {
        j["view"]["fov"] = request.fovYDeg;
        j["units"]["fov"] = "vertical, degrees";
    }
    j["weather"] = facts.weatherSource;
    j["weatherValidTime"] = formatIso8601Utc(result.weatherValidTimeUnixS);  // of the snapshot drawn
    if (facts.weatherVersion != 0)
        j["weatherVersion"] = facts.weatherVersion;
    j["sun"] = {{"azimuthDeg", result.sunAzimuthDeg}, {"elevationDeg", result.sunElevationDeg}};
    j["moon"] = {{"azimuthDeg", result.moonAzimuthDeg},
                 {"elevationDeg", result.moonElevationDeg},
                 {"illuminatedFraction", result.moonIlluminatedFraction},
                 {"isKeyLight", result.moonIsKeyLight}};
    j["device"] = {{"name", facts.deviceName}, {"driver", facts.driver}};
    j["timingsMs"] = result.gpuMs;
    j["timingsMs"]["cpuSetup"] = result.cpuSetupMs;
    j["exposure"] = result.exposure;
    j["radianceUnits"] = "EXR values are pre-exposed: divide by `exposure` for W m^-2 sr^-1 nm^-1 at 680/550/440 nm";
    j["quality"] = facts.quality;
    if (!facts.caption.empty())
        j["caption"] = facts.caption;
    if (result.shadowMapSize > 0)
    {
        if (!writeShadowMapFiles(prefix, result, error))
            return false;
        j["shadowMap"] = result.shadowMap;
        j["shadowMap"]["files"] = {
            {"exr", "-shadow.exr: Y = transmittance (float), opticalDepth (float); header attribute skyShadowMap = "
                    "this metadata"},
            {"png", "-shadow.png: grey, 8-bit linear transmittance (255 = clear), not sRGB"}};
    }
    j["files"] = {{"png", "tone-mapped sRGB, sky and clouds"}};
    if (exr)
        j["files"]["exr"] = "R,G,B: premultiplied linear cloud radiance; A: 1 - cloud transmittance; Z: "
                            "transmittance-weighted cloud distance (m, 0 where A = 0); sky.R/G/B: final linear frame";
    return writeJsonAtomic(prefix + ".json", j, error);
}

}  // namespace sky
