// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_report.h"

namespace sky
{
namespace
{

// A clock from nvidia-smi as a JSON number, or the string "n/a".
nlohmann::json clockJson(const std::string& mhz)
{
    return mhz == "n/a" ? nlohmann::json("n/a") : nlohmann::json(std::stod(mhz));
}

double jsonNumberOr(const nlohmann::json& j, const char* key, double fallback)
{
    return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

nlohmann::json runJson(const ServiceRunResult& r)
{
    nlohmann::json latency =
        r.latencyMs.empty() ? nlohmann::json(nullptr) : benchSummaryJson(summarizeSamples(r.latencyMs));
    return {{"width", r.width},
            {"height", r.height},
            {"transport", r.transport},
            {"timelineSemaphore", r.timelineSemaphore},
            {"frames", r.frames},
            {"torn", r.torn},
            {"skipped", r.skipped},
            {"elapsedS", r.elapsedS},
            {"deliveredFps", r.deliveredFps},
            {"latencyMs", latency},
            {"intervalMs", benchSummaryJson(summarizeSamples(r.intervalMs))},
            {"daemon",
             {{"framesRendered", r.daemonFrames},
              {"cpuS", r.daemonCpuS},
              {"cpuMsPerFrame", r.daemonCpuMsPerFrame},
              {"frameMs", r.daemonFrameMs}}}};
}

} // namespace

nlohmann::json serviceBenchToJson(const ServiceBenchRun& run)
{
    nlohmann::json doc;
    doc["tool"] = "sky-service-bench";
    doc["formatVersion"] = 1;
    doc["device"] = {{"name", run.deviceName}, {"driver", run.driver}};
    doc["daemon"] = run.daemonBinary;
    doc["mode"] = run.renderRateHz > 0 ? "rate" : "request";
    doc["renderRateHz"] = run.renderRateHz;
    doc["eyeSpeedMps"] = run.renderRateHz > 0 ? 0.0 : run.speedMps;
    doc["frames"] = run.frames;
    doc["warmup"] = run.warmup;
    doc["shadowMapSize"] = run.shadowMapSize;
    doc["layers"] = run.layers;
    doc["quality"] = "medium";
    doc["reprojected"] = true;
    nlohmann::json scenes = nlohmann::json::array();
    for (const ServiceSceneResult& s : run.scenes)
    {
        nlohmann::json runs = nlohmann::json::array();
        for (const ServiceRunResult& r : s.runs)
            runs.push_back(runJson(r));
        const EyePose& p = s.scene.pose;
        scenes.push_back(
            {{"name", s.scene.name},
             {"description", s.scene.description},
             {"timeUtc", s.scene.timeIso},
             {"weather", s.scene.builtinWeather ? "builtin" : "synthetic"},
             {"view",
              {{"latDeg", p.latDeg},
               {"lonDeg", p.lonDeg},
               {"altitudeM", p.altitudeM},
               {"headingDeg", p.headingDeg},
               {"pitchDeg", p.pitchDeg},
               {"rollDeg", p.rollDeg},
               {"fovYDeg", s.scene.fovYDeg}}},
             {"smClockMhz", {{"start", clockJson(s.smClockStartMhz)}, {"end", clockJson(s.smClockEndMhz)}}},
             {"runs", runs}});
    }
    doc["scenes"] = scenes;
    return doc;
}

void printServiceBenchTable(std::FILE* out, const ServiceBenchRun& run)
{
    const bool rateMode = run.renderRateHz > 0;
    std::string layers;
    for (const std::string& l : run.layers)
        layers += (layers.empty() ? "" : ",") + l;
    std::fprintf(out,
                 "sky-service-bench: %s | %s | quality medium, reprojected | layers %s | %u frames after %u warm-up\n",
                 run.deviceName.c_str(), run.driver.c_str(), layers.c_str(), run.frames, run.warmup);
    if (rateMode)
        std::fprintf(out,
                     "the daemon renders at %.0f Hz; the client only waits (wait_frame, acquire, release); "
                     "interval = between frames in hand (median/p95/p99)\n",
                     run.renderRateHz);
    else
        std::fprintf(out,
                     "per frame: set_view (eye at %.0f m/s, 60 Hz steps), request_frame, wait_frame, acquire, "
                     "read, release; latency = set_view -> frame in hand (median/p95/p99)\n",
                     run.speedMps);
    std::fprintf(out, "daemon cpu = its CPU time per frame rendered; frame_ms = its own status (median of its last "
                      "frames); SM clock at scene start/end\n");
    std::fprintf(out, "%-19s %10s %-9s %8s %23s %11s %9s %11s %11s\n", "scene", "size", "transport", "fps",
                 rateMode ? "interval ms" : "latency ms", "daemon cpu", "frame_ms", "torn/skip", "SM MHz");
    for (const ServiceSceneResult& s : run.scenes)
        for (const ServiceRunResult& r : s.runs)
        {
            char size[32], cpu[32], frameMs[32], lost[32], clock[32];
            std::snprintf(size, sizeof size, "%ux%u", r.width, r.height);
            if (r.daemonCpuMsPerFrame >= 0)
                std::snprintf(cpu, sizeof cpu, "%.2f", r.daemonCpuMsPerFrame);
            else
                std::snprintf(cpu, sizeof cpu, "n/a");
            std::snprintf(frameMs, sizeof frameMs, "%.2f", jsonNumberOr(r.daemonFrameMs, "median", 0.0));
            std::snprintf(lost, sizeof lost, "%u/%llu", r.torn, static_cast<unsigned long long>(r.skipped));
            std::snprintf(clock, sizeof clock, "%s/%s", s.smClockStartMhz.c_str(), s.smClockEndMhz.c_str());
            BenchSummary timing = summarizeSamples(rateMode ? r.intervalMs : r.latencyMs);
            std::fprintf(out, "%-19s %10s %-9s %8.2f %23s %11s %9s %11s %11s\n", s.scene.name.c_str(), size,
                         r.transport.c_str(), r.deliveredFps, summaryCell(timing, 2, true).c_str(), cpu, frameMs, lost,
                         clock);
        }
    std::fflush(out);
}

} // namespace sky
