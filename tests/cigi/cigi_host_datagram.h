// SPDX-License-Identifier: MIT
// A test host's datagram: IG Control with the host frame number, then any packets, in the host's byte
// order (the encoder side of skyservice/cigi/cigi_packets.h), and the packets a test host sends most.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <vector>

namespace sky::cigi::test
{

class HostDatagram
{
  public:
    HostDatagram(ByteOrder order, uint32_t hostFrame) : order_(order)
    {
        IgControl ig;
        ig.hostFrameNumber = hostFrame;
        ig.igMode = 1; // Operate
        encode(ig, order_, bytes_);
    }
    template <typename Packet> HostDatagram& add(const Packet& p)
    {
        encode(p, order_, bytes_);
        return *this;
    }
    const std::vector<uint8_t>& bytes() const { return bytes_; }
    ByteOrder order() const { return order_; }

  private:
    ByteOrder order_;
    std::vector<uint8_t> bytes_;
};

inline EntityControl ownshipAt(uint16_t id, double latDeg, double lonDeg, double altMslM, float yawDeg = 0,
                               float pitchDeg = 0, float rollDeg = 0)
{
    EntityControl e;
    e.entityId = id;
    e.entityState = 1;
    e.latDegOrXM = latDeg;
    e.lonDegOrYM = lonDeg;
    e.altMslMOrZM = altMslM;
    e.yawDeg = yawDeg;
    e.pitchDeg = pitchDeg;
    e.rollDeg = rollDeg;
    return e;
}

/// Date and time (UTC) valid; ephemeris off unless asked: the time stays where it is set.
inline CelestialSphereControl celestialAt(uint32_t dateMMDDYYYY, uint8_t hour, uint8_t minute, bool ephemeris = false)
{
    CelestialSphereControl c;
    c.dateMMDDYYYY = dateMMDDYYYY;
    c.hour = hour;
    c.minute = minute;
    c.dateTimeValid = true;
    c.ephemerisEnable = ephemeris;
    c.sunEnable = c.moonEnable = c.starFieldEnable = true;
    c.starFieldIntensityPct = 100;
    return c;
}

/// A global (or, with regionId >= 0, regional) cloud layer.
inline WeatherControl cloudLayer(uint8_t layerId, CloudType type, float baseMslM, float thicknessM, float coveragePct,
                                 int regionId = -1)
{
    WeatherControl w;
    w.layerId = layerId;
    w.weatherEnable = true;
    w.cloudType = uint8_t(type);
    w.scope = uint8_t(regionId >= 0 ? WeatherScope::Regional : WeatherScope::Global);
    w.entityOrRegionId = uint16_t(regionId >= 0 ? regionId : 0);
    w.baseElevationM = baseMslM;
    w.thicknessM = thicknessM;
    w.coveragePct = coveragePct;
    w.visibilityM = 50000;
    w.humidityPct = 80;
    return w;
}

inline ViewDefinition viewDefinition(uint16_t viewId, float leftDeg, float rightDeg, float topDeg, float bottomDeg)
{
    ViewDefinition v;
    v.viewId = viewId;
    v.leftEnable = v.rightEnable = v.topEnable = v.bottomEnable = true;
    v.nearEnable = v.farEnable = true;
    v.nearM = 1;
    v.farM = 200000;
    v.leftDeg = leftDeg;
    v.rightDeg = rightDeg;
    v.topDeg = topDeg;
    v.bottomDeg = bottomDeg;
    return v;
}

inline EnvironmentalConditionsRequest conditionsRequest(uint8_t id, double latDeg, double lonDeg, double altMslM,
                                                        uint8_t type = kRequestWeather)
{
    EnvironmentalConditionsRequest r;
    r.requestId = id;
    r.requestType = type;
    r.latDeg = latDeg;
    r.lonDeg = lonDeg;
    r.altMslM = altMslM;
    return r;
}

} // namespace sky::cigi::test
