// SPDX-License-Identifier: MIT
#include "skyservice/cigi/cigi_state.h"

#include "weather_ingest/civil_time.h"

#include <algorithm>
#include <cmath>

namespace sky::cigi
{
namespace
{

double wrapLonDeg(double lonDeg)
{
    const double wrapped = std::fmod(lonDeg + 180.0, 360.0);
    return (wrapped < 0 ? wrapped + 360.0 : wrapped) - 180.0;
}

struct Applier
{
    CigiState& state;
    uint16_t ownshipEntityId;
    uint32_t hostFrame;

    void operator()(const EntityControl& p)
    {
        // Attached entities are posed relative to a parent this IG does not model; other entities are not drawn.
        if (p.entityId != ownshipEntityId || p.attached)
        {
            ++state.otherEntityPackets;
            return;
        }
        OwnshipPose& o = state.ownship;
        o.valid = true;
        o.entityState = p.entityState;
        o.latDeg = p.latDegOrXM;
        o.lonDeg = wrapLonDeg(p.lonDegOrYM);
        o.altitudeMslM = p.altMslMOrZM;
        o.yawDeg = p.yawDeg;
        o.pitchDeg = p.pitchDeg;
        o.rollDeg = p.rollDeg;
    }

    void operator()(const CelestialSphereControl& p)
    {
        SimulatedTime& t = state.time;
        t.ephemerisEnable = p.ephemerisEnable;
        t.sunEnable = p.sunEnable;
        t.moonEnable = p.moonEnable;
        t.starFieldEnable = p.starFieldEnable;
        t.starFieldIntensityPct = p.starFieldIntensityPct;
        if (!p.dateTimeValid)
            return;  // the ICD: hour, minute and date are to be ignored
        t.valid = true;
        t.month = static_cast<int>(p.dateMMDDYYYY / 1000000u);
        t.day = static_cast<int>(p.dateMMDDYYYY / 10000u % 100u);
        t.year = static_cast<int>(p.dateMMDDYYYY % 10000u);
        t.hour = p.hour;
        t.minute = p.minute;
        t.seconds = 0;
        t.setAtHostFrame = hostFrame;
    }

    void operator()(const AtmosphereControl& p)
    {
        AtmosphereState& a = state.atmosphere;
        a.set = true;
        a.modelEnable = p.atmosphericModelEnable;
        a.humidityPct = p.humidityPct;
        a.airTemperatureC = p.airTemperatureC;
        a.visibilityM = p.visibilityM;
        a.horizontalWindMps = p.horizontalWindMps;
        a.verticalWindMps = p.verticalWindMps;
        a.windDirectionDeg = p.windDirectionDeg;
        a.pressureHpa = p.pressureHpa;
    }

    void operator()(const EnvironmentalRegionControl& p)
    {
        EnvironmentalRegion& r = state.regions[p.regionId];
        const RegionState newState = static_cast<RegionState>(p.regionState);
        if (!r.defined || r.state != newState)
            r.stateChangedAtHostFrame = hostFrame;
        r.regionId = p.regionId;
        r.defined = true;
        r.state = newState;
        r.mergeWeather = p.mergeWeather;
        r.mergeAerosol = p.mergeAerosol;
        r.mergeMaritime = p.mergeMaritime;
        r.mergeTerrestrial = p.mergeTerrestrial;
        r.latDeg = p.latDeg;
        r.lonDeg = wrapLonDeg(p.lonDeg);
        r.sizeXM = p.sizeXM;
        r.sizeYM = p.sizeYM;
        r.cornerRadiusM = std::min(p.cornerRadiusM, 0.5f * std::min(p.sizeXM, p.sizeYM));
        r.rotationDeg = p.rotationDeg;
        r.transitionPerimeterM = p.transitionPerimeterM;
    }

