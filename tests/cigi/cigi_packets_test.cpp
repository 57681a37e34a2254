// SPDX-License-Identifier: MIT
// Every packet survives encode -> decode in both byte orders, and the bytes sit where the ICD puts them.
#include "cigi_samples.h"

#include "skyservice/cigi/cigi_decoder.h"

#include <gtest/gtest.h>

namespace sky::cigi
{
namespace
{

using namespace sky::cigi::test;

template <typename Packet, typename Decode>
void expectRoundTrip(const Packet& sample, Decode decodeFn, uint8_t opcode, uint8_t size)
{
    for (ByteOrder order : {ByteOrder::Big, ByteOrder::Little})
    {
        SCOPED_TRACE(order == ByteOrder::Big ? "big-endian" : "little-endian");
        std::vector<uint8_t> bytes;
        encode(sample, order, bytes);
        ASSERT_EQ(bytes.size(), size);
        EXPECT_EQ(bytes[0], opcode);
        EXPECT_EQ(bytes[1], size);
        EXPECT_EQ(decodeFn(bytes.data(), order), sample);
        // Read in the other order, a packet with multi-byte fields must come back different.
        const ByteOrder other = order == ByteOrder::Big ? ByteOrder::Little : ByteOrder::Big;
        EXPECT_NE(decodeFn(bytes.data(), other), sample);
    }
}

TEST(CigiPackets, RoundTripEveryPacketBothByteOrders)
{
    expectRoundTrip(sampleIgControl(), decodeIgControl, kOpIgControl, kSizeIgControl);
    expectRoundTrip(sampleEntityControl(), decodeEntityControl, kOpEntityControl, kSizeEntityControl);
    expectRoundTrip(sampleCelestialSphereControl(), decodeCelestialSphereControl, kOpCelestialSphereControl,
                    kSizeCelestialSphereControl);
    expectRoundTrip(sampleAtmosphereControl(), decodeAtmosphereControl, kOpAtmosphereControl, kSizeAtmosphereControl);
    expectRoundTrip(sampleEnvironmentalRegionControl(), decodeEnvironmentalRegionControl,
                    kOpEnvironmentalRegionControl, kSizeEnvironmentalRegionControl);
    expectRoundTrip(sampleWeatherControl(), decodeWeatherControl, kOpWeatherControl, kSizeWeatherControl);
    expectRoundTrip(sampleViewControl(), decodeViewControl, kOpViewControl, kSizeViewControl);
    expectRoundTrip(sampleViewDefinition(), decodeViewDefinition, kOpViewDefinition, kSizeViewDefinition);
    expectRoundTrip(sampleEnvironmentalConditionsRequest(), decodeEnvironmentalConditionsRequest,
                    kOpEnvironmentalConditionsRequest, kSizeEnvironmentalConditionsRequest);
    expectRoundTrip(sampleStartOfFrame(), decodeStartOfFrame, kOpStartOfFrame, kSizeStartOfFrame);
    expectRoundTrip(sampleWeatherConditionsResponse(), decodeWeatherConditionsResponse, kOpWeatherConditionsResponse,
                    kSizeWeatherConditionsResponse);
    expectRoundTrip(sampleAerosolConcentrationResponse(), decodeAerosolConcentrationResponse,
                    kOpAerosolConcentrationResponse, kSizeAerosolConcentrationResponse);
}

TEST(CigiPackets, IgControlBytesAtTheirIcdOffsets)
{
    std::vector<uint8_t> big, little;
    encode(sampleIgControl(), ByteOrder::Big, big);
    encode(sampleIgControl(), ByteOrder::Little, little);
    EXPECT_EQ(big[2], 3);     // major version
    EXPECT_EQ(big[3], 0xFB);  // database -5
    // byte 4: mode 2 (bits 0-1) | timestamp valid (bit 2) | extrapolation (bit 3) | minor version 3 (bits 4-7)
    EXPECT_EQ(big[4], 0x02 | 0x04 | 0x08 | 0x30);
    EXPECT_EQ(big[6], 0x80);  // magic in the sender's order
    EXPECT_EQ(big[7], 0x00);
    EXPECT_EQ(little[6], 0x00);
    EXPECT_EQ(little[7], 0x80);
    EXPECT_EQ((std::vector<uint8_t>(big.begin() + 8, big.begin() + 12)), (std::vector<uint8_t>{1, 2, 3, 4}));
    EXPECT_EQ((std::vector<uint8_t>(little.begin() + 8, little.begin() + 12)), (std::vector<uint8_t>{4, 3, 2, 1}));
}

TEST(CigiPackets, WeatherControlBitsAndFloatsAtTheirIcdOffsets)
{
    std::vector<uint8_t> big;
    encode(sampleWeatherControl(), ByteOrder::Big, big);
    EXPECT_EQ(big[4], 2);   // layer id
    EXPECT_EQ(big[5], 88);  // humidity
    EXPECT_EQ(big[6], 0x01 | 0x04 | (9 << 4));  // enable, random winds, cloud type 9 in bits 4-7
    EXPECT_EQ(big[7], 1 | (4 << 2));            // scope regional, severity 4 in bits 2-4
    // Coverage 62.5 = 0x427A0000 at byte 20, big-endian.
    EXPECT_EQ((std::vector<uint8_t>(big.begin() + 20, big.begin() + 24)), (std::vector<uint8_t>{0x42, 0x7A, 0, 0}));
}

TEST(CigiPackets, WholeDatagramDecodesInEitherByteOrder)
{
    for (ByteOrder order : {ByteOrder::Big, ByteOrder::Little})
    {
        std::vector<uint8_t> datagram;
        encode(sampleIgControl(), order, datagram);
        encode(sampleEntityControl(), order, datagram);
        encode(sampleCelestialSphereControl(), order, datagram);
        encode(sampleAtmosphereControl(), order, datagram);
        encode(sampleEnvironmentalRegionControl(), order, datagram);
        encode(sampleWeatherControl(), order, datagram);
        encode(sampleViewControl(), order, datagram);
        encode(sampleViewDefinition(), order, datagram);
        encode(sampleEnvironmentalConditionsRequest(), order, datagram);
        Decoder decoder;
        const DecodeResult r = decoder.decode(datagram.data(), datagram.size());
        ASSERT_TRUE(r.accepted);
        EXPECT_TRUE(r.errors.empty()) << r.errors.front().message;
        EXPECT_EQ(r.order, order);
        EXPECT_EQ(r.igControl, sampleIgControl());
        ASSERT_EQ(r.packets.size(), 8u);
        EXPECT_EQ(std::get<EntityControl>(r.packets[0]), sampleEntityControl());
        EXPECT_EQ(std::get<CelestialSphereControl>(r.packets[1]), sampleCelestialSphereControl());
        EXPECT_EQ(std::get<AtmosphereControl>(r.packets[2]), sampleAtmosphereControl());
        EXPECT_EQ(std::get<EnvironmentalRegionControl>(r.packets[3]), sampleEnvironmentalRegionControl());
        EXPECT_EQ(std::get<WeatherControl>(r.packets[4]), sampleWeatherControl());
        EXPECT_EQ(std::get<ViewControl>(r.packets[5]), sampleViewControl());
        EXPECT_EQ(std::get<ViewDefinition>(r.packets[6]), sampleViewDefinition());
        EXPECT_EQ(std::get<EnvironmentalConditionsRequest>(r.packets[7]), sampleEnvironmentalConditionsRequest());
        EXPECT_EQ(decoder.counters().packetsDecoded, 9u);
        EXPECT_EQ(decoder.counters().totalErrors(), 0u);
    }
}

} // namespace
} // namespace sky::cigi
