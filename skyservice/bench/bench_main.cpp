// SPDX-License-Identifier: MIT
// sky-bench: GPU time per pass and wall time per frame of the benchmark scenes (BENCHMARKS.md).
//
//   sky-bench --scene all --width 1920 --height 1080 --frames 100 --warmup 10 --json bench.json
//
// Each scene is rendered `warmup` times untimed (pipeline caches, clocks), then `frames` times with
// GPU timestamps per pass and the wall time of the renderView call, without reading the images back;
// then once more with the readback, to check the picture (finite values, cloud share) and optionally
// to tile it on a contact sheet.
//
// --gpu-frames K runs the renderer's accumulation loop: one CPU setup, then K GPU frames back to back
// (each with new jitter), and a sample is their mean GPU time. It exists because renderView prepares
// every frame on the CPU: with one GPU frame per call the GPU idles most of
// the time and its clock governor drops the SM clock, which inflates GPU timestamps
// several times over. Back-to-back frames keep the clock up, as a real-time loop would. Exit codes: 0 ok, 1 runtime failure (Vulkan, files, validation
// messages), 2 bad command line.
//
// --mode reprojected times the temporal reprojection loop (skyservice/render/reprojection.h): each call
// marches one pixel of every 4x4 block ("march"; 2x2 or every pixel near or inside a cloud layer, the
// JSON's marchBlockPx) and rebuilds the full image from the previous call's ("reconstruct"). The camera
// is still, as in full mode, unless --speed V flies it along its heading (V/60 m per frame: the CPU
// setup then shows what a moving eye costs); setWeather drops the history per scene.
#include "skyservice/bench/bench_report.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/output/image_files.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/ephemeris.h"

#include <CLI/CLI.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <chrono>
#include <cmath>
#include <ctime>
#include <glm/gtc/packing.hpp>

