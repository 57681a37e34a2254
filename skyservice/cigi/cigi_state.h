// SPDX-License-Identifier: MIT
// The IG-side state that CIGI host packets drive, as plain data the renderer can read: the ownship's pose,
// each view's offset and frustum, the simulated UTC, the atmosphere, the global and regional weather layers
// and the environmental regions. Applying a decoded datagram updates it; nothing ages out on its own, so
// a host that stops sending leaves the last state in place. Altitudes are as the host sent them (above
// mean sea level); geoid_undulation.h turns them into ellipsoid heights.
#pragma once

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <map>
#include <vector>

namespace sky::cigi
{

struct OwnshipPose
{
    bool valid = false;  ///< an Entity Control for the ownship has been applied
    double latDeg = 0;
    double lonDeg = 0;   ///< wrapped to [-180, 180)
    double altitudeMslM = 0;
    double yawDeg = 0;   ///< heading from true north, clockwise
    double pitchDeg = 0;
    double rollDeg = 0;
    uint8_t entityState = 1;  ///< as sent: 0 Inactive/Standby, 1 Active, 2 Destroyed
};

/// One view (channel). Offsets are in the ownship's body axes (X forward, Y right, Z down), angles relative
/// to the ownship's attitude; the frustum's half-angles are signed (left and bottom usually negative).
struct ViewState
{
    uint16_t viewId = 0;
    uint8_t groupId = 0;      ///< from View Definition
    uint16_t entityId = 0;    ///< the entity the view is attached to (View Control)
    float xOffsetM = 0, yOffsetM = 0, zOffsetM = 0;
    float rollDeg = 0, pitchDeg = 0, yawDeg = 0;
    // Until a View Definition sets them: a 60° x 40° symmetric view, 1 m to 100 km.
    float leftDeg = -30, rightDeg = 30, topDeg = 20, bottomDeg = -20;
    float nearM = 1, farM = 100000;
    uint8_t mirrorMode = 0;
    bool orthographic = false;
    bool controlled = false;  ///< a View Control has been applied
    bool defined = false;     ///< a View Definition has been applied
};

/// Simulated UTC from Celestial Sphere Control. CIGI 3.3 sends hours and minutes only, so seconds start at
/// 0 each time the host sets the time; with the ephemeris model enabled the IG lets it run on from there.
struct SimulatedTime
{
    bool valid = false;  ///< a Celestial Sphere Control with Date/Time Valid has been applied
    int year = 2000, month = 1, day = 1, hour = 12, minute = 0;
    double seconds = 0;
    bool ephemerisEnable = false, sunEnable = true, moonEnable = true, starFieldEnable = true;
    float starFieldIntensityPct = 100;
    uint32_t setAtHostFrame = 0;  ///< host frame of the IG Control that came with it

    /// Seconds since 1970-01-01T00:00:00Z of the time as set (proleptic Gregorian, no leap seconds).
    double unixTimeS() const;
};

/// The simulated UTC `secondsSinceSet` of IG time after the host set it: frozen unless the ephemeris runs.
double simulatedUnixTimeS(const SimulatedTime& time, double secondsSinceSet);

struct AtmosphereState
{
    bool set = false;  ///< an Atmosphere Control has been applied
    bool modelEnable = false;
    float humidityPct = 0, airTemperatureC = 15, visibilityM = 0;
    float horizontalWindMps = 0, verticalWindMps = 0, windDirectionDeg = 0, pressureHpa = 1013.25f;
};

/// One weather layer as the host last set it (Weather Control; all fields kept, used or not).
struct WeatherLayer
{
    uint8_t layerId = 0;  ///< 0 ground fog, 1-3 cloud layers, 4 rain, 5 snow, 6 sleet, 7 hail, 8 sand, 9 dust
    bool enabled = false;
    CloudType cloudType = CloudType::None;  ///< 11-15 ("Other") are kept as their number
    float baseElevationMslM = 0, thicknessM = 0, transitionBandM = 0, coveragePct = 0;
    float visibilityM = 0, humidityPct = 0, airTemperatureC = 0, pressureHpa = 0, aerosolGPerM3 = 0;
    float horizontalWindMps = 0, verticalWindMps = 0, windDirectionDeg = 0;
    bool scudEnable = false, randomWindsEnable = false, randomLightningEnable = false;
    float scudFrequencyPct = 0;
    uint8_t severity = 0;
    uint32_t setAtHostFrame = 0;  ///< lets the renderer fade a change in from the frame it arrived
};

/// An environmental region: a rectangle sizeX x sizeY (X along `rotationDeg` from true north) with rounded
/// corners, centred at lat/lon, whose weather fades out over `transitionPerimeterM` outside it.
struct EnvironmentalRegion
{
    uint16_t regionId = 0;
    bool defined = false;  ///< an Environmental Region Control has been applied (layers may come first)
    RegionState state = RegionState::Inactive;
    bool mergeWeather = false, mergeAerosol = false, mergeMaritime = false, mergeTerrestrial = false;
    double latDeg = 0, lonDeg = 0;
    float sizeXM = 0, sizeYM = 0;
    float cornerRadiusM = 0;  ///< clamped to half the smaller side
    float rotationDeg = 0, transitionPerimeterM = 0;
    uint32_t stateChangedAtHostFrame = 0;  ///< for fading in (Active) or out (Destroyed)
    std::map<uint8_t, WeatherLayer> layers;  ///< by layer id
};

struct CigiState
{
    uint32_t lastHostFrame = 0;  ///< from the last accepted IG Control
    uint32_t hostTimestamp10us = 0;
    uint8_t igMode = 0;          ///< as the host requests: 0 Reset/Standby, 1 Operate, 2 Debug
    int8_t databaseNumber = 0;
    ByteOrder hostByteOrder = ByteOrder::Big;
    uint64_t datagramsApplied = 0;

    OwnshipPose ownship;
    std::map<uint16_t, ViewState> views;  ///< by view id
    SimulatedTime time;
    AtmosphereState atmosphere;
    std::map<uint8_t, WeatherLayer> globalLayers;       ///< by layer id
    std::map<uint16_t, EnvironmentalRegion> regions;    ///< by region id (destroyed ones stay, state Destroyed)
    /// Requests not yet answered, in arrival order: the daemon answers them (109/110) and clears the list.
    std::vector<EnvironmentalConditionsRequest> pendingRequests;

    uint64_t otherEntityPackets = 0;   ///< Entity Control for entities other than the ownship (not drawn)
    uint64_t entityWeatherPackets = 0; ///< Weather Control with entity scope (not drawn)
};

/// Applies an accepted datagram in packet order (a later packet overrides an earlier one); a datagram that
/// was not accepted changes nothing. `ownshipEntityId` is the entity whose pose drives the eye.
void applyDatagram(CigiState& state, const DecodeResult& datagram, uint16_t ownshipEntityId);

/// Removes destroyed regions whose state changed at or before `hostFrame` (after the renderer faded them).
void pruneDestroyedRegions(CigiState& state, uint32_t hostFrame);

} // namespace sky::cigi
