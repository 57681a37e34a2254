// SPDX-License-Identifier: MIT
#include "skyservice/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sky
{
namespace
{

// Columns of the table in pipeline order; passes not named here follow, then "total" last.
const char* const kPassOrder[] = {"shadowMap", "sky", "lightVolume", "clouds", "march", "reconstruct", "composite"};

std::vector<std::string> passColumns(const BenchRun& run)
{
    std::vector<std::string> all;
    for (const BenchSceneResult& s : run.scenes)
        for (const auto& [pass, samples] : s.gpuMs)
            if (std::find(all.begin(), all.end(), pass) == all.end())
                all.push_back(pass);
    std::vector<std::string> ordered;
    for (const char* name : kPassOrder)
        if (std::find(all.begin(), all.end(), name) != all.end())
            ordered.push_back(name);
    for (const std::string& name : all)
        if (name != "total" && std::find(ordered.begin(), ordered.end(), name) == ordered.end())
            ordered.push_back(name);
    if (std::find(all.begin(), all.end(), "total") != all.end())
        ordered.push_back("total");
    return ordered;
}

double mib(uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

}  // namespace

BenchSummary summarizeSamples(std::vector<double> samples)
{
    BenchSummary s;
    if (samples.empty())
        return s;
    std::sort(samples.begin(), samples.end());
    size_t n = samples.size();
    s.count = n;
    s.median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
    auto nearestRank = [&](double q)
    { return samples[std::clamp<size_t>(size_t(std::ceil(q * double(n))), 1, n) - 1]; };
    s.p95 = nearestRank(0.95);
    s.p99 = nearestRank(0.99);
    s.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / double(n);
    s.min = samples.front();
    s.max = samples.back();
    return s;
}

nlohmann::json benchSummaryJson(const BenchSummary& s)
{
    return {{"count", s.count}, {"median", s.median}, {"p95", s.p95}, {"p99", s.p99},
            {"mean", s.mean},   {"min", s.min},       {"max", s.max}};
}

std::string summaryCell(const BenchSummary& s, int decimals, bool withP99)
{
    if (s.count == 0)
        return "-";
    char cell[64];
    if (withP99)
        std::snprintf(cell, sizeof cell, "%.*f/%.*f/%.*f", decimals, s.median, decimals, s.p95, decimals, s.p99);
    else
        std::snprintf(cell, sizeof cell, "%.*f/%.*f", decimals, s.median, decimals, s.p95);
    return cell;
}

nlohmann::json benchToJson(const BenchRun& run)
{
    nlohmann::json doc;
    doc["tool"] = "sky-bench";
    doc["formatVersion"] = 1;
    doc["device"] = {{"name", run.deviceName},
                     {"driver", run.driver},
                     {"type", run.deviceType},
                     {"apiVersion", std::to_string(run.apiVersion >> 22) + "." +
                                        std::to_string((run.apiVersion >> 12) & 0x3ffu) + "." +
                                        std::to_string(run.apiVersion & 0xfffu)},
                     {"timestampPeriodNs", run.timestampPeriodNs}};
    doc["width"] = run.width;
    doc["height"] = run.height;
    doc["frames"] = run.frames;
    doc["warmup"] = run.warmup;
    doc["gpuFramesPerCall"] = run.gpuFramesPerCall;
    doc["mode"] = run.mode;
    doc["eyeSpeedMps"] = run.speedMps;
    doc["quality"] = run.quality;
    doc["pipelineStatistics"] = run.pipelineStatistics;
    nlohmann::json alloc = nlohmann::json::object();
    for (const auto& [name, bytes] : run.memory.liveBytes)
        alloc[name] = bytes;
    doc["memory"] = {{"totalBytes", run.memory.totalBytes},
                     {"totalMiB", mib(run.memory.totalBytes)},
                     {"peakBytes", run.memory.peakBytes},
                     {"allocations", alloc}};
    nlohmann::json scenes = nlohmann::json::array();
    for (const BenchSceneResult& s : run.scenes)
    {
        nlohmann::json passes = nlohmann::json::object();
        for (const auto& [pass, samples] : s.gpuMs)
            passes[pass] = benchSummaryJson(summarizeSamples(samples));
        const EyePose& p = s.scene.pose;
        scenes.push_back({{"name", s.scene.name},
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
                          {"sunElevationDeg", s.sunElevationDeg},
                          {"cloudFraction", s.cloudFraction},
                          {"anyCloudFraction", s.anyCloudFraction},
                          {"allFinite", s.allFinite},
                          {"marchBlockPx", s.marchBlockPx},
                          {"marchBlockReason", s.marchBlockReason},
                          {"marchRowLookups", s.marchRowLookups},
                          {"gpuMs", passes},
                          {"wallMs", benchSummaryJson(summarizeSamples(s.wallMs))},
                          {"cpuSetupMs", benchSummaryJson(summarizeSamples(s.cpuSetupMs))}});
    }
    doc["scenes"] = scenes;
    return doc;
}

void printBenchTable(std::FILE* out, const BenchRun& run)
{
    std::fprintf(out, "sky-bench: %s | %s | %ux%u | mode %s | eye %.0f m/s | %u samples after %u warm-up, %u GPU frame(s) each\n",
                 run.deviceName.c_str(), run.driver.c_str(), run.width, run.height, run.mode.c_str(), run.speedMps,
                 run.frames, run.warmup, run.gpuFramesPerCall);
    for (const auto& [program, statistics] : run.pipelineStatistics)
        std::fprintf(out, "pipeline %s: %s\n", program.c_str(), statistics.c_str());
    std::fprintf(out, "GPU ms per pass and frame (median/p95, timestamps); wall = renderView call incl. CPU setup "
                      "(median/p95)\n");
    std::vector<std::string> columns = passColumns(run);
    std::fprintf(out, "%-19s", "scene");
    for (const std::string& c : columns)
        std::fprintf(out, " %15s", c.c_str());
    std::fprintf(out, " %15s %9s %6s\n", "wall", "cpu-setup", "cloud%");
    for (const BenchSceneResult& s : run.scenes)
    {
        std::fprintf(out, "%-19s", s.scene.name.c_str());
        for (const std::string& c : columns)
        {
            auto it = s.gpuMs.find(c);
            if (it == s.gpuMs.end())
            {
                std::fprintf(out, " %15s", "-");
                continue;
            }
            std::fprintf(out, " %15s", summaryCell(summarizeSamples(it->second), 3).c_str());
        }
        std::fprintf(out, " %15s %9.2f %5.1f%s\n", summaryCell(summarizeSamples(s.wallMs), 2).c_str(),
                     summarizeSamples(s.cpuSetupMs).median,
                     100.0 * s.cloudFraction, s.allFinite ? "" : "  NON-FINITE");
    }
    std::fprintf(out, "device memory at %ux%u: %.2f MiB live (%.2f MB), peak %.2f MiB with staging\n", run.width,
                 run.height, mib(run.memory.totalBytes), double(run.memory.totalBytes) * 1e-6,
                 mib(run.memory.peakBytes));
    std::vector<std::pair<std::string, uint64_t>> allocations(run.memory.liveBytes.begin(), run.memory.liveBytes.end());
    std::sort(allocations.begin(), allocations.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    for (const auto& [name, bytes] : allocations)
        std::fprintf(out, "  %-24s %9.3f MiB\n", name.c_str(), mib(bytes));
    std::fflush(out);
}

}  // namespace sky