namespace sky
{
namespace
{

constexpr int kExitOk = 0, kExitRuntime = 1, kExitUsage = 2;
// Contact-sheet tiles are shrunk to at most this width so that a sheet of eight 1080p views stays
// far below the 16 MiB a returned file may have on the device machine.
constexpr uint32_t kSheetTileMaxWidthPx = 640;

struct BenchOptions
{
    std::string scene = "all";
    uint32_t width = 1920, height = 1080;
    uint32_t frames = 100, warmup = 10;
    std::string mode = "full";
    std::string json;
    std::string sheet;
    std::string device;
    bool validate = false;
    uint32_t steps = 0;
    double lightLodM = -1;  ///< < 0: the renderer's default
    int lightSamples = -1;  ///< < 0: the renderer's default
    int fullConeSamples = -1;
    double lightVolumeTexelM = -1;  ///< < 0: the renderer's default; 0: no light volume
    int64_t lightVolumeMinRays = -1;  ///< < 0: the renderer's default
    double detailMinTransmittance = -1;  ///< < 0: the renderer's default
    double deepStepFactor = -1;          ///< < 0: the renderer's default
    double maxStepOpticalDepth = -1;     ///< < 0: the renderer's default
    int64_t insideCloudBlockPx = 0;      ///< 0: the renderer's default
    double detailFadeStartM = -1, detailFadeEndM = -1;
    bool noDetail = false;
    bool noSkipping = false;
    bool noCostOrder = false;
    bool lookupTotals = false;
    double coneTailReuseM = -1;  ///< < 0: the renderer's default
    double coneTailReuseBeyondM = -1;  ///< < 0: the renderer's default
    double deepLightReuseM = -1;       ///< < 0: the renderer's default
    double coneNearMergeBeyondM = -1;  ///< < 0: the renderer's default
    int64_t octaves = -1;              ///< < 0: the renderer's default
    bool noFarLightVolume = false;
    uint32_t gpuFrames = 1;
    bool shadowMap = false;
    double speedMps = 0;  ///< the eye flies along its heading at this speed, one frame per 1/60 s
};

std::string utcClock()
{
    auto now = std::chrono::system_clock::now();
    std::time_t t = std::chrono::system_clock::to_time_t(now);
    std::tm tm = {};
    gmtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%H:%M:%S", &tm);
    auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
    return std::string(text) + "." + std::to_string(1000 + ms).substr(1);
}

// The settings and the experiment knobs, in one object (the report's "quality", as before they were split).
nlohmann::json qualityJson(const QualitySettings& q, const RenderTuning& t)
{
    return {{"maxViewSteps", q.maxViewSteps}, {"lightSamples", q.lightSamples}, {"octaves", q.octaves},
            {"detail", q.detail},             {"highCloud", q.highCloud},       {"maxDistanceM", q.maxDistanceM},
            {"gpuFramesPerCall", q.accumulationFrames}, {"baseNoisePeriodM", q.baseNoisePeriodM},
            {"detailNoisePeriodM", q.detailNoisePeriodM}, {"extinctionPerM", q.extinctionPerM},
            {"coneStepM", q.coneStepM}, {"lightLodDistanceM", t.lightLodDistanceM},
            {"fullConeSamples", q.fullConeSamples}, {"detailFadeStartM", t.detailFadeStartM},
            {"detailFadeEndM", t.detailFadeEndM}, {"lightVolumeTexelM", q.lightVolumeTexelM},
            {"lightVolumeMinRays", q.lightVolumeMinRays}, {"detailMinTransmittance", t.detailMinTransmittance},
            {"deepStepFactor", t.deepStepFactor}, {"maxStepOpticalDepth", t.maxStepOpticalDepth},
            {"insideCloudBlockPx", t.insideCloudBlockPx}, {"emptySpaceSkipping", t.emptySpaceSkipping},
            {"lightVolumeFarCascade", t.lightVolumeFarCascade}, {"coneTailReuseM", t.coneTailReuseM},
            {"coneTailReuseBeyondM", t.coneTailReuseBeyondM}, {"deepLightReuseM", t.deepLightReuseM},
            {"coneNearMergeBeyondM", t.coneNearMergeBeyondM}, {"marchLookupTotals", t.marchLookupTotals}};
}

// Box-filters an image down by an integer factor (contact sheet tiles only).
ImageRgba8 shrink(const std::vector<uint8_t>& rgba, uint32_t width, uint32_t height)
{
    uint32_t f = (width + kSheetTileMaxWidthPx - 1) / kSheetTileMaxWidthPx;
    ImageRgba8 out;
    out.width = width / f;
    out.height = height / f;
    out.pixels.resize(size_t(out.width) * out.height * 4);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x)
            for (uint32_t c = 0; c < 4; ++c)
            {
                uint32_t sum = 0;
                for (uint32_t dy = 0; dy < f; ++dy)
                    for (uint32_t dx = 0; dx < f; ++dx)
                        sum += rgba[((size_t(y * f + dy) * width) + x * f + dx) * 4 + c];
                out.pixel(x, y)[c] = uint8_t(sum / (f * f));
            }
    return out;
}

void checkPicture(const RenderResult& result, BenchSceneResult& out)
{
    size_t pixels = size_t(result.width) * result.height, cloud = 0, anyCloud = 0;
    for (size_t i = 0; i < pixels * 4; ++i)
    {
        float c = glm::unpackHalf1x16(result.cloudRgbaHalf[i]);
        float lin = result.linearRgbaHalf.empty() ? 0.0f : glm::unpackHalf1x16(result.linearRgbaHalf[i]);
        if (!std::isfinite(c) || !std::isfinite(lin) || c < 0.0f || lin < 0.0f)
            out.allFinite = false;
        if (i % 4 == 3 && c > 0.5f)
            ++cloud;
        if (i % 4 == 3 && c > 0.0f)
            ++anyCloud;
    }
    out.cloudFraction = pixels ? double(cloud) / double(pixels) : 0.0;
    out.anyCloudFraction = pixels ? double(anyCloud) / double(pixels) : 0.0;
}

SkyStatus runScene(Renderer& r, const BenchOptions& o, const BenchScene& scene, const QualitySettings& quality,
                   BenchSceneResult& out, std::vector<ImageRgba8>& tiles)
{
    ViewRequest request;
    request.pose = scene.pose;
    request.fovYDeg = scene.fovYDeg;
    request.width = o.width;
    request.height = o.height;
    request.shadowMap = o.shadowMap;
    request.copyToHost = false;  // no readback while timed
    // No linear frame: an image generator reads the display image (the service makes the linear one only
    // for EXR files), and the memory report is then what such a frame holds. The picture check reads the
    // cloud radiance only.
    request.linearOutput = false;
    std::string error;
    if (!parseIso8601Utc(scene.timeIso, request.unixTimeS, error))
        return SkyStatus::failure(scene.name + ": " + error, VK_ERROR_INITIALIZATION_FAILED);
    setWeather(r, makeBenchWeather(scene, request.unixTimeS));

    out.scene = scene;
    RenderResult result;
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    for (uint32_t i = 0; i < o.warmup + o.frames; ++i)
    {
        if (o.speedMps > 0 && i > 0)  // one 60 Hz frame of flight along the heading
            geodesic.Direct(request.pose.latDeg, request.pose.lonDeg, request.pose.headingDeg, o.speedMps / 60.0,
                            request.pose.latDeg, request.pose.lonDeg);
        auto start = std::chrono::steady_clock::now();
        SKY_TRY(renderView(r, request, quality, result));
        double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (i < o.warmup)
            continue;
        for (const auto& [pass, ms] : result.gpuMs)
            out.gpuMs[pass].push_back(ms);
        out.wallMs.push_back(wallMs);
        out.cpuSetupMs.push_back(result.cpuSetupMs);
    }
    QualitySettings checked = quality;
    checked.accumulationFrames = 1;
    request.copyToHost = true;
    SKY_TRY(renderView(r, request, checked, result));
    out.sunElevationDeg = result.sunElevationDeg;
    out.marchBlockPx = result.marchBlockPx;
    out.marchBlockReason = result.marchBlockReason;
    out.marchRowLookups = result.marchRowLookups;
    checkPicture(result, out);
    if (!o.sheet.empty())
        tiles.push_back(shrink(result.displayRgba8, result.width, result.height));
    return SkyStatus::success();
}

void fillDevice(const Renderer& r, BenchRun& run)
{
    const VkPhysicalDeviceProperties& p = r.ctx.properties;
    run.deviceName = r.ctx.deviceName;
    run.driver = r.ctx.driverInfo;
    run.apiVersion = p.apiVersion;
    run.timestampPeriodNs = r.ctx.timestampPeriodNs;
    for (const Program* program : {&r.march.program, &r.reconstruct.program, &r.composite.program, &r.lightVolume.program})
        if (!program->statistics.empty())
            run.pipelineStatistics[program->name] = program->statistics;
    switch (p.deviceType)
    {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: run.deviceType = "discrete"; break;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: run.deviceType = "integrated"; break;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: run.deviceType = "virtual"; break;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: run.deviceType = "cpu"; break;
    default: run.deviceType = "other"; break;
    }
}

// The shipped settings with the command line's overrides (the requests copy nothing back while timed:
// runScene).
QualitySettings benchQuality(const BenchOptions& o)
{
    QualitySettings quality;
    quality.accumulationFrames = o.gpuFrames;
    // Reprojected: every call is one frame of the temporal loop (march 1/16, reconstruct, composite),
    // reusing the previous call's image; --gpu-frames does not apply (a frame needs the one before).
    quality.reprojected = o.mode == "reprojected";
    if (quality.reprojected)
        quality.accumulationFrames = 1;
    if (o.steps > 0)
        quality.maxViewSteps = o.steps;
    if (o.lightSamples >= 0)
        quality.lightSamples = uint32_t(o.lightSamples);
    if (o.noDetail)
        quality.detail = false;
    if (o.octaves >= 0)
        quality.octaves = uint32_t(o.octaves);
    if (o.fullConeSamples >= 0)
        quality.fullConeSamples = uint32_t(o.fullConeSamples);
    if (o.lightVolumeTexelM >= 0)
        quality.lightVolumeTexelM = o.lightVolumeTexelM;
    if (o.lightVolumeMinRays >= 0)
        quality.lightVolumeMinRays = uint32_t(o.lightVolumeMinRays);
    return quality;
}

// The experiment knobs (render_tuning.h) with the command line's overrides.
RenderTuning benchTuning(const BenchOptions& o)
{
    RenderTuning tuning;
    if (o.lightLodM >= 0)
        tuning.lightLodDistanceM = o.lightLodM;
    if (o.noCostOrder)
        tuning.costOrderedMarch = false;
    if (o.lookupTotals)
        tuning.marchLookupTotals = true;
    if (o.coneTailReuseM >= 0)
        tuning.coneTailReuseM = o.coneTailReuseM;
    if (o.coneTailReuseBeyondM >= 0)
        tuning.coneTailReuseBeyondM = o.coneTailReuseBeyondM;
    if (o.deepLightReuseM >= 0)
        tuning.deepLightReuseM = o.deepLightReuseM;
    if (o.coneNearMergeBeyondM >= 0)
        tuning.coneNearMergeBeyondM = o.coneNearMergeBeyondM;
    if (o.noSkipping)
        tuning.emptySpaceSkipping = false;
    if (o.noFarLightVolume)
        tuning.lightVolumeFarCascade = false;
    if (o.detailMinTransmittance >= 0)
        tuning.detailMinTransmittance = o.detailMinTransmittance;
    if (o.deepStepFactor >= 0)
        tuning.deepStepFactor = o.deepStepFactor;
    if (o.maxStepOpticalDepth >= 0)
        tuning.maxStepOpticalDepth = o.maxStepOpticalDepth;
    if (o.insideCloudBlockPx > 0)
        tuning.insideCloudBlockPx = uint32_t(o.insideCloudBlockPx);
    if (o.detailFadeStartM >= 0)
        tuning.detailFadeStartM = o.detailFadeStartM;
    if (o.detailFadeEndM >= 0)
        tuning.detailFadeEndM = o.detailFadeEndM;
    return tuning;
}

// Runs the scenes in order, stopping at the first that fails; each adds its result, its contact-sheet
// caption and (with --sheet) its tile.
SkyStatus runScenes(Renderer& r, const BenchOptions& o, const std::vector<BenchScene>& scenes,
                    const QualitySettings& quality, BenchRun& run, std::vector<ImageRgba8>& tiles,
                    std::vector<std::string>& captions)
{
    SkyStatus status = SkyStatus::success();
    for (size_t i = 0; status.ok() && i < scenes.size(); ++i)
    {
        auto start = std::chrono::steady_clock::now();
        std::string startUtc = utcClock();
        run.scenes.emplace_back();
        status = runScene(r, o, scenes[i], quality, run.scenes.back(), tiles);
        captions.push_back(scenes[i].name);
        // UTC start and end, to line up with an external clock log (nvidia-smi --query-gpu=timestamp,...).
        std::fprintf(stderr, "sky-bench: %-19s %ux%u done in %.1f s (UTC %s..%s)\n", scenes[i].name.c_str(), o.width,
                     o.height, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                     startUtc.c_str(), utcClock().c_str());
    }
    return status;
}

// The memory report and the run's settings, for the table and the JSON.
void recordRunSettings(Renderer& r, const BenchOptions& o, const QualitySettings& quality, const RenderTuning& tuning,
                       BenchRun& run)
{
    {
        std::lock_guard<std::mutex> lock(r.memory.mutex);
        run.memory.liveBytes.insert(r.memory.liveBytes.begin(), r.memory.liveBytes.end());
        run.memory.totalBytes = r.memory.totalBytes;
        run.memory.peakBytes = r.memory.peakBytes;
    }
    run.width = o.width;
    run.height = o.height;
    run.frames = o.frames;
    run.warmup = o.warmup;
    run.gpuFramesPerCall = o.gpuFrames;
    run.mode = o.mode;
    run.speedMps = o.speedMps;
    run.quality = qualityJson(quality, tuning);
}

// Writes --json, then --sheet; the exit code, with the message printed on failure.
int writeBenchFiles(const BenchOptions& o, const BenchRun& run, const std::vector<ImageRgba8>& tiles,
                    const std::vector<std::string>& captions)
{
    std::string error;
    int code = kExitOk;
    if (!o.json.empty() && !writeJsonAtomic(o.json, benchToJson(run), error))
        code = kExitRuntime;
    if (code == kExitOk && !o.sheet.empty() && !writePng(o.sheet, makeContactSheet(tiles, captions, 2), error))
        code = kExitRuntime;
    if (code != kExitOk)
        std::fprintf(stderr, "sky-bench: %s\n", error.c_str());
    return code;
}

int runBench(const BenchOptions& o)
{
    std::vector<BenchScene> scenes;
    std::string error;
    if (!selectBenchScenes(o.scene, scenes, error))
    {
        std::fprintf(stderr, "sky-bench: --scene %s: %s\n", o.scene.c_str(), error.c_str());
        return kExitUsage;
    }
    const QualitySettings quality = benchQuality(o);
    const RenderTuning tuning = benchTuning(o);

    Renderer r;
    RendererOptions ro;
    ro.context.deviceSelector = o.device;
    ro.context.validation = o.validate;
    ro.context.pipelineStatistics = true;
    SkyStatus status = createRenderer(r, ro);
    r.tuning = tuning;
    BenchRun run;
    std::vector<ImageRgba8> tiles;
    std::vector<std::string> captions;
    if (status.ok())
    {
        fillDevice(r, run);
        if (r.ctx.timestampPeriodNs <= 0)
            std::fprintf(stderr, "sky-bench: %s has no timestamps on its compute queue: GPU columns stay empty\n",
                         run.deviceName.c_str());
        status = runScenes(r, o, scenes, quality, run, tiles, captions);
    }
    if (!status.ok())
    {
        std::fprintf(stderr, "sky-bench: %s\n", status.message.c_str());
        destroyRenderer(r);
        return kExitRuntime;
    }
    recordRunSettings(r, o, quality, tuning, run);
    printBenchTable(stdout, run);

    int code = writeBenchFiles(o, run, tiles, captions);
    if (o.validate && r.ctx.validationMessages.load() > 0)
    {
        std::fprintf(stderr, "sky-bench: %u validation messages\n", r.ctx.validationMessages.load());
        code = kExitRuntime;
    }
    destroyRenderer(r);
    return code;
}

}  // namespace
}  // namespace sky

