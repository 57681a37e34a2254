// SPDX-License-Identifier: MIT
// Malformed datagrams: each is counted under the right kind, named in a message, and never crashes; the
// good packets around a bad one still come through.
#include "cigi_samples.h"

#include "skyservice/cigi/cigi_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

namespace sky::cigi
{
namespace
{

using namespace sky::cigi::test;

std::vector<uint8_t> header(ByteOrder order = ByteOrder::Big)
{
    std::vector<uint8_t> d;
    encode(sampleIgControl(), order, d);
    return d;
}

struct BadCase
{
    const char* name;
    std::function<std::vector<uint8_t>()> make;
    DecodeErrorKind kind;
    bool accepted;          ///< the header was good
    size_t goodPackets;     ///< packets that still come through
    const char* mentions;   ///< a word the message must contain
};

std::vector<BadCase> badCases()
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {
        {"empty", [] { return std::vector<uint8_t>{}; }, DecodeErrorKind::ShortDatagram, false, 0, "0 bytes"},
        {"short", [] { auto d = header(); d.resize(23); return d; }, DecodeErrorKind::ShortDatagram, false, 0,
         "23 bytes"},
        {"no IG Control first",
         [] {
             std::vector<uint8_t> d;
             encode(sampleEntityControl(), ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::MissingIgControl, false, 0, "Entity Control"},
        {"wrong magic", [] { auto d = header(); d[6] = 0x12; d[7] = 0x34; return d; }, DecodeErrorKind::BadMagic,
         false, 0, "0x1234"},
        {"CIGI 2 version", [] { auto d = header(); d[2] = 2; return d; }, DecodeErrorKind::BadVersion, false, 0,
         "CIGI Version"},
        {"unknown opcode then a good packet",
         [] {
             auto d = header();
             const size_t at = d.size();
             d.resize(at + 16, 0);
             d[at] = 77;  // not defined by CIGI 3.3
             d[at + 1] = 16;
             encode(sampleAtmosphereControl(), ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::UnknownOpcode, true, 1, "opcode 77"},
        {"size field smaller than the packet",
         [] {
             auto d = header();
             const size_t at = d.size();
             encode(sampleWeatherControl(), ByteOrder::Big, d);
             d[at + 1] = 48;  // 56 in truth: skipped by its (lying) size; the next bytes then look like junk
             return d;
         },
         DecodeErrorKind::SizeMismatch, true, 0, "is not 56"},
        {"size field past the end",
         [] {
             auto d = header();
             const size_t at = d.size();
             encode(sampleAtmosphereControl(), ByteOrder::Big, d);
             d[at + 1] = 200;
             return d;
         },
         DecodeErrorKind::Truncated, true, 0, "past the datagram's end"},
        {"cut-off packet",
         [] {
             auto d = header();
             encode(sampleEntityControl(), ByteOrder::Big, d);
             d.resize(d.size() - 10);
             return d;
         },
         DecodeErrorKind::Truncated, true, 0, "Entity Control"},
        {"size zero",
         [] {
             auto d = header();
             d.push_back(kOpViewControl);
             d.push_back(0);
             d.resize(d.size() + 30, 0);
             return d;
         },
         DecodeErrorKind::BadSize, true, 0, "less than 2"},
        {"NaN latitude",
         [nan] {
             auto d = header();
             EntityControl e = sampleEntityControl();
             e.latDegOrXM = nan;
             encode(e, ByteOrder::Big, d);
             encode(sampleViewControl(), ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 1, "Latitude"},
        {"latitude 91",
         [] {
             auto d = header(ByteOrder::Little);
             EntityControl e = sampleEntityControl();
             e.latDegOrXM = 91;
             encode(e, ByteOrder::Little, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 0, "Latitude 91"},
        {"coverage 140",
         [] {
             auto d = header();
             WeatherControl w = sampleWeatherControl();
             w.coveragePct = 140;
             encode(w, ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 0, "Coverage 140"},
        {"negative thickness",
         [] {
             auto d = header();
             WeatherControl w = sampleWeatherControl();
             w.thicknessM = -5;
             encode(w, ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 0, "Thickness -5"},
        {"infinite view angle",
         [] {
             auto d = header();
             ViewDefinition v = sampleViewDefinition();
             v.rightDeg = std::numeric_limits<float>::infinity();
             encode(v, ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 0, "Right"},
        {"30 February",
         [] {
             auto d = header();
             CelestialSphereControl c = sampleCelestialSphereControl();
             c.dateMMDDYYYY = 2302026;
             encode(c, ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::BadValue, true, 0, "day"},
        {"Start of Frame from the host",
         [] {
             auto d = header();
             encode(sampleStartOfFrame(), ByteOrder::Big, d);
             return d;
         },
         DecodeErrorKind::UnexpectedPacket, true, 0, "Start of Frame"},
    };
}

TEST(CigiDecoder, MalformedDatagramsAreCountedByKindAndSurvived)
{
    for (const BadCase& c : badCases())
    {
        SCOPED_TRACE(c.name);
        Decoder decoder;
        const std::vector<uint8_t> bytes = c.make();
        const DecodeResult r = decoder.decode(bytes.data(), bytes.size());
        EXPECT_EQ(r.accepted, c.accepted);
        EXPECT_EQ(r.packets.size(), c.goodPackets);
        ASSERT_FALSE(r.errors.empty());
        EXPECT_EQ(r.errors.front().kind, c.kind) << r.errors.front().message;
        EXPECT_NE(r.errors.front().message.find(c.mentions), std::string::npos) << r.errors.front().message;
        EXPECT_TRUE(r.errors.front().firstOfKind);
        EXPECT_EQ(decoder.counters().error(c.kind), 1u) << decodeErrorName(c.kind);
        EXPECT_EQ(decoder.counters().datagramsDropped, c.accepted ? 0u : 1u);
    }
}

TEST(CigiDecoder, RepeatedErrorsCountButOnlyTheFirstAsksToBeLogged)
{
    Decoder decoder;
    auto d = header();
    d[6] = 0;
    d[7] = 0;
    for (int i = 0; i < 3; ++i)
    {
        const DecodeResult r = decoder.decode(d.data(), d.size());
        ASSERT_EQ(r.errors.size(), 1u);
        EXPECT_EQ(r.errors[0].firstOfKind, i == 0);
    }
    EXPECT_EQ(decoder.counters().error(DecodeErrorKind::BadMagic), 3u);
    EXPECT_EQ(decoder.counters().datagrams, 3u);
}

TEST(CigiDecoder, PacketsThisIgDoesNotUseAreSkippedWithoutError)
{
    auto d = header();
    const size_t at = d.size();
    d.resize(at + 32, 0);
    d[at] = 4;  // Component Control, 32 bytes
    d[at + 1] = 32;
    d.resize(d.size() + 8, 0);
    d[at + 32] = 230;  // user-defined
    d[at + 33] = 8;
    encode(sampleCelestialSphereControl(), ByteOrder::Big, d);
    Decoder decoder;
    const DecodeResult r = decoder.decode(d.data(), d.size());
    EXPECT_TRUE(r.errors.empty());
    EXPECT_EQ(r.packets.size(), 1u);
    EXPECT_EQ(decoder.counters().packetsIgnored, 2u);
}

TEST(CigiDecoder, MinorVersionIsNotCheckedButTheIgControlSizeIs)
{
    IgControl ig = sampleIgControl();
    ig.minorVersion = 0;  // a host that leaves the nibble unset still sends the 24-byte 3.2+ layout
    std::vector<uint8_t> d;
    encode(ig, ByteOrder::Big, d);
    Decoder decoder;
    EXPECT_TRUE(decoder.decode(d.data(), d.size()).accepted);
    d[1] = 16;  // a CIGI 3.0/3.1 IG Control is 16 bytes: another layout, refused
    const DecodeResult old = decoder.decode(d.data(), d.size());
    EXPECT_FALSE(old.accepted);
    ASSERT_EQ(old.errors.size(), 1u);
    EXPECT_EQ(old.errors[0].kind, DecodeErrorKind::MissingIgControl);
}

TEST(CigiDecoder, EveryTruncationOfAGoodDatagramIsSurvived)
{
    // Each prefix of a full datagram: no crash (run under the sanitizers), and whole packets before the cut
    // are still delivered.
    std::vector<uint8_t> full = header();
    encode(sampleWeatherControl(), ByteOrder::Big, full);
    encode(sampleEntityControl(), ByteOrder::Big, full);
    Decoder decoder;
    for (size_t n = 0; n <= full.size(); ++n)
    {
        const DecodeResult r = decoder.decode(full.data(), n);
        const size_t expected = n >= 24 + 56 + 48 ? 2 : n >= 24 + 56 ? 1 : 0;
        EXPECT_EQ(r.packets.size(), expected) << n;
        EXPECT_EQ(r.accepted, n >= 24) << n;
    }
}

} // namespace
} // namespace sky::cigi