    void operator()(const WeatherControl& p)
    {
        const WeatherScope scope = static_cast<WeatherScope>(p.scope);
        if (scope == WeatherScope::Entity)
        {
            ++state.entityWeatherPackets;
            return;
        }
        std::map<uint8_t, WeatherLayer>& layers =
            scope == WeatherScope::Global ? state.globalLayers : state.regions[p.entityOrRegionId].layers;
        if (scope == WeatherScope::Regional)
            state.regions[p.entityOrRegionId].regionId = p.entityOrRegionId;
        WeatherLayer& l = layers[p.layerId];
        l.layerId = p.layerId;
        l.enabled = p.weatherEnable;
        l.cloudType = static_cast<CloudType>(p.cloudType);
        l.baseElevationMslM = p.baseElevationM;
        l.thicknessM = p.thicknessM;
        l.transitionBandM = p.transitionBandM;
        l.coveragePct = p.coveragePct;
        l.visibilityM = p.visibilityM;
        l.humidityPct = p.humidityPct;
        l.airTemperatureC = p.airTemperatureC;
        l.pressureHpa = p.pressureHpa;
        l.aerosolGPerM3 = p.aerosolGPerM3;
        l.horizontalWindMps = p.horizontalWindMps;
        l.verticalWindMps = p.verticalWindMps;
        l.windDirectionDeg = p.windDirectionDeg;
        l.scudEnable = p.scudEnable;
        l.randomWindsEnable = p.randomWindsEnable;
        l.randomLightningEnable = p.randomLightningEnable;
        l.scudFrequencyPct = p.scudFrequencyPct;
        l.severity = p.severity;
        l.setAtHostFrame = hostFrame;
    }

    void applyViewControl(ViewState& v, const ViewControl& p)
    {
        v.controlled = true;
        v.entityId = p.entityId;
        if (p.xOffsetEnable)
            v.xOffsetM = p.xOffsetM;
        if (p.yOffsetEnable)
            v.yOffsetM = p.yOffsetM;
        if (p.zOffsetEnable)
            v.zOffsetM = p.zOffsetM;
        if (p.rollEnable)
            v.rollDeg = p.rollDeg;
        if (p.pitchEnable)
            v.pitchDeg = p.pitchDeg;
        if (p.yawEnable)
            v.yawDeg = p.yawDeg;
    }

    void operator()(const ViewControl& p)
    {
        // Group ID 0 addresses the one view; otherwise every view a View Definition put in that group.
        if (p.groupId == 0)
        {
            ViewState& v = state.views[p.viewId];
            v.viewId = p.viewId;
            applyViewControl(v, p);
            return;
        }
        for (auto& [id, v] : state.views)
            if (v.groupId == p.groupId)
                applyViewControl(v, p);
    }

    void operator()(const ViewDefinition& p)
    {
        ViewState& v = state.views[p.viewId];
        v.viewId = p.viewId;
        v.groupId = p.groupId;
        v.defined = true;
        v.mirrorMode = p.mirrorMode;
        v.orthographic = p.orthographic;
        if (p.nearEnable)
            v.nearM = p.nearM;
        if (p.farEnable)
            v.farM = p.farM;
        if (p.leftEnable)
            v.leftDeg = p.leftDeg;
        if (p.rightEnable)
            v.rightDeg = p.rightDeg;
        if (p.topEnable)
            v.topDeg = p.topDeg;
        if (p.bottomEnable)
            v.bottomDeg = p.bottomDeg;
    }

    void operator()(const EnvironmentalConditionsRequest& p) { state.pendingRequests.push_back(p); }
};

} // namespace

double SimulatedTime::unixTimeS() const
{
    return static_cast<double>(unixTimeFromCivil(year, month, day, hour, minute, 0)) + seconds;
}

double simulatedUnixTimeS(const SimulatedTime& time, double secondsSinceSet)
{
    return time.unixTimeS() + (time.ephemerisEnable ? std::max(0.0, secondsSinceSet) : 0.0);
}

void applyDatagram(CigiState& state, const DecodeResult& datagram, uint16_t ownshipEntityId)
{
    if (!datagram.accepted)
        return;
    const IgControl& ig = datagram.igControl;
    state.lastHostFrame = ig.hostFrameNumber;
    state.hostTimestamp10us = ig.timestamp10us;
    state.igMode = ig.igMode;
    state.databaseNumber = ig.databaseNumber;
    state.hostByteOrder = datagram.order;
    ++state.datagramsApplied;
    Applier applier{state, ownshipEntityId, ig.hostFrameNumber};
    for (const HostPacket& packet : datagram.packets)
        std::visit(applier, packet);
}

void pruneDestroyedRegions(CigiState& state, uint32_t hostFrame)
{
    std::erase_if(state.regions, [hostFrame](const auto& entry) {
        const EnvironmentalRegion& r = entry.second;
        return r.defined && r.state == RegionState::Destroyed && r.stateChangedAtHostFrame <= hostFrame;
    });
}

} // namespace sky::cigi