int main(int argc, char** argv)
{
    sky::BenchOptions o;
    CLI::App app{"sky-bench: GPU time per pass and wall time per frame of the benchmark scenes"};
    app.add_option("--scene", o.scene, "all, a scene name, or names separated by commas");
    app.add_option("--width", o.width, "Image width (pixels)")->check(CLI::Range(8, 8192));
    app.add_option("--height", o.height, "Image height (pixels)")->check(CLI::Range(8, 8192));
    app.add_option("--frames", o.frames, "Timed frames per scene")->check(CLI::Range(1, 100000));
    app.add_option("--warmup", o.warmup, "Untimed frames per scene before timing")->check(CLI::Range(0, 100000));
    app.add_option("--mode", o.mode, "full | reprojected (1/16 march + temporal reconstruction)")
        ->check(CLI::IsMember({"full", "reprojected"}));
    app.add_option("--json", o.json, "Write the results as JSON to this file");
    app.add_option("--sheet", o.sheet, "Write a contact sheet PNG of one frame per scene to this file");
    app.add_option("--device", o.device, "Vulkan device: index or part of its name (default: best GPU, else CPU)");
    app.add_flag("--validate", o.validate, "Enable the Vulkan validation layers (fail on any message)");
    app.add_option("--gpu-frames", o.gpuFrames,
                   "GPU frames per renderView call, back to back after one CPU setup; a sample is their mean")
        ->check(CLI::Range(1, 64));
    app.add_option("--speed", o.speedMps, "Fly the eye along its heading at this speed (m/s, 60 Hz frames; 0 = still)")
        ->check(CLI::Range(0.0, 3000.0));
    app.add_flag("--shadow-map", o.shadowMap, "Also render (and read back) the cloud shadow map every call");
    app.add_option("--steps", o.steps, "Maximum view samples per ray (default: the renderer's)")
        ->check(CLI::Range(8, 4096));
    // Knobs that take parts of the model away, to see what each costs (A/B timings; not for pictures).
    app.add_option("--light-samples", o.lightSamples, "Cone light samples (default: the renderer's; 0: none)")
        ->check(CLI::Range(0, 6));
    app.add_flag("--no-detail", o.noDetail, "Turn the detail erosion off");
    app.add_flag("--no-skipping", o.noSkipping, "Turn the march's empty-space skipping off (search every step)");
    app.add_flag("--lookup-totals", o.lookupTotals,
                 "The JSON's marchRowLookups sum every ray's march iterations (not the slowest per workgroup)");
    app.add_flag("--no-cost-order", o.noCostOrder,
                 "Launch the march's workgroup rows in the interleaved order, not costliest first");
    app.add_option("--cone-tail-reuse", o.coneTailReuseM,
                   "Lit samples within this distance (m) of the last full cone take its far samples (0: never)")
        ->check(CLI::Range(0.0, 5000.0));
    app.add_option("--cone-tail-reuse-beyond", o.coneTailReuseBeyondM,
                   "Only lit samples farther than this (m) take an earlier cone's far samples")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--deep-light-reuse", o.deepLightReuseM,
                   "Deep lit samples within this distance (m) of the last marched cone take its light (0: never)")
        ->check(CLI::Range(0.0, 5000.0));
    app.add_option("--octaves", o.octaves, "Multiple-scattering octaves (default: the renderer's)")
        ->check(CLI::Range(1, 8));
    app.add_option("--cone-near-merge-beyond", o.coneNearMergeBeyondM,
                   "Beyond this distance (m) a cone's detailed near samples are taken as one (0: never)")
        ->check(CLI::Range(0.0, 1e7));
    app.add_flag("--no-far-light-volume", o.noFarLightVolume, "No far cascade of the light volume");
    app.add_option("--full-cone-samples", o.fullConeSamples, "Cone samples that may take the detailed density")
        ->check(CLI::Range(0, 6));
    app.add_option("--light-volume-texel", o.lightVolumeTexelM,
                   "Light volume texel size (m; 0: no light volume, every cone sample marched)")
        ->check(CLI::Range(0.0, 5000.0));
    app.add_option("--light-volume-min-rays", o.lightVolumeMinRays,
                   "Frames marching fewer rays draw no light volume (default: the renderer's)")
        ->check(CLI::Range(int64_t(0), int64_t(4294967295)));
    app.add_option("--detail-min-transmittance", o.detailMinTransmittance,
                   "View samples behind a transmittance below this skip the detail erosion (0: never)")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--deep-step-factor", o.deepStepFactor,
                   "Those deep view samples step this many times further (1: the same)")
        ->check(CLI::Range(1.0, 8.0));
    app.add_option("--max-step-optical-depth", o.maxStepOpticalDepth,
                   "A step inside a cloud covers at most this optical depth (0: no limit)")
        ->check(CLI::Range(0.0, 100.0));
    app.add_option("--inside-cloud-block", o.insideCloudBlockPx,
                   "Reprojected, inside an overcast layer: march 1 pixel of every NxN block (default: the renderer's)")
        ->check(CLI::Range(int64_t(1), int64_t(2)));
    app.add_option("--detail-fade-start", o.detailFadeStartM, "Detail erosion fades out from this distance (m)")
        ->check(CLI::Range(0.0, 1e7));
    app.add_option("--detail-fade-end", o.detailFadeEndM, "... to this distance (m)")->check(CLI::Range(0.0, 1e7));
    app.add_option("--light-lod", o.lightLodM, "Light LOD distance (m): beyond it 3 cheap cone samples (0: off)")
        ->check(CLI::Range(0.0, 1e7));
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
        int code = app.exit(e);
        return code == 0 ? sky::kExitOk : sky::kExitUsage;
    }
    return sky::runBench(o);
}
