// SPDX-License-Identifier: MIT
// Wireshark's CIGI dissector reads what this code writes: datagrams are wrapped in UDP (text2pcap, ports
// 8004/8005), decoded with `tshark -d udp.port==8004,cigi -T fields`, and every field is compared with the
// value encoded. IG -> host (Start of Frame, Weather Conditions and Aerosol Concentration Responses, from the
// IgEncoder) and host -> IG (every packet the IG reads), in both byte orders. The fields compared are those of
// the packets' field tables (cigi_fields.h) that the dissector names. Skipped, saying so, when tshark
// or text2pcap (Debian packages tshark, wireshark-common) are not installed.
#include "cigi_samples.h"

#include "skyservice/cigi/cigi_encoder.h"
#include "skyservice/cigi/cigi_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>

namespace sky::cigi
{
namespace
{

using namespace sky::cigi::test;
namespace fs = std::filesystem;

using FieldTable = std::vector<std::pair<std::string, double>>;  // tshark field name, expected value

bool haveTool(const char* name)
{
    return std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0;
}

std::string runCapture(const std::string& command)
{
    std::string out;
    if (FILE* pipe = popen(command.c_str(), "r"))
    {
        char buffer[4096];
        size_t n;
        while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0)
            out.append(buffer, n);
        pclose(pipe);
    }
    return out;
}

// text2pcap's input: each datagram as offset + hex bytes, 16 a line; a new offset 0 starts the next one.
void appendHexDump(std::string& text, const std::vector<uint8_t>& datagram)
{
    char cell[32];
    for (size_t i = 0; i < datagram.size(); ++i)
    {
        if (i % 16 == 0)
        {
            std::snprintf(cell, sizeof cell, "%s%06zx", i ? "\n" : "", i);
            text += cell;
        }
        std::snprintf(cell, sizeof cell, " %02x", datagram[i]);
        text += cell;
    }
    text += "\n\n";
}

// Runs text2pcap + tshark on `datagrams` sent from `srcPort` to `dstPort`; one line of fields per datagram.
std::vector<std::vector<std::string>> dissect(const std::vector<std::vector<uint8_t>>& datagrams, int srcPort,
                                              int dstPort, const FieldTable& fields, const std::string& tag)
{
    const fs::path dir = fs::temp_directory_path() / ("sky-cigi-tshark-" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::string hex;
    for (const auto& d : datagrams)
        appendHexDump(hex, d);
    const fs::path txt = dir / (tag + ".txt"), pcap = dir / (tag + ".pcap"), err = dir / (tag + ".err");
    std::ofstream(txt) << hex;
    std::string command = "text2pcap -q -u " + std::to_string(srcPort) + "," + std::to_string(dstPort) + " " +
                          txt.string() + " " + pcap.string() + " 2>" + err.string() + " && tshark -r " +
                          pcap.string() + " -d udp.port==8004,cigi -T fields -E separator=/t -E occurrence=f";
    for (const auto& f : fields)
        command += " -e " + f.first;
    command += " 2>>" + err.string();
    const std::string out = runCapture(command);
    std::vector<std::vector<std::string>> rows;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);)
    {
        std::vector<std::string> row;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, '\t');)
            row.push_back(cell);
        rows.push_back(row);
    }
    if (rows.size() != datagrams.size())
    {
        std::ifstream errFile(err);
        ADD_FAILURE() << "tshark gave " << rows.size() << " rows for " << datagrams.size()
                      << " datagrams; stderr: " << std::string(std::istreambuf_iterator<char>(errFile), {});
    }
    fs::remove_all(dir);
    return rows;
}

void expectFields(const std::vector<std::string>& row, const FieldTable& fields, const char* what)
{
    ASSERT_EQ(row.size(), fields.size()) << what;
    for (size_t i = 0; i < fields.size(); ++i)
    {
        const double expected = fields[i].second;
        char* end = nullptr;
        const double got = std::strtod(row[i].c_str(), &end);
        EXPECT_TRUE(!row[i].empty() && *end == '\0') << what << " " << fields[i].first << " = '" << row[i] << "'";
        // Floats print with about 7 significant digits.
        EXPECT_NEAR(got, expected, 1e-6 * std::max(1.0, std::abs(expected))) << what << " " << fields[i].first;
    }
}

