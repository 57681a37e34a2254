// SPDX-License-Identifier: MIT
// `skyservice showcase` (what `./sky run` runs): the views that show what the product does, rendered
// from the built-in weather and, when the real GFS sample is beside the project (../shared/weather/),
// from that forecast at places chosen from its data, plus a captioned contact sheet, the look sheet
// (skyservice/app/look_views.h) and four look views next to the reference path tracer.
#include "skyservice/app/commands.h"

#include "skyservice/app/look_views.h"
#include "skyservice/app/reference_pairs.h"
#include "skyservice/app/render_files.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/output/image_files.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"
#include "skyservice/sky/weather_places.h"

#ifdef SKY_HAVE_INGEST
#include "weather_ingest/ingest.h"
#include "weather_ingest/snapshot_file.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace sky
{
namespace
{

// Size of the views next to the reference (look-reference-pairs.png): the path tracer's cost grows with it.
constexpr uint32_t kReferencePairWidth = 64;
constexpr uint32_t kReferencePairHeight = 36;

struct ShowcaseView
{
    std::string name;
    std::string caption;     ///< the JSON sidecar's caption: what, where, when
    std::string tileCaption; ///< the contact sheet's (about 40 characters fit a 640-pixel tile)
    EyePose pose;
    double fovYDeg = 60.0;
    int64_t unixTimeS = 0;
    const WeatherSnapshot* weather = nullptr; ///< nullptr: the built-in weather at the view's time
    std::string weatherSource = "builtin";
    uint32_t shadowMapSize = 0;              ///< > 0: also write the cloud shadow map (texels per side)
    bool look = false;  ///< a look-sheet view (look_views.h): half size, on look-sheet.png instead of the contact sheet
};

ShowcaseView builtinView(const char* name, const char* caption, const EyePose& pose, double fovYDeg,
                         const char* timeIso, uint32_t shadowMapSize = 0)
{
    ShowcaseView v;
    v.shadowMapSize = shadowMapSize;
    v.name = name;
    v.caption = caption;
    v.tileCaption = caption;
    v.pose = pose;
    v.fovYDeg = fovYDeg;
    std::string error;
    parseIso8601Utc(timeIso, v.unixTimeS, error);
    return v;
}

std::vector<ShowcaseView> builtinViews()
{
    const double cbLat = kBuiltinCumulonimbusLatDeg, cbLon = kBuiltinCumulonimbusLonDeg;
    return {
        builtinView("cumulus-midday", "Scattered cumulus at midday from 600 m",
                    {kBuiltinCumulusLatDeg - 0.35, kBuiltinCumulusLonDeg, 600.0, 10.0, 8.0, 0.0}, 60.0,
                    "2026-06-21T11:30:00Z"),
        builtinView("cumulonimbus-40km", "Cumulonimbus and anvil from 40 km",
                    {cbLat, cbLon - lonOffsetDeg(40000.0, cbLat), 4500.0, 90.0, 6.0, 0.0}, 60.0,
                    "2026-06-21T15:00:00Z", 512),
        builtinView("deck-sunset", "Sunset over the stratocumulus deck",
                    {kBuiltinDeckLatDeg, kBuiltinDeckLonDeg + 0.6, 2600.0, 300.0, 1.0, 0.0}, 60.0,
                    "2026-06-21T19:15:00Z"),
        builtinView("deck-above-11000m", "The deck from 11 000 m: the earth's curvature",
                    {kBuiltinDeckLatDeg, kBuiltinDeckLonDeg + 1.0, 11000.0, 250.0, -8.0, 0.0}, 70.0,
                    "2026-06-21T09:30:00Z"),
    };
}

// The look sheet (skyservice/app/look_views.h). Small (half the showcase size) so that `./sky run` stays quick
// on a CPU.
std::vector<ShowcaseView> lookSheetViews()
{
    std::vector<ShowcaseView> views;
    for (const LookView& l : lookViews())
    {
        ShowcaseView v;
        v.name = l.name;
        v.caption = l.caption;
        v.tileCaption = l.caption;
        v.pose = l.pose;
        v.fovYDeg = l.fovYDeg;
        v.unixTimeS = l.unixTimeS;
        v.look = true;
        views.push_back(v);
    }
    return views;
}

#ifdef SKY_HAVE_INGEST

const char* const kGfsSampleName = "gfs-2p5deg-20110110-12z-f120.grib2";

// ./sky run runs from the project root, so ../shared/weather is the sample folder there; otherwise
// the shared folder the build was configured with (the source tree's ../shared by default).
std::string findGfsSample()
{
    for (const std::string& dir : {std::string("../shared/weather"), std::string(SKY_SHARED_DIR) + "/weather"})
    {
        std::error_code ec;
        const std::filesystem::path path = std::filesystem::path(dir) / kGfsSampleName;
        if (std::filesystem::is_regular_file(path, ec))
            return std::filesystem::absolute(path, ec).lexically_normal().string();
    }
    return {};
}

// Azimuth of the sun at a place and time (degrees), to turn views towards or away from it.
double sunAzimuthDeg(double latDeg, double lonDeg, int64_t unixTimeS)
{
    return computeSunMoon(unixTimeS, latDeg, lonDeg, 0.0).sun.azimuthDeg;
}

// Three views of the GFS forecast at places the data picks (skyservice/sky/weather_places.h), in
// daylight at the valid time: a low deck from above, a convective area from below its bases, and clear
// sky. Each caption names the place, the valid time and what the file says there.
std::vector<ShowcaseView> gfsViews(const WeatherSnapshot& gfs, const std::string& source)
{
    std::vector<ShowcaseView> views;
    const std::string when = formatIso8601Utc(gfs.validTimeUnixS);
    const std::string whenShort = when.substr(0, 10) + " " + when.substr(11, 5) + "Z";
    PlaceFilter daylight;
    daylight.minSunElevationDeg = 20.0;
    char text[512];

    auto add = [&](const char* name, const WeatherPlace& p, const EyePose& pose, const std::string& what,
                   const std::string& tile)
    {
        ShowcaseView v;
        v.name = name;
        std::snprintf(text, sizeof text, "GFS forecast valid %s (run 2011-01-10 12Z + 120 h) at %s: %s. Data: %s",
                      whenShort.c_str(), formatLatLon(p.latDeg, p.lonDeg).c_str(), what.c_str(),
                      describeWeatherPlace(p).c_str());
        v.caption = text;
        v.tileCaption = "GFS " + formatLatLon(p.latDeg, p.lonDeg) + " " + tile;
        v.pose = pose;
        v.unixTimeS = gfs.validTimeUnixS;
        v.weather = &gfs;
        v.weatherSource = source;
        views.push_back(v);
    };

    const WeatherPlace deck = findWeatherPlace(gfs, PlaceKind::LowDeck, daylight);
    if (deck.found)
    {
        // Above the deck, the sun behind the eye so the tops are lit.
        const double eyeM = double(deck.topM[0]) + 1500.0;
        std::snprintf(text, sizeof text, "%s deck %.0f %%, %.0f-%.0f m, seen from %.0f m",
                      deck.type[0] == uint8_t(CloudType::Stratus) ? "stratus" : "stratocumulus",
                      double(deck.coverage[0]) * 100.0, double(deck.baseM[0]), double(deck.topM[0]), eyeM);
        const double heading = std::fmod(sunAzimuthDeg(deck.latDeg, deck.lonDeg, gfs.validTimeUnixS) + 150.0, 360.0);
        add("gfs-low-deck", deck, {deck.latDeg, deck.lonDeg, eyeM, heading, -6.0, 0.0}, text, "low deck, above");
    }
    const WeatherPlace storm = findWeatherPlace(gfs, PlaceKind::Convective, daylight);
    if (storm.found)
    {
        // Seen from its edge: under the cell itself a field this dense is one grey overcast. The eye goes
        // 90 % of the way to the neighbouring cell with the least convective cover (the window interpolates
        // linearly between cells, so the cover there is mostly the neighbour's), above the bases, looking
        // back at the cell.
        double eyeLat = storm.latDeg, eyeLon = storm.lonDeg;
        float leastCover = 2.0f;
        for (int di = -1; di <= 1; ++di)
            for (int dj = -1; dj <= 1; ++dj)
            {
                const int64_t i = int64_t(storm.iLat) + di;
                if ((di == 0 && dj == 0) || i < 0 || i >= int64_t(gfs.grid.nLat))
                    continue;
                const uint32_t j = uint32_t((int64_t(storm.iLon) + dj + gfs.grid.nLon) % gfs.grid.nLon);
                const float cover = gfs.layers[2].coverage[gfs.grid.index(uint32_t(i), j)];
                if (cover < leastCover)
                {
                    leastCover = cover;
                    eyeLat = storm.latDeg + 0.9 * di * gfs.grid.dLatDeg;
                    eyeLon = storm.lonDeg + 0.9 * dj * gfs.grid.dLonDeg;
                }
            }
        const double eyeM = double(storm.baseM[2]) + 1500.0;
        const CameraFrame eye = computeCameraFrame({eyeLat, eyeLon, eyeM, 0.0, 0.0, 0.0});
        double headingDeg = 0, elevationDeg = 0;
        const glm::dvec3 towardsCell = geodeticToEnu(eye, storm.latDeg, storm.lonDeg, eyeM);
        enuDirectionToAzimuthElevation(towardsCell, headingDeg, elevationDeg);
        std::snprintf(text, sizeof text,
                      "convective cloud %.0f %% (%s, base %.0f m, tops %.0f m), CAPE %.0f J/kg, "
                      "seen from %s at %.0f m, looking towards it (heading %.0f deg)",
                      double(storm.coverage[2]) * 100.0,
                      storm.type[2] == uint8_t(CloudType::Cumulonimbus) ? "cumulonimbus" : "cumulus",
                      double(storm.baseM[2]), double(storm.topM[2]), double(storm.capeJKg),
                      formatLatLon(eyeLat, eyeLon).c_str(), eyeM, headingDeg);
        add("gfs-convective", storm, {eyeLat, eyeLon, eyeM, headingDeg, 4.0, 0.0}, text, "convection");
    }
    const WeatherPlace clear = findWeatherPlace(gfs, PlaceKind::Clear, daylight);
    if (clear.found)
    {
        // Towards the sun: an empty sky shows its gradient best there.
        std::snprintf(text, sizeof text,
                      "clear sky (no cloud in any layer for %.0f grid cells around), seen from 500 m", clear.score);
        const double heading = std::fmod(sunAzimuthDeg(clear.latDeg, clear.lonDeg, gfs.validTimeUnixS) + 325.0, 360.0);
        add("gfs-clear", clear, {clear.latDeg, clear.lonDeg, 500.0, heading, 15.0, 0.0}, text, "clear sky");
    }
    return views;
}

// Converts the sample in-process and keeps a copy as OUT/gfs.skywx (for `skyservice render --weather`).
std::unique_ptr<WeatherSnapshot> loadGfsSample(const std::string& path, const std::string& outDir,
                                               std::string& snapshotPath)
{
    try
    {
        auto start = std::chrono::steady_clock::now();
        ConvertResult converted = convertFiles({path}, MappingOptions{}, {});
        if (converted.snapshots.empty())
            return nullptr;
        snapshotPath = outDir + "/gfs.skywx";
        std::string error;
        if (!writeSnapshotFile(snapshotPath, {converted.snapshots[0]}, error))
        {
            std::fprintf(stderr, "skyservice showcase: %s (continuing)\n", error.c_str());
            snapshotPath = path;
        }
        std::printf("converted %s in %.1f s\n", path.c_str(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        return std::make_unique<WeatherSnapshot>(std::move(converted.snapshots[0]));
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "skyservice showcase: GFS views skipped: %s\n", e.what());
        return nullptr;
    }
}

#endif

// The views to render and the forecast the GFS ones point into (null without the sample).
struct ShowcaseViews
{
    std::vector<ShowcaseView> views;
    std::unique_ptr<WeatherSnapshot> gfs;
};

// The built-in views, the look sheet's and, when the GFS sample is found and converts, the forecast's.
ShowcaseViews collectShowcaseViews(const ShowcaseOptions& options)
{
    ShowcaseViews out;
    out.views = builtinViews();
    for (ShowcaseView& v : lookSheetViews())
        out.views.push_back(std::move(v));
#ifdef SKY_HAVE_INGEST
    const std::string gfsPath = findGfsSample();
    if (!gfsPath.empty())
    {
        std::string snapshotPath;
        out.gfs = loadGfsSample(gfsPath, options.outDir, snapshotPath);
        if (out.gfs)
            for (ShowcaseView& v : gfsViews(*out.gfs, snapshotPath))
                out.views.push_back(std::move(v));
    }
    else
        std::printf("GFS sample (../shared/weather/%s) not found: built-in weather only\n", kGfsSampleName);
#else
    (void)options;
#endif
    return out;
}

// The tiles of the two sheets, in view order, with their captions.
struct ShowcaseSheets
{
    std::vector<ImageRgba8> tiles, lookTiles;
    std::vector<std::string> captions, lookCaptions;
};

// Renders one view, writes its files and adds its tile to its sheet; false (with the message printed)
// when the render or a file fails.
bool renderShowcaseView(Renderer& renderer, const ShowcaseOptions& options, const QualitySettings& quality,
                        const ShowcaseView& view, ShowcaseSheets& sheets)
{
    ViewRequest request;
    request.pose = view.pose;
    request.fovYDeg = view.fovYDeg;
    request.width = view.look ? std::max(options.width / 2, 8u) : options.width;
    request.height = view.look ? std::max(options.height / 2, 8u) : options.height;
    request.unixTimeS = view.unixTimeS;
    // Some views also write the geo-referenced cloud shadow map (docs/model.md), 150 km wide.
    request.shadowMap = view.shadowMapSize > 0;
    request.shadowMapSize = view.shadowMapSize > 0 ? view.shadowMapSize : request.shadowMapSize;
    request.shadowMapExtentM = 150000.0;
    setWeather(renderer, view.weather ? *view.weather : makeBuiltinWeather(request.unixTimeS));
    auto start = std::chrono::steady_clock::now();
    RenderResult result;
    const SkyStatus status = renderView(renderer, request, quality, result);
    if (!status.ok())
    {
        std::fprintf(stderr, "skyservice showcase: %s: %s\n", view.name.c_str(), status.message.c_str());
        return false;
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    RenderFacts facts;
    facts.weatherSource = view.weatherSource;
    facts.timeIso = formatIso8601Utc(view.unixTimeS);
    facts.deviceName = renderer.ctx.deviceName;
    facts.driver = renderer.ctx.driverInfo;
    facts.caption = view.caption;
    facts.quality = qualityToJson(quality);
    std::string prefix = options.outDir + "/" + view.name;
    std::string error;
    if (!writeRenderFiles(prefix, request, result, facts, error))
    {
        std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
        return false;
    }
    std::printf("%-20s %s  (sun %.1f deg, %.1f s wall)\n", view.name.c_str(), view.caption.c_str(),
                result.sunElevationDeg, seconds);
    std::fflush(stdout);
    (view.look ? sheets.lookTiles : sheets.tiles).push_back({result.width, result.height, result.displayRgba8});
    (view.look ? sheets.lookCaptions : sheets.captions).push_back(view.tileCaption);
    return true;
}

// Writes one captioned sheet; nothing when it has no tiles. False (with the message printed) when the
// file fails.
bool writeSheet(const std::string& outDir, const char* name, const std::vector<ImageRgba8>& sheetTiles,
                const std::vector<std::string>& sheetCaptions, uint32_t columns)
{
    if (sheetTiles.empty())
        return true;
    ImageRgba8 sheet = makeContactSheet(sheetTiles, sheetCaptions, columns);
    std::string error;
    if (!writePng(outDir + "/" + name, sheet, error))
    {
        std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
        return false;
    }
    std::printf("wrote %s/%s\n", outDir.c_str(), name);
    return true;
}

// Four look views next to the reference path tracer (reference_pairs.h), small: the path tracing is most of the
// cost (docs/programs.md gives its time on a 2-core CPU).
bool writeReferencePairs(Renderer& renderer, const QualitySettings& quality, const ShowcaseOptions& options)
{
    const std::string path = options.outDir + "/look-reference-pairs.png";
    const auto start = std::chrono::steady_clock::now();
    const SkyStatus status = writeLookReferencePairs(renderer, quality, kReferencePairWidth, kReferencePairHeight,
                                                     options.referenceSpp, path);
    if (!status.ok())
    {
        std::fprintf(stderr, "skyservice showcase: reference pairs: %s\n", status.message.c_str());
        return false;
    }
    std::printf("wrote %s (%.1f s wall)\n", path.c_str(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return true;
}

// Renders every view, then the sheets and the reference pairs; each step runs only while all before it
// succeeded.
int renderShowcase(Renderer& renderer, const ShowcaseOptions& options, const QualitySettings& quality,
                   const std::vector<ShowcaseView>& views)
{
    ShowcaseSheets sheets;
    for (const ShowcaseView& view : views)
        if (!renderShowcaseView(renderer, options, quality, view, sheets))
            return kExitRuntime;
    if (!writeSheet(options.outDir, "contact-sheet.png", sheets.tiles, sheets.captions, 2) ||
        !writeSheet(options.outDir, "look-sheet.png", sheets.lookTiles, sheets.lookCaptions, 3))
        return kExitRuntime;
    if (options.referenceSpp > 0 && !writeReferencePairs(renderer, quality, options))
        return kExitRuntime;
    return kExitOk;
}

}  // namespace

int runShowcaseCommand(const ShowcaseOptions& options)
{
    QualitySettings quality;
    std::string error;
    if (!qualityFromOptions(options.common, quality, error))
    {
        std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
        return kExitUsage;
    }
    // Two accumulated frames keep `./sky run` within a few minutes on a 2-core CPU (lavapipe).
    if (options.common.accumulate == 0)
        quality.accumulationFrames = std::min(quality.accumulationFrames, 2u);
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec)
    {
        std::fprintf(stderr, "skyservice showcase: cannot create %s: %s\n", options.outDir.c_str(),
                     ec.message().c_str());
        return kExitRuntime;
    }

    const ShowcaseViews views = collectShowcaseViews(options);
    Renderer renderer;
    if (!startRenderer(options.common, quality.noiseSeed, renderer, "showcase"))
        return kExitRuntime;
    int code = renderShowcase(renderer, options, quality, views.views);
    if (options.common.validate && renderer.ctx.validationMessages.load() > 0)
        code = kExitRuntime;
    destroyRenderer(renderer);
    return code;
}

}  // namespace sky
