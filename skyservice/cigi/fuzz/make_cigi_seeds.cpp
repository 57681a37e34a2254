// SPDX-License-Identifier: MIT
// Seeds for fuzz_cigi_decoder: a few well-formed host datagrams (every packet the IG reads, both byte
// orders), so that mutations start from deep inside the packet parser. usage: make_cigi_seeds DIR
#include "skyservice/cigi/cigi_packets.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

int main(int argc, char** argv)
{
    using namespace sky::cigi;
    if (argc != 2)
    {
        std::fprintf(stderr, "usage: make_cigi_seeds DIR\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    int n = 0;
    for (ByteOrder order : {ByteOrder::Big, ByteOrder::Little})
    {
        std::vector<uint8_t> d;
        encode(IgControl{}, order, d);
        EntityControl e;
        e.latDegOrXM = 47.5;
        e.lonDegOrYM = 10.25;
        e.altMslMOrZM = 3000;
        encode(e, order, d);
        CelestialSphereControl c;
        c.dateTimeValid = true;
        c.dateMMDDYYYY = 6212026;
        c.hour = 12;
        encode(c, order, d);
        encode(AtmosphereControl{}, order, d);
        EnvironmentalRegionControl r;
        r.regionState = 1;
        r.sizeXM = r.sizeYM = 5000;
        r.cornerRadiusM = 500;
        encode(r, order, d);
        WeatherControl w;
        w.layerId = 1;
        w.weatherEnable = true;
        w.cloudType = 10;
        w.coveragePct = 100;
        w.baseElevationM = 1000;
        w.thicknessM = 600;
        encode(w, order, d);
        w.scope = 1;
        encode(w, order, d);
        encode(ViewControl{}, order, d);
        ViewDefinition v;
        v.leftEnable = v.rightEnable = true;
        v.leftDeg = -30;
        v.rightDeg = 30;
        encode(v, order, d);
        encode(EnvironmentalConditionsRequest{}, order, d);
        std::ofstream(dir / ("host-" + std::to_string(n++)), std::ios::binary)
            .write(reinterpret_cast<const char*>(d.data()), static_cast<std::streamsize>(d.size()));
        d.resize(24);
        std::ofstream(dir / ("header-" + std::to_string(n++)), std::ios::binary)
            .write(reinterpret_cast<const char*>(d.data()), static_cast<std::streamsize>(d.size()));
    }
    return 0;
}