// Each field of the packet's table (cigi_fields.h) that the dissector shows, with the value `p` holds.
template <typename Packet>
void appendFields(FieldTable& table, const Packet& p)
{
    forEachField<Packet>([&](const auto& f) {
        if (f.dissector != nullptr)
            table.emplace_back(f.dissector, static_cast<double>(p.*f.member));
    });
}

FieldTable igToHostFields(const StartOfFrame& s, const WeatherConditionsResponse& w,
                          const AerosolConcentrationResponse& a)
{
    FieldTable table;
    appendFields(table, s);
    appendFields(table, w);
    appendFields(table, a);
    return table;
}

TEST(CigiTshark, EncoderOutputReadsBackInWiresharksDissector)
{
    if (!haveTool("tshark") || !haveTool("text2pcap"))
        GTEST_SKIP() << "tshark or text2pcap is not installed (Debian packages tshark, wireshark-common): "
                        "the Wireshark cross-check of the CIGI encoder is skipped";
    // Frames 0 and 1 big-endian, frame 2 little-endian: the dissector must follow the byte-swap magic.
    std::vector<std::vector<uint8_t>> datagrams;
    std::vector<FieldTable> expected;
    IgEncoder encoder(ByteOrder::Big);
    for (int frame = 0; frame < 3; ++frame)
    {
        encoder.setByteOrder(frame < 2 ? ByteOrder::Big : ByteOrder::Little);
        StartOfFrame sof = sampleStartOfFrame();
        const uint32_t lastHostFrame = 0x55667788u + static_cast<uint32_t>(frame);
        const double timeS = 1234.5 + 0.02 * frame;
        encoder.beginFrame(lastHostFrame, timeS, sof);
        WeatherConditionsResponse w = sampleWeatherConditionsResponse();
        w.visibilityM += static_cast<float>(frame);
        AerosolConcentrationResponse a = sampleAerosolConcentrationResponse();
        a.layerId = static_cast<uint8_t>(frame);
        encoder.add(w);
        encoder.add(a);
        datagrams.push_back(encoder.datagram());
        sof.igFrameNumber = static_cast<uint32_t>(frame);
        sof.lastHostFrameNumber = lastHostFrame;
        sof.timestamp10us = timestampTicks10us(timeS);
        expected.push_back(igToHostFields(sof, w, a));
    }
    const auto rows = dissect(datagrams, 8004, 8005, expected[0], "ig");
    ASSERT_EQ(rows.size(), 3u);
    for (size_t i = 0; i < rows.size(); ++i)
        expectFields(rows[i], expected[i], i < 2 ? "big-endian frame" : "little-endian frame");
}

FieldTable hostToIgFields()
{
    FieldTable table;
    appendFields(table, sampleIgControl());
    appendFields(table, sampleEntityControl());
    appendFields(table, sampleCelestialSphereControl());
    appendFields(table, sampleAtmosphereControl());
    appendFields(table, sampleEnvironmentalRegionControl());
    appendFields(table, sampleWeatherControl());
    appendFields(table, sampleViewControl());
    appendFields(table, sampleViewDefinition());
    appendFields(table, sampleEnvironmentalConditionsRequest());
    return table;
}

TEST(CigiTshark, HostPacketLayoutsAgreeWithWiresharksDissector)
{
    if (!haveTool("tshark") || !haveTool("text2pcap"))
        GTEST_SKIP() << "tshark or text2pcap is not installed (Debian packages tshark, wireshark-common): "
                        "the Wireshark cross-check of the CIGI packet layouts is skipped";
    std::vector<std::vector<uint8_t>> datagrams;
    for (ByteOrder order : {ByteOrder::Big, ByteOrder::Little})
    {
        std::vector<uint8_t> d;
        encode(sampleIgControl(), order, d);
        encode(sampleEntityControl(), order, d);
        encode(sampleCelestialSphereControl(), order, d);
        encode(sampleAtmosphereControl(), order, d);
        encode(sampleEnvironmentalRegionControl(), order, d);
        encode(sampleWeatherControl(), order, d);
        encode(sampleViewControl(), order, d);
        encode(sampleViewDefinition(), order, d);
        encode(sampleEnvironmentalConditionsRequest(), order, d);
        datagrams.push_back(d);
    }
    const FieldTable fields = hostToIgFields();
    const auto rows = dissect(datagrams, 8005, 8004, fields, "host");
    ASSERT_EQ(rows.size(), 2u);
    expectFields(rows[0], fields, "big-endian host datagram");
    expectFields(rows[1], fields, "little-endian host datagram");
}

} // namespace
} // namespace sky::cigi
