// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_flight_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>

namespace sky
{
namespace
{

/// The client's wall time that frame i took: from the previous frame in hand (the first: from its set_view).
double framePeriodS(const ServiceRunResult& run, size_t i)
{
    return i > 0 ? run.inHandS[i] - run.inHandS[i - 1] : run.latencyMs[0] / 1000.0;
}

/// Sums of one daemon figure over the frames that have it.
struct Mean
{
    double sum = 0;
    uint32_t count = 0;
    void add(double v)
    {
        sum += v;
        ++count;
    }
    double value() const { return count > 0 ? sum / count : -1.0; }
};

template <typename Wanted>
FlightFrameMeans meansOf(const FlightInputs& in, size_t first, size_t end, Wanted wanted)
{
    FlightFrameMeans m;
    double wallS = 0, clientMs = 0;
    Mean daemon, publish, setup, march, reconstruct, composite, sky, total;
    auto pass = [](const DaemonFrameTimes& t, const char* name, Mean& mean)
    {
        auto it = t.gpuMs.find(name);
        if (it != t.gpuMs.end())
            mean.add(it->second);
    };
    for (size_t i = first; i < end; ++i)
    {
        if (!wanted(i))
            continue;
        ++m.frames;
        wallS += framePeriodS(in.run, i);
        clientMs += in.run.latencyMs[i];
        auto it = in.daemonTimes.find(in.run.frameIds[i]);
        if (it == in.daemonTimes.end())
            continue;
        ++m.framesWithDaemonTimes;
        daemon.add(it->second.frameMs);
        publish.add(it->second.publishMs);
        if (it->second.setupMs >= 0)
            setup.add(it->second.setupMs);
        pass(it->second, "march", march);
        pass(it->second, "reconstruct", reconstruct);
        pass(it->second, "composite", composite);
        pass(it->second, "sky", sky);
        pass(it->second, "total", total);
    }
    if (m.frames == 0)
        return m;
    m.fps = wallS > 0 ? m.frames / wallS : 0;
    m.clientFrameMs = clientMs / m.frames;
    m.daemonFrameMs = daemon.value();
    m.publishMs = publish.value();
    m.setupMs = setup.value();
    m.marchMs = march.value();
    m.reconstructMs = reconstruct.value();
    m.compositeMs = composite.value();
    m.skyMs = sky.value();
    m.gpuTotalMs = total.value();
    return m;
}

FlightWindow slowestWindow(const FlightInputs& in, const FlightPathSpec& spec)
{
    const size_t frames = in.run.latencyMs.size();
    const size_t span = std::min(frames, size_t(std::max(1.0, std::round(1.0 / spec.stepS))));
    // Sliding sum of the frames' periods over `span` frames.
    double wallS = 0, slowestS = -1;
    size_t slowestFirst = 0;
    for (size_t i = 0; i < frames; ++i)
    {
        wallS += framePeriodS(in.run, i);
        if (i >= span)
            wallS -= framePeriodS(in.run, i - span);
        if (i + 1 >= span && wallS > slowestS)
        {
            slowestS = wallS;
            slowestFirst = i + 1 - span;
        }
    }
    FlightWindow w;
    w.firstFrame = uint32_t(slowestFirst);
    w.frames = uint32_t(span);
    w.startS = in.poses[slowestFirst].timeS;
    w.wallS = slowestS;
    w.pose = in.poses[slowestFirst].pose;
    w.insideCloudLayer = in.insideCloudLayer[slowestFirst];
    w.means = meansOf(in, slowestFirst, slowestFirst + span, [](size_t) { return true; });
    return w;
}

nlohmann::json orNull(double v) { return v < 0 ? nlohmann::json(nullptr) : nlohmann::json(v); }

nlohmann::json meansJson(const FlightFrameMeans& m)
{
    return {{"frames", m.frames},
            {"framesWithDaemonTimes", m.framesWithDaemonTimes},
            {"fps", m.fps},
            {"meanMs",
             {{"clientFrame", m.clientFrameMs},
              {"daemonFrame", orNull(m.daemonFrameMs)},
              {"publish", orNull(m.publishMs)},
              {"setup", orNull(m.setupMs)},
              {"march", orNull(m.marchMs)},
              {"reconstruct", orNull(m.reconstructMs)},
              {"composite", orNull(m.compositeMs)},
              {"sky", orNull(m.skyMs)},
              {"gpuTotal", orNull(m.gpuTotalMs)}}}};
}

nlohmann::json poseJson(const EyePose& p)
{
    return {{"latDeg", p.latDeg},         {"lonDeg", p.lonDeg},     {"altitudeM", p.altitudeM},
            {"headingDeg", p.headingDeg}, {"pitchDeg", p.pitchDeg}, {"rollDeg", p.rollDeg}};
}

nlohmann::json clockJson(const std::string& mhz)
{
    return mhz == "n/a" ? nlohmann::json("n/a") : nlohmann::json(std::stod(mhz));
}

std::string msCell(double ms) { return ms < 0 ? std::string("n/a") : std::to_string(ms).substr(0, 6); }

void printMeansRow(std::FILE* out, const char* label, const FlightFrameMeans& m)
{
    std::fprintf(out, "  %-22s %6u %8.1f %8.3f %8s %8s %8s %8s %8s %8s %8s\n", label, m.frames, m.fps,
                 m.clientFrameMs, msCell(m.daemonFrameMs).c_str(), msCell(m.setupMs).c_str(),
                 msCell(m.gpuTotalMs).c_str(), msCell(m.marchMs).c_str(), msCell(m.reconstructMs).c_str(),
                 msCell(m.compositeMs).c_str(), msCell(m.publishMs).c_str());
}

} // namespace

void analyzeFlight(const FlightInputs& in, FlightReport& report)
{
    const ServiceRunResult& run = in.run;
    report.frames = run.frames;
    report.torn = run.torn;
    report.elapsedS = run.elapsedS;
    report.fps = run.deliveredFps;
    report.daemonTimesPublished = in.daemonTimesPublished;
    report.cloudLayers = in.cloudLayers;
    if (run.latencyMs.empty())
        return;
    const BenchSummary summary = summarizeSamples(run.latencyMs);
    report.frameMsMedian = summary.median;
    report.frameMsP99 = summary.p99;
    report.frameMsMax = summary.max;
    std::vector<double> slowest = run.latencyMs;
    const size_t percent = std::max<size_t>(1, slowest.size() / 100);
    std::partial_sort(slowest.begin(), slowest.begin() + std::ptrdiff_t(percent), slowest.end(), std::greater<>());
    double sum = 0;
    for (size_t i = 0; i < percent; ++i)
        sum += slowest[i];
    report.slowestPercentMeanMs = sum / double(percent);
    const size_t n = run.latencyMs.size();
    report.whole = meansOf(in, 0, n, [](size_t) { return true; });
    report.insideCloudLayer = meansOf(in, 0, n, [&](size_t i) { return bool(in.insideCloudLayer[i]); });
    report.outsideCloudLayer = meansOf(in, 0, n, [&](size_t i) { return !in.insideCloudLayer[i]; });
    report.slowestWindow = slowestWindow(in, report.spec);
}

nlohmann::json flightReportToJson(const FlightReport& r)
{
    nlohmann::json layers = nlohmann::json::array();
    for (const CloudLayerStretch& s : r.cloudLayers)
        layers.push_back({{"layer", s.layer},
                          {"enterS", s.enterS},
                          {"leaveS", s.leaveS},
                          {"coverage", {{"min", s.minCoverage}, {"max", s.maxCoverage}}}});
    const FlightWindow& w = r.slowestWindow;
    nlohmann::json window = meansJson(w.means);
    window["startS"] = w.startS;
    window["firstFrame"] = w.firstFrame;
    window["wallS"] = w.wallS;
    window["pose"] = poseJson(w.pose);
    window["insideCloudLayer"] = w.insideCloudLayer;
    return {{"tool", "sky-service-bench"},
            {"formatVersion", 1},
            {"mode", "flight-path"},
            {"device", {{"name", r.deviceName}, {"driver", r.driver}}},
            {"daemon", r.daemonBinary},
            {"quality", "medium"},
            {"reprojected", true},
            {"width", r.width},
            {"height", r.height},
            {"transport", r.transport},
            {"warmup", r.warmup},
            {"path",
             {{"start", {{"latDeg", r.spec.startLatDeg}, {"lonDeg", r.spec.startLonDeg},
                         {"altitudeM", r.spec.startAltitudeM}, {"headingDeg", r.spec.startHeadingDeg}}},
              {"groundSpeedMps", r.spec.groundSpeedMps},
              {"climbMps", r.spec.climbMps},
              {"turnDegPerS", r.spec.turnDegPerS},
              {"seconds", r.spec.seconds},
              {"stepS", r.spec.stepS}}},
            {"smClockMhz", {{"start", clockJson(r.smClockStartMhz)}, {"end", clockJson(r.smClockEndMhz)}}},
            {"frames", r.frames},
            {"torn", r.torn},
            {"elapsedS", r.elapsedS},
            {"fps", r.fps},
            {"frameMs",
             {{"median", r.frameMsMedian}, {"p99", r.frameMsP99}, {"max", r.frameMsMax},
              {"slowestPercentMean", r.slowestPercentMeanMs}}},
            {"daemonTimesPublished", r.daemonTimesPublished},
            {"whole", meansJson(r.whole)},
            {"insideCloudLayer", meansJson(r.insideCloudLayer)},
            {"outsideCloudLayer", meansJson(r.outsideCloudLayer)},
            {"slowestWindow", window},
            {"cloudLayers", layers}};
}

void printFlightReport(std::FILE* out, const FlightReport& r)
{
    std::fprintf(out, "flight path on %s (%s), %ux%u %s, %u frames of %.4f s simulated, SM clock %s..%s MHz\n",
                 r.deviceName.c_str(), r.driver.c_str(), r.width, r.height, r.transport.c_str(), r.frames,
                 r.spec.stepS, r.smClockStartMhz.c_str(), r.smClockEndMhz.c_str());
    std::fprintf(out, "  fps %.1f over %.2f s; frame ms (set_view -> in hand) median %.3f, p99 %.3f, "
                      "slowest 1 %% mean %.3f, max %.3f; torn %u\n",
                 r.fps, r.elapsedS, r.frameMsMedian, r.frameMsP99, r.slowestPercentMeanMs, r.frameMsMax, r.torn);
    for (const CloudLayerStretch& s : r.cloudLayers)
        std::fprintf(out, "  inside layer %-10s %7.2f .. %7.2f s (coverage %.2f..%.2f)\n", s.layer.c_str(), s.enterS,
                     s.leaveS, double(s.minCoverage), double(s.maxCoverage));
    const FlightWindow& w = r.slowestWindow;
    std::fprintf(out, "  slowest second: from %.2f s (frame %u), %.1f fps, eye %.5f N %.5f E %.0f m heading %.1f, %s\n",
                 w.startS, w.firstFrame, w.means.fps, w.pose.latDeg, w.pose.lonDeg, w.pose.altitudeM,
                 w.pose.headingDeg, w.insideCloudLayer ? "inside a cloud layer" : "outside the cloud layers");
    if (!r.daemonTimesPublished)
        std::fprintf(out, "  (the daemon's status has no recent_frames: no per-pass times)\n");
    std::fprintf(out, "  %-22s %6s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "mean ms", "frames", "fps", "client",
                 "daemon", "setup", "gpu", "march", "reconst", "compos", "publish");
    printMeansRow(out, "whole path", r.whole);
    printMeansRow(out, "inside cloud layer", r.insideCloudLayer);
    printMeansRow(out, "outside cloud layers", r.outsideCloudLayer);
    printMeansRow(out, "slowest second", w.means);
}

bool writeFlightFramesCsv(const std::string& path, const FlightInputs& in, std::string& error)
{
    std::ofstream f(path);
    if (!f)
    {
        error = "cannot write " + path;
        return false;
    }
    f << "time_s,frame_id,lat_deg,lon_deg,alt_m,heading_deg,inside_layer,client_ms,period_ms,daemon_ms,"
         "publish_ms,setup_ms,gpu_total_ms,march_ms,reconstruct_ms,composite_ms\n";
    char line[512];
    for (size_t i = 0; i < in.run.latencyMs.size() && i < in.poses.size(); ++i)
    {
        const EyePose& p = in.poses[i].pose;
        auto it = in.daemonTimes.find(in.run.frameIds[i]);
        auto gpu = [&](const char* pass)
        {
            if (it == in.daemonTimes.end() || !it->second.gpuMs.count(pass))
                return std::string();
            return std::to_string(it->second.gpuMs.at(pass));
        };
        const bool have = it != in.daemonTimes.end();
        std::snprintf(line, sizeof line, "%.4f,%llu,%.7f,%.7f,%.1f,%.2f,%d,%.4f,%.4f,%s,%s,%s,%s,%s,%s,%s\n",
                      in.poses[i].timeS, (unsigned long long)in.run.frameIds[i], p.latDeg, p.lonDeg, p.altitudeM,
                      p.headingDeg, in.insideCloudLayer[i] ? 1 : 0, in.run.latencyMs[i],
                      1000.0 * framePeriodS(in.run, i), have ? std::to_string(it->second.frameMs).c_str() : "",
                      have ? std::to_string(it->second.publishMs).c_str() : "",
                      have && it->second.setupMs >= 0 ? std::to_string(it->second.setupMs).c_str() : "",
                      gpu("total").c_str(),
                      gpu("march").c_str(), gpu("reconstruct").c_str(), gpu("composite").c_str());
        f << line;
    }
    f.close();
    if (!f)
    {
        error = "cannot write " + path;
        return false;
    }
    return true;
}

} // namespace sky
