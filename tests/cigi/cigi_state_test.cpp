// SPDX-License-Identifier: MIT
// The IG-side state after a scripted host sequence: ownship, views, time, atmosphere, global and regional
// weather, regions; bad datagrams and silence leave it as it was.
#include "cigi_samples.h"

#include "skyservice/cigi/cigi_state.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace sky::cigi
{
namespace
{

constexpr uint16_t kOwnship = 7;

// A small scripted host: each frame's datagram in the host's byte order.
class ScriptedHost
{
public:
    explicit ScriptedHost(ByteOrder order) : order_(order) {}
    ScriptedHost& frame(uint32_t hostFrame)
    {
        datagram_.clear();
        IgControl ig;
        ig.hostFrameNumber = hostFrame;
        encode(ig, order_, datagram_);
        return *this;
    }
    template <typename Packet>
    ScriptedHost& add(const Packet& p)
    {
        encode(p, order_, datagram_);
        return *this;
    }
    void send(Decoder& decoder, CigiState& state) const
    {
        applyDatagram(state, decoder.decode(datagram_.data(), datagram_.size()), kOwnship);
    }
    std::vector<uint8_t>& bytes() { return datagram_; }

private:
    ByteOrder order_;
    std::vector<uint8_t> datagram_;
};

EntityControl ownshipAt(double latDeg, double lonDeg, double altMslM, float yawDeg)
{
    EntityControl e;
    e.entityId = kOwnship;
    e.latDegOrXM = latDeg;
    e.lonDegOrYM = lonDeg;
    e.altMslMOrZM = altMslM;
    e.yawDeg = yawDeg;
    e.pitchDeg = 2.5f;
    e.rollDeg = -1.0f;
    return e;
}

WeatherControl stratus(float baseM, float thicknessM, float coveragePct)
{
    WeatherControl w;
    w.layerId = kLayerCloud1;
    w.weatherEnable = true;
    w.cloudType = static_cast<uint8_t>(CloudType::Stratus);
    w.scope = static_cast<uint8_t>(WeatherScope::Global);
    w.baseElevationM = baseM;
    w.thicknessM = thicknessM;
    w.coveragePct = coveragePct;
    w.transitionBandM = 50;
    w.visibilityM = 100;
    w.horizontalWindMps = 5;
    w.windDirectionDeg = 270;
    w.pressureHpa = 900;
    return w;
}

class CigiStateScript : public ::testing::TestWithParam<ByteOrder>
{
};

TEST_P(CigiStateScript, HostSequenceDrivesTheState)
{
    ScriptedHost host(GetParam());
    Decoder decoder;
    CigiState state;

    // Frame 1: ownship, time, one global Stratus deck, two half views of a display wall.
    CelestialSphereControl sky;
    sky.hour = 14;
    sky.minute = 30;
    sky.dateMMDDYYYY = 3202026;
    sky.dateTimeValid = true;
    sky.ephemerisEnable = true;
    sky.sunEnable = true;
    ViewDefinition left;
    left.viewId = 0;
    left.groupId = 1;
    left.leftEnable = left.rightEnable = left.topEnable = left.bottomEnable = left.nearEnable = true;
    left.leftDeg = -40;
    left.rightDeg = 0;
    left.topDeg = 15;
    left.bottomDeg = -15;
    left.nearM = 0.5f;
    ViewDefinition right = left;
    right.viewId = 1;
    right.leftDeg = 0;
    right.rightDeg = 40;
    EntityControl otherAircraft = ownshipAt(10, 10, 100, 0);
    otherAircraft.entityId = 99;
    host.frame(1)
        .add(ownshipAt(47.5, 190.25, 3000, 90))  // longitude beyond 180 is wrapped
        .add(sky)
        .add(stratus(1000, 600, 100))
        .add(left)
        .add(right)
        .add(otherAircraft)
        .send(decoder, state);

    EXPECT_EQ(state.lastHostFrame, 1u);
    EXPECT_EQ(state.hostByteOrder, GetParam());
    ASSERT_TRUE(state.ownship.valid);
    EXPECT_DOUBLE_EQ(state.ownship.latDeg, 47.5);
    EXPECT_DOUBLE_EQ(state.ownship.lonDeg, -169.75);
    EXPECT_DOUBLE_EQ(state.ownship.altitudeMslM, 3000);
    EXPECT_DOUBLE_EQ(state.ownship.yawDeg, 90);
    EXPECT_DOUBLE_EQ(state.ownship.pitchDeg, 2.5);
    EXPECT_EQ(state.otherEntityPackets, 1u);
    ASSERT_TRUE(state.time.valid);
    EXPECT_EQ(state.time.year, 2026);
    EXPECT_EQ(state.time.month, 3);
    EXPECT_EQ(state.time.day, 20);
    // 2026-03-20T14:30:00Z
    EXPECT_DOUBLE_EQ(state.time.unixTimeS(), 1774017000.0);
    EXPECT_DOUBLE_EQ(simulatedUnixTimeS(state.time, 10), 1774017010.0);  // the ephemeris runs
    ASSERT_EQ(state.globalLayers.count(kLayerCloud1), 1u);
    const WeatherLayer& deck = state.globalLayers.at(kLayerCloud1);
    EXPECT_TRUE(deck.enabled);
    EXPECT_EQ(deck.cloudType, CloudType::Stratus);
    EXPECT_FLOAT_EQ(deck.baseElevationMslM, 1000);
    EXPECT_FLOAT_EQ(deck.thicknessM, 600);
    EXPECT_FLOAT_EQ(deck.coveragePct, 100);
    EXPECT_FLOAT_EQ(deck.transitionBandM, 50);
    EXPECT_EQ(deck.setAtHostFrame, 1u);
    ASSERT_EQ(state.views.size(), 2u);
    EXPECT_FLOAT_EQ(state.views.at(0).leftDeg, -40);
    EXPECT_FLOAT_EQ(state.views.at(0).rightDeg, 0);
    EXPECT_FLOAT_EQ(state.views.at(1).leftDeg, 0);
    EXPECT_FLOAT_EQ(state.views.at(1).rightDeg, 40);
    EXPECT_FLOAT_EQ(state.views.at(1).nearM, 0.5f);
    EXPECT_FLOAT_EQ(state.views.at(1).farM, 100000);  // far not enabled: the default stays

    // Frame 2: fog layer, rain, atmosphere, a region with its own layer, a group view offset, a request.
    WeatherControl fog = stratus(0, 80, 100);
    fog.layerId = kLayerGroundFog;
    fog.cloudType = 0;
    fog.visibilityM = 300;
    WeatherControl rain = stratus(0, 1000, 60);
    rain.layerId = kLayerRain;
    rain.cloudType = 0;
    AtmosphereControl air;
    air.atmosphericModelEnable = true;
    air.humidityPct = 80;
    air.visibilityM = 30000;
    air.horizontalWindMps = 7;
    air.windDirectionDeg = 200;
    air.pressureHpa = 1010;
    EnvironmentalRegionControl region;
    region.regionId = 4;
    region.regionState = static_cast<uint8_t>(RegionState::Active);
    region.mergeWeather = true;
    region.latDeg = 47.6;
    region.lonDeg = 10.4;
    region.sizeXM = 10000;
    region.sizeYM = 4000;
    region.cornerRadiusM = 3000;  // more than half the short side: clamped to 2000
    region.rotationDeg = 30;
    region.transitionPerimeterM = 1500;
    WeatherControl regional = stratus(2500, 400, 70);
    regional.scope = static_cast<uint8_t>(WeatherScope::Regional);
    regional.entityOrRegionId = 4;
    regional.cloudType = static_cast<uint8_t>(CloudType::Cumulus);
    ViewControl eyeOffset;
    eyeOffset.groupId = 1;  // both views of group 1
    eyeOffset.entityId = kOwnship;
    eyeOffset.xOffsetEnable = eyeOffset.zOffsetEnable = eyeOffset.yawEnable = true;
    eyeOffset.xOffsetM = 3;
    eyeOffset.yOffsetM = 99;  // not enabled: ignored
    eyeOffset.zOffsetM = -1.5f;
    eyeOffset.yawDeg = 5;
    EnvironmentalConditionsRequest ask;
    ask.requestType = kRequestWeather;
    ask.requestId = 9;
    ask.latDeg = 47.5;
    ask.lonDeg = 10.25;
    ask.altMslM = 1300;
    host.frame(2).add(fog).add(rain).add(air).add(region).add(regional).add(eyeOffset).add(ask).send(decoder, state);

    EXPECT_EQ(state.globalLayers.size(), 3u);
    EXPECT_FLOAT_EQ(state.globalLayers.at(kLayerGroundFog).visibilityM, 300);
    EXPECT_FLOAT_EQ(state.globalLayers.at(kLayerRain).coveragePct, 60);
    EXPECT_EQ(state.globalLayers.at(kLayerCloud1).setAtHostFrame, 1u);  // untouched since frame 1
    EXPECT_TRUE(state.atmosphere.set);
    EXPECT_FLOAT_EQ(state.atmosphere.visibilityM, 30000);
    EXPECT_FLOAT_EQ(state.atmosphere.humidityPct, 80);
    ASSERT_EQ(state.regions.count(4), 1u);
    const EnvironmentalRegion& r = state.regions.at(4);
    EXPECT_TRUE(r.defined);
    EXPECT_EQ(r.state, RegionState::Active);
    EXPECT_TRUE(r.mergeWeather);
    EXPECT_FLOAT_EQ(r.cornerRadiusM, 2000);
    EXPECT_FLOAT_EQ(r.rotationDeg, 30);
    EXPECT_FLOAT_EQ(r.transitionPerimeterM, 1500);
    ASSERT_EQ(r.layers.count(kLayerCloud1), 1u);
    EXPECT_EQ(r.layers.at(kLayerCloud1).cloudType, CloudType::Cumulus);
    EXPECT_EQ(r.stateChangedAtHostFrame, 2u);
    for (uint16_t id : {uint16_t{0}, uint16_t{1}})
    {
        const ViewState& v = state.views.at(id);
        EXPECT_FLOAT_EQ(v.xOffsetM, 3);
        EXPECT_FLOAT_EQ(v.yOffsetM, 0);
        EXPECT_FLOAT_EQ(v.zOffsetM, -1.5f);
        EXPECT_FLOAT_EQ(v.yawDeg, 5);
        EXPECT_FLOAT_EQ(v.pitchDeg, 0);
    }
    ASSERT_EQ(state.pendingRequests.size(), 1u);
    EXPECT_EQ(state.pendingRequests[0].requestId, 9);

    // Frame 3: a datagram whose deck is bad (NaN thickness) changes nothing of the deck, but its good
    // ownship packet still applies; a datagram with a bad header changes nothing at all.
    WeatherControl broken = stratus(1000, 600, 100);
    broken.thicknessM = std::numeric_limits<float>::quiet_NaN();
    host.frame(3).add(broken).add(ownshipAt(47.5, 10.25, 500, 90)).send(decoder, state);
    EXPECT_FLOAT_EQ(state.globalLayers.at(kLayerCloud1).thicknessM, 600);
    EXPECT_DOUBLE_EQ(state.ownship.altitudeMslM, 500);
    EXPECT_EQ(decoder.counters().error(DecodeErrorKind::BadValue), 1u);
    host.frame(4).add(ownshipAt(0, 0, 0, 0));
    host.bytes()[6] = 0x42;  // bad magic
    host.send(decoder, state);
    EXPECT_EQ(state.lastHostFrame, 3u);
    EXPECT_DOUBLE_EQ(state.ownship.altitudeMslM, 500);

    // Frame 5: the region is destroyed: it stays, marked, until pruned.
    region.regionState = static_cast<uint8_t>(RegionState::Destroyed);
    host.frame(5).add(region).send(decoder, state);
    EXPECT_EQ(state.regions.at(4).state, RegionState::Destroyed);
    EXPECT_EQ(state.regions.at(4).stateChangedAtHostFrame, 5u);
    pruneDestroyedRegions(state, 4);
    EXPECT_EQ(state.regions.count(4), 1u);
    pruneDestroyedRegions(state, 5);
    EXPECT_EQ(state.regions.count(4), 0u);
}

std::string byteOrderName(const ::testing::TestParamInfo<ByteOrder>& info)
{
    return info.param == ByteOrder::Big ? "Big" : "Little";
}

INSTANTIATE_TEST_SUITE_P(ByteOrders, CigiStateScript, ::testing::Values(ByteOrder::Big, ByteOrder::Little),
                         byteOrderName);

TEST(CigiState, DateTimeNotValidLeavesTheTime)
{
    CigiState state;
    DecodeResult d;
    d.accepted = true;
    CelestialSphereControl c;
    c.hour = 3;
    c.dateTimeValid = false;
    c.moonEnable = false;
    d.packets.emplace_back(c);
    applyDatagram(state, d, kOwnship);
    EXPECT_FALSE(state.time.valid);
    EXPECT_EQ(state.time.hour, 12);
    EXPECT_FALSE(state.time.moonEnable);
    EXPECT_DOUBLE_EQ(simulatedUnixTimeS(state.time, 100), state.time.unixTimeS());  // ephemeris off: frozen
}

} // namespace
} // namespace sky::cigi
