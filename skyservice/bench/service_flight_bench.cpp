// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_flight_bench.h"

#include "skyservice/bench/service_client_run.h"
#include "skyservice/bench/service_daemon.h"
#include "skyservice/bench/service_flight_report.h"
#include "skyservice/bench/service_host_metrics.h"
#include "skyservice/bench/service_session.h"
#include "skyservice/output/image_files.h"

#include <filesystem>
#include <unistd.h>

namespace sky
{
namespace
{

constexpr int kExitOk = 0, kExitRuntime = 1;
constexpr double kDaemonStartTimeoutS = 300; // device creation and pipelines; minutes on a loaded lavapipe host
constexpr double kWeatherTimeoutS = 300;
constexpr double kDaemonStopTimeoutS = 60;

ServiceDaemonConfig daemonConfig(const FlightBenchSettings& s, const BenchScene& scene)
{
    ServiceDaemonConfig config;
    config.binary = s.daemon.empty() ? defaultDaemonBinary() : s.daemon;
    config.dir = s.dir;
    config.shmName =
        "/sky-service-bench-" + std::to_string(getpid()) + "-" + std::filesystem::path(s.dir).filename().string();
    config.maxWidth = config.width = s.width;
    config.maxHeight = config.height = s.height;
    config.device = s.device;
    config.scene = scene;
    return config;
}

/// The daemon's device, its scene's weather, and the client's run over the path with the daemon's
/// frame times read beside it.
bool flyPath(const FlightBenchSettings& s, ServiceDaemon& daemon, const BenchScene& scene, FlightInputs& in,
             FlightReport& report, std::string& error)
{
    {
        ServiceConnection c;
        nlohmann::json status;
        if (!c.open(daemon.socketPath(), "sky-service-bench-setup", error) ||
            !readServiceStatus(c.get(), status, error))
            return false;
        report.deviceName = status.value("device", std::string());
        report.driver = status.value("driver", std::string());
    }
    if (!prepareSceneWeather(daemon.socketPath(), scene, s.dir, true, kWeatherTimeoutS, error))
        return false;
    ServiceRunSettings run;
    run.socketPath = daemon.socketPath();
    run.daemonPid = daemon.pid();
    run.scene = scene;
    run.width = s.width;
    run.height = s.height;
    run.transport = s.transport;
    run.frames = uint32_t(in.poses.size());
    run.warmup = s.warmup;
    for (const FlightPose& p : in.poses)
        run.path.push_back(p.pose);
    DaemonFrameTimesReader reader;
    report.smClockStartMhz = gpuSmClockMhz();
    if (!reader.start(daemon.socketPath(), error) || !runServiceClient(run, in.run, error))
        return false;
    report.smClockEndMhz = gpuSmClockMhz();
    std::string readError;
    in.daemonTimes = reader.finish(in.daemonTimesPublished, readError);
    if (!readError.empty())
    {
        error = "reading the daemon's frame times: " + readError;
        return false;
    }
    return true;
}

} // namespace

int runFlightPathBench(const FlightBenchSettings& s)
{
    const BenchScene scene = flightPathScene(s.spec);
    FlightInputs in;
    in.poses = flightPathPoses(s.spec);
    in.cloudLayers = cloudLayerStretches(in.poses, in.insideCloudLayer);
    FlightReport report;
    report.spec = s.spec;
    report.width = s.width;
    report.height = s.height;
    report.transport = s.transport;
    report.warmup = s.warmup;
    const ServiceDaemonConfig config = daemonConfig(s, scene);
    report.daemonBinary = config.binary;

    ServiceDaemon daemon;
    std::string error;
    if (!daemon.start(config, kDaemonStartTimeoutS, error))
    {
        std::fprintf(stderr, "sky-service-bench: flight path: %s\n", error.c_str());
        return kExitRuntime;
    }
    if (!flyPath(s, daemon, scene, in, report, error))
    {
        if (daemon.running())
            error += "\nthe daemon's log ends:\n" + daemon.logTail();
        std::fprintf(stderr, "sky-service-bench: flight path: %s\n", error.c_str());
        return kExitRuntime;
    }
    if (!daemon.stop(kDaemonStopTimeoutS, error))
    {
        std::fprintf(stderr, "sky-service-bench: flight path: %s\n", error.c_str());
        return kExitRuntime;
    }
    analyzeFlight(in, report);
    printFlightReport(stdout, report);
    if (!s.json.empty() && !writeJsonAtomic(s.json, flightReportToJson(report), error))
    {
        std::fprintf(stderr, "sky-service-bench: --json %s: %s\n", s.json.c_str(), error.c_str());
        return kExitRuntime;
    }
    if (!s.csv.empty() && !writeFlightFramesCsv(s.csv, in, error))
    {
        std::fprintf(stderr, "sky-service-bench: --frames-csv: %s\n", error.c_str());
        return kExitRuntime;
    }
    return kExitOk;
}

} // namespace sky
