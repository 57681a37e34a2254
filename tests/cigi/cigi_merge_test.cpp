// SPDX-License-Identifier: MIT
// The host's weather over a gridded weather (skyservice/service/cigi_weather_merge.h):
//  - a region with Merge Weather averages its layer with the gridded one inside, leaves the gridded weather
//    outside, and blends between the two across its transition perimeter; a "use last" region replaces it;
//  - a global host layer replaces the gridded layer at its altitude (the others stay exactly), one at an
//    altitude no gridded layer has gets a slot of its own, and a disabled one leaves the gridded weather;
//  - the applier lays its weather over a loaded file as an overlay (the file's timeline and name stay), so
//    every sample of the file is merged again; without a file it draws its own weather as before;
//  - fade steps are published as small steps (WeatherState::smallStepFrom), nothing else is.
#include "cigi_host_datagram.h"

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/service/cigi_apply.h"
#include "skyservice/service/cigi_weather_merge.h"
#include "skyservice/service/weather_schedule.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sky
{
namespace
{

using namespace sky::cigi;
using namespace sky::cigi::test;
using cigi::CloudType;

constexpr double kOwnLat = 45.0, kOwnLon = 7.0;
constexpr double kMetresPerDegree = 111195.0; // as the region shapes measure

struct GriddedLayer
{
    const char* name;
    float coverage, baseM, topM;
    CloudType type;
};

/// A global 1-degree gridded weather of uniform layers.
WeatherSnapshot gridded(std::initializer_list<GriddedLayer> layers, int64_t validTimeUnixS = 1782043200)
{
    WeatherSnapshot w;
    w.grid = LatLonGrid{-90.0, -180.0, 1.0, 1.0, 181, 360};
    w.validTimeUnixS = validTimeUnixS;
    const size_t n = w.grid.cellCount();
    for (const GriddedLayer& g : layers)
    {
        CloudLayerFields l;
        l.name = g.name;
        l.coverage.assign(n, g.coverage);
        l.baseAltitudeM.assign(n, g.baseM);
        l.topAltitudeM.assign(n, g.topM);
        l.type.assign(n, uint8_t(g.type));
        l.precipitationMmH.assign(n, 0.0f);
        l.windEastMS.assign(n, 3.0f);
        l.windNorthMS.assign(n, 0.0f);
        w.layers.push_back(std::move(l));
    }
    return w;
}

CigiState stateWith(std::initializer_list<WeatherControl> layers)
{
    CigiState s;
    Decoder decoder;
    HostDatagram d(ByteOrder::Big, 1);
    for (const WeatherControl& w : layers)
        d.add(w);
    applyDatagram(s, decoder.decode(d.bytes().data(), d.bytes().size()), 0);
    return s;
}

/// A 20 km square region at the ownship with a 12 km transition perimeter.
void addRegion(CigiState& s, uint16_t id, bool merge)
{
    EnvironmentalRegion& r = s.regions[id];
    r.defined = true;
    r.state = RegionState::Active;
    r.latDeg = kOwnLat;
    r.lonDeg = kOwnLon;
    r.sizeXM = r.sizeYM = 20000;
    r.transitionPerimeterM = 12000;
    r.mergeWeather = merge;
}

/// The cell of `w` nearest a point.
size_t cellAt(const WeatherSnapshot& w, double latDeg, double lonDeg)
{
    const long iLat = std::lround((latDeg - w.grid.lat0Deg) / w.grid.dLatDeg);
    const long iLon = std::lround(std::fmod(lonDeg - w.grid.lon0Deg + 720.0, 360.0) / w.grid.dLonDeg);
    return w.grid.index(uint32_t(iLat), uint32_t(iLon));
}

/// Layer k's coverage `eastM` metres east of the ownship.
float coverageEast(const WeatherSnapshot& w, size_t k, double eastM)
{
    const double lon = kOwnLon + eastM / (kMetresPerDegree * std::cos(kOwnLat * M_PI / 180.0));
    return w.layers.at(k).coverage.at(cellAt(w, kOwnLat, lon));
}

WeatherSnapshot mergeOver(const WeatherSnapshot& g, const CigiState& s, const GeoidGrid& geoid = GeoidGrid{})
{
    CigiWeatherFade fade;
    fade.setTarget(s, 0.0); // the first weather is drawn at once
    const CigiWeatherGrid grid = cigiWeatherGrid(fade, kOwnLat, kOwnLon, true);
    return cigiMergeWeather(g, fade, 0.0, grid, geoid, kOwnLat, kOwnLon);
}

const GeoidGrid& egm96()
{
    static GeoidGrid grid = []
    {
        GeoidGrid g;
        std::string error;
        EXPECT_TRUE(g.load(defaultEgm96GridPath(), error)) << error;
        return g;
    }();
    return grid;
}

// Merge Weather: (0.4 + 0.8) / 2 inside, the gridded 0.4 outside, in between across the perimeter; the grid
// around the ownship reaches the renderer's whole window.
TEST(CigiMerge, MergeRegionAveragesWithTheGriddedWeatherAndBlendsAcrossItsPerimeter)
{
    const WeatherSnapshot g = gridded({{"low", 0.4f, 1000, 2000, CloudType::Stratocumulus}});
    CigiState s = stateWith({cloudLayer(1, CloudType::Cumulus, 1000, 1000, 80, 3)});
    addRegion(s, 3, true);
    const WeatherSnapshot m = mergeOver(g, s);
    ASSERT_EQ(m.layers.size(), 1u) << "the region's layer was not matched with the gridded one at its altitude";
    EXPECT_GE(std::fabs(m.grid.dLatDeg) * kMetresPerDegree * double(m.grid.nLat - 1) / 2, 790000.0)
        << "the merged grid does not reach the renderer's window";
    EXPECT_NEAR(coverageEast(m, 0, 0), 0.6f, 1e-5) << "inside: the average";
    const float edge = coverageEast(m, 0, 16000); // 6 km into the 12 km perimeter
    EXPECT_GT(edge, 0.41f);
    EXPECT_LT(edge, 0.59f);
    EXPECT_NEAR(coverageEast(m, 0, 40000), 0.4f, 1e-5) << "outside: the gridded weather";
    EXPECT_NEAR(m.layers[0].coverage.at(cellAt(m, kOwnLat + 3.0, kOwnLon)), 0.4f, 1e-5);
}

// Use last: the region's 0.8 inside (its altitudes and type), the gridded 0.4 outside.
TEST(CigiMerge, UseLastRegionReplacesTheGriddedWeatherInside)
{
    const WeatherSnapshot g = gridded({{"low", 0.4f, 900, 1900, CloudType::Stratocumulus}});
    CigiState s = stateWith({cloudLayer(1, CloudType::Cumulus, 1000, 1500, 80, 3)});
    addRegion(s, 3, false);
    const WeatherSnapshot m = mergeOver(g, s);
    ASSERT_EQ(m.layers.size(), 1u);
    const size_t centre = cellAt(m, kOwnLat, kOwnLon);
    EXPECT_FLOAT_EQ(m.layers[0].coverage[centre], 0.8f);
    EXPECT_FLOAT_EQ(m.layers[0].baseAltitudeM[centre], 1000.0f);
    EXPECT_FLOAT_EQ(m.layers[0].topAltitudeM[centre], 2500.0f);
    EXPECT_EQ(m.layers[0].type[centre], uint8_t(CloudType::Cumulus));
    const float edge = coverageEast(m, 0, 16000);
    EXPECT_GT(edge, 0.41f);
    EXPECT_LT(edge, 0.79f);
    EXPECT_NEAR(coverageEast(m, 0, 40000), 0.4f, 1e-5);
    EXPECT_EQ(m.layers[0].type[cellAt(m, kOwnLat, kOwnLon + 1.0)], uint8_t(CloudType::Stratocumulus));
}

// A global host layer at 4200-4800 m replaces the gridded middle layer everywhere (the host's altitudes
// above mean sea level + the geoid), the low one stays exactly; a host layer above every gridded one opens a
// slot of its own; a disabled host layer leaves the gridded weather as it is.
TEST(CigiMerge, GlobalHostLayersOverrideTheGriddedLayerAtTheirAltitude)
{
    const WeatherSnapshot g = gridded({{"low", 0.3f, 500, 1500, CloudType::Stratocumulus},
                                       {"middle", 0.5f, 4000, 5000, CloudType::Altocumulus}});
    const WeatherSnapshot m = mergeOver(g, stateWith({cloudLayer(1, CloudType::Altostratus, 4200, 600, 90)}), egm96());
    ASSERT_EQ(m.layers.size(), 2u);
    EXPECT_EQ(m.grid.nLat, g.grid.nLat) << "without regions the gridded grid is kept";
    EXPECT_EQ(m.layers[0].name, "low");
    EXPECT_EQ(m.layers[0].coverage, g.layers[0].coverage);
    EXPECT_EQ(m.layers[0].baseAltitudeM, g.layers[0].baseAltitudeM);
    const size_t here = cellAt(m, kOwnLat, kOwnLon);
    EXPECT_FLOAT_EQ(m.layers[1].coverage[here], 0.9f);
    EXPECT_NEAR(m.layers[1].baseAltitudeM[here], 4200.0 + egm96().undulationM(kOwnLat, kOwnLon), 0.01);
    EXPECT_EQ(m.layers[1].type[here], uint8_t(CloudType::Altostratus));
    EXPECT_FLOAT_EQ(m.layers[1].coverage[cellAt(m, -30.0, 120.0)], 0.9f) << "a global layer is global";

    const WeatherSnapshot high = mergeOver(g, stateWith({cloudLayer(2, CloudType::Stratus, 7000, 500, 70)}));
    ASSERT_EQ(high.layers.size(), 3u);
    EXPECT_EQ(high.layers[0].coverage, g.layers[0].coverage);
    EXPECT_EQ(high.layers[1].coverage, g.layers[1].coverage);
    EXPECT_FLOAT_EQ(high.layers[2].coverage[here], 0.7f);
    EXPECT_FLOAT_EQ(high.layers[2].baseAltitudeM[here], 7000.0f);

    WeatherControl off = cloudLayer(1, CloudType::Altostratus, 4200, 600, 90);
    off.weatherEnable = false;
    const WeatherSnapshot none = mergeOver(g, stateWith({off}));
    ASSERT_EQ(none.layers.size(), 2u);
    EXPECT_EQ(none.layers[0].coverage, g.layers[0].coverage);
    EXPECT_EQ(none.layers[1].coverage, g.layers[1].coverage);
    EXPECT_EQ(none.layers[1].topAltitudeM, g.layers[1].topAltitudeM);
}

// A regional model's domain edge (dataWeight) fades the gridded weather, not the host's layers over it.
TEST(CigiMerge, TheModelsDomainEdgeDoesNotFadeTheHostsLayers)
{
    WeatherSnapshot g = gridded({{"low", 0.4f, 1000, 2000, CloudType::Stratocumulus}});
    g.dataWeight.assign(g.grid.cellCount(), 0.0f); // no data anywhere
    const WeatherSnapshot m = mergeOver(g, stateWith({cloudLayer(2, CloudType::Stratus, 3000, 500, 60)}));
    EXPECT_TRUE(m.dataWeight.empty());
    ASSERT_EQ(m.layers.size(), 1u) << "the file's layer has no cloud anywhere: the host's takes its slot";
    EXPECT_FLOAT_EQ(m.layers[0].coverage[cellAt(m, kOwnLat, kOwnLon)], 0.6f);
    EXPECT_FLOAT_EQ(m.layers[0].baseAltitudeM[cellAt(m, kOwnLat, kOwnLon)], 3000.0f);
}

HostDatagram regionDatagram(uint32_t frame, float coveragePct)
{
    HostDatagram d(ByteOrder::Big, frame);
    EnvironmentalRegionControl r;
    r.regionId = 3;
    r.regionState = uint8_t(RegionState::Active);
    r.mergeWeather = false;
    r.latDeg = kOwnLat;
    r.lonDeg = kOwnLon;
    r.sizeXM = r.sizeYM = 20000;
    r.transitionPerimeterM = 12000;
    d.add(ownshipAt(0, kOwnLat, kOwnLon, 3000)).add(r);
    d.add(cloudLayer(1, CloudType::Cumulus, 1000, 1000, coveragePct, 3));
    return d;
}

// Over a loaded file the host's weather is an overlay: the file's timeline and name stay, each of its
// samples is merged (outside the region the file's weather moves on with its timeline, inside the region's
// stays); with the file gone the host's weather is drawn alone, as it is without one.
TEST(CigiMerge, ApplierLaysTheHostsWeatherOverALoadedFile)
{
    ServiceState service;
    service.view.pose.latDeg = kOwnLat;
    service.view.pose.lonDeg = kOwnLon;
    auto file = std::make_shared<WeatherTimeline>();
    std::string error;
    ASSERT_TRUE(file->setSnapshots({gridded({{"low", 0.2f, 1000, 2000, CloudType::Stratocumulus}}, 1000),
                                    gridded({{"low", 0.6f, 1000, 2000, CloudType::Stratocumulus}}, 4600)},
                                   error))
        << error;
    service.weather.timeline = file;
    service.weather.source = "/data/model.skywx";
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, GeoidGrid{});
    auto send = [&](const HostDatagram& d)
    {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, service, 0.0);
    };
    send(regionDatagram(1, 100));
    EXPECT_EQ(service.weather.timeline, file) << "the file's timeline was replaced";
    ASSERT_TRUE(service.weather.overlay);
    EXPECT_EQ(weatherName(service.weather), "/data/model.skywx + cigi");
    EXPECT_TRUE(applier.statusJson()["over_gridded"].get<bool>());
    const WeatherSnapshot early = service.weather.overlay->over(file->sample(1000));
    const WeatherSnapshot later = service.weather.overlay->over(file->sample(2800));
    ASSERT_EQ(early.layers.size(), 1u);
    ASSERT_EQ(later.layers.size(), 1u);
    EXPECT_NEAR(coverageEast(early, 0, 60000), 0.2f, 1e-5);
    EXPECT_NEAR(coverageEast(later, 0, 60000), 0.4f, 1e-5) << "the merge did not follow the timeline";
    EXPECT_FLOAT_EQ(coverageEast(early, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(coverageEast(later, 0, 0), 1.0f);

    service.weather.timeline.reset(); // SIGHUP with weather = "builtin"
    service.weather.source = "builtin";
    ++service.weather.version;
    send(regionDatagram(2, 100));
    EXPECT_EQ(service.weather.source, "cigi");
    EXPECT_FALSE(service.weather.overlay);
    ASSERT_TRUE(service.weather.timeline);
    EXPECT_FALSE(applier.statusJson()["over_gridded"].get<bool>());
}

// The steps of a fade are small steps from the last one published; the first weather, and a step after
// another weather came in between, are not.
TEST(CigiMerge, FadeStepsArePublishedAsSmallSteps)
{
    ServiceState service;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, GeoidGrid{});
    auto send = [&](const HostDatagram& d, double nowS)
    {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, service, nowS);
    };
    auto drawn = [&] { service.frameWeather = FrameWeather{service.weather.version, "cigi", 0, true}; };
    auto small = [&] { return service.weather.smallStepFrom + 1 == service.weather.version; };
    send(regionDatagram(1, 100), 0.0);
    const uint64_t v0 = service.weather.version;
    EXPECT_FALSE(small()) << "the host's first weather";
    drawn();
    send(regionDatagram(2, 40), 10.0);
    applier.tick(state, service, 10.0 + kCigiFadeStepS);
    ASSERT_EQ(service.weather.version, v0 + 1);
    EXPECT_EQ(service.weather.smallStepFrom, v0);
    drawn();
    ++service.weather.version; // another weather swapped in meanwhile
    drawn();
    applier.tick(state, service, 10.0 + 2 * kCigiFadeStepS);
    ASSERT_EQ(service.weather.version, v0 + 3);
    EXPECT_FALSE(small()) << "a step over a weather it was not made from";
    drawn();
    applier.tick(state, service, 10.0 + 3 * kCigiFadeStepS);
    ASSERT_EQ(service.weather.version, v0 + 4);
    EXPECT_TRUE(small());
}

} // namespace
} // namespace sky
