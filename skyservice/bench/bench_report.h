// SPDX-License-Identifier: MIT
// What sky-bench measured, and its two renderings: a JSON document and a table for humans.
#pragma once

#include "skyservice/bench/bench_scenes.h"

#include <cstdint>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sky
{

/// Order statistics of a set of samples (milliseconds).
struct BenchSummary
{
    size_t count = 0;
    double median = 0;  ///< middle value (mean of the two middle values for an even count)
    double p95 = 0;     ///< 95th percentile, nearest rank: the ceil(0.95 n)-th smallest value
    double p99 = 0;     ///< 99th percentile, nearest rank: the ceil(0.99 n)-th smallest value
    double mean = 0;
    double min = 0;
    double max = 0;
};

/**
 * @param[in] samples any values (copied and sorted).
 * @return their summary; all zero when samples is empty.
 **********************************************************************/
BenchSummary summarizeSamples(std::vector<double> samples);

/// A summary as JSON: count, median, p95, p99, mean, min, max.
nlohmann::json benchSummaryJson(const BenchSummary& s);

/**
 * One table cell: "median/p95" (or "median/p95/p99"), each with `decimals` digits after the point.
 *
 * @param[in] s the summary.
 * @param[in] decimals digits after the decimal point.
 * @param[in] withP99 append the 99th percentile.
 * @return the cell text; "-" when the summary has no samples.
 **********************************************************************/
std::string summaryCell(const BenchSummary& s, int decimals, bool withP99 = false);

/// Timings of one scene: one sample per timed frame.
struct BenchSceneResult
{
    BenchScene scene;
    std::map<std::string, std::vector<double>> gpuMs;  ///< per pass (RenderResult::gpuMs keys), ms
    std::vector<double> wallMs;       ///< renderView call, CPU setup + upload + GPU + wait, ms
    std::vector<double> cpuSetupMs;   ///< RenderResult::cpuSetupMs (weather window, lighting), ms
    double sunElevationDeg = 0;
    double cloudFraction = 0;         ///< share of pixels with cloud alpha > 0.5 (one checked frame)
    /// Share of pixels with any cloud (alpha > 0): where the composite reads the aerial-perspective LUT
    /// and the reconstruct pass follows the cloud's depth (their cost grows with it).
    double anyCloudFraction = 0;
    bool allFinite = true;            ///< every value of the checked frame finite and >= 0
    uint32_t marchBlockPx = 1;        ///< RenderResult::marchBlockPx of the checked frame (4, or 2/1 near clouds)
    std::string marchBlockReason;     ///< and why it was not 4
    /// RenderResult::marchRowLookups of the checked frame: per workgroup row (top first) the sum over its
    /// workgroups of their slowest ray's march iterations (with --lookup-totals: of every ray's). Where the
    /// march's cost lies, without a shader patch.
    std::vector<uint32_t> marchRowLookups;
};

/// Device allocations (MemoryTracker) after the scenes ran at the bench size.
struct BenchMemory
{
    std::map<std::string, uint64_t> liveBytes;  ///< by allocation name
    uint64_t totalBytes = 0;                    ///< live total (textures, buffers, LUTs, output images)
    uint64_t peakBytes = 0;                     ///< high-water mark, transient staging buffers included
};

struct BenchRun
{
    std::string deviceName, driver, deviceType;
    uint32_t apiVersion = 0;
    double timestampPeriodNs = 0;
    uint32_t width = 0, height = 0;
    uint32_t frames = 0, warmup = 0;
    uint32_t gpuFramesPerCall = 1;  ///< GPU frames per renderView call (one CPU setup); samples are their mean
    std::string mode;
    double speedMps = 0;      ///< eye speed along its heading (m/s, 60 Hz frames); 0 = a still eye
    nlohmann::json quality;   ///< the QualitySettings used
    /// The driver compiler's statistics per frame-path pipeline (registers, spills, ...), where the
    /// device reports them (VK_KHR_pipeline_executable_properties); empty otherwise.
    std::map<std::string, std::string> pipelineStatistics;
    BenchMemory memory;
    std::vector<BenchSceneResult> scenes;
};

/// The whole run as JSON: device, driver, sizes, quality, memory, and per scene the summary of every
/// pass, of wall time and of CPU setup time.
nlohmann::json benchToJson(const BenchRun& run);

/// A readable table: one row per scene (median and p95 of each pass), then the memory by allocation.
void printBenchTable(std::FILE* out, const BenchRun& run);

}  // namespace sky
