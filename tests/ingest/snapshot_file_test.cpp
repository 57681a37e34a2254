// SPDX-License-Identifier: MIT
// The snapshot file format: round trip, and rejection of corrupted, truncated and foreign files.
#include "weather_ingest/crc32c.h"
#include "weather_ingest/snapshot_file.h"

#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace sky
{
namespace
{

TEST(Crc32c, MatchesRfc3720CheckValue)
{
    EXPECT_EQ(crc32c("123456789", 9), 0xE3069283u);
    // Chaining in pieces gives the same result as one call.
    EXPECT_EQ(crc32c("6789", 4, crc32c("12345", 5)), 0xE3069283u);
    std::vector<uint8_t> big(1000003);
    for (size_t i = 0; i < big.size(); ++i)
        big[i] = uint8_t(i * 7 + 3);
    EXPECT_EQ(crc32c(big.data(), big.size()), crc32c(big.data() + 11, big.size() - 11, crc32c(big.data(), 11)));
}

TEST(SnapshotFile, RoundTripsSeveralSnapshotsBitExactly)
{
    const std::string path = test::tempPath("roundtrip.skywx");
    std::vector<WeatherSnapshot> in = {test::makeSnapshot(1000, 0.25f), test::makeSnapshot(4600, 0.75f)};
    in[1].levelFields.push_back({"cloudMixingRatio", "kg/kg", {85000.f, 50000.f}, std::vector<float>(2 * 12, 1e-5f)});
    in[1].levelFields[0].values[3] = NAN;
    std::string error;
    ASSERT_TRUE(writeSnapshotFile(path, in, error)) << error;
    std::vector<WeatherSnapshot> out;
    ASSERT_TRUE(readSnapshotFile(path, out, error)) << error;
    ASSERT_EQ(out.size(), 2u);
    for (size_t i = 0; i < 2; ++i)
    {
        EXPECT_EQ(out[i].validTimeUnixS, in[i].validTimeUnixS);
        EXPECT_EQ(out[i].grid.nLat, in[i].grid.nLat);
        EXPECT_EQ(out[i].grid.dLatDeg, in[i].grid.dLatDeg);
        ASSERT_EQ(out[i].layers.size(), in[i].layers.size());
        EXPECT_EQ(out[i].layers[0].name, "low");
        EXPECT_EQ(out[i].layers[1].coverage, in[i].layers[1].coverage);
        EXPECT_EQ(out[i].layers[0].type, in[i].layers[0].type);
        EXPECT_TRUE(std::isnan(out[i].layers[0].baseAltitudeM[5]));  // NaN survives
        EXPECT_EQ(out[i].high.altitudeM, in[i].high.altitudeM);
        EXPECT_EQ(out[i].provenance, in[i].provenance);
        EXPECT_TRUE(out[i].tropopauseAltitudeM.empty());  // absent stays absent
    }
    ASSERT_EQ(out[1].levelFields.size(), 1u);
    EXPECT_EQ(out[1].levelFields[0].pressurePa, in[1].levelFields[0].pressurePa);
    EXPECT_TRUE(std::isnan(out[1].levelFields[0].values[3]));
    EXPECT_EQ(out[1].levelFields[0].values[4], 1e-5f);
    // No temporary file is left beside it.
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
        EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
}

class SnapshotCorruption : public ::testing::Test
{
protected:
    void SetUp() override
    {
        path = test::tempPath("good.skywx");
        std::string error;
        ASSERT_TRUE(writeSnapshotFile(path, {test::makeSnapshot(0, 0.5f)}, error)) << error;
        bytes = test::readBytes(path);
    }
    std::string parseError(const std::vector<uint8_t>& b)
    {
        std::vector<WeatherSnapshot> out;
        std::string error;
        EXPECT_FALSE(parseSnapshotBytes(b.data(), b.size(), "mem", out, error));
        EXPECT_TRUE(out.empty());
        return error;
    }
    std::string path;
    std::vector<uint8_t> bytes;
};

TEST_F(SnapshotCorruption, EveryTruncationIsRejected)
{
    for (size_t n = 0; n < bytes.size(); n += (n < 64 ? 1 : 97))
    {
        std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + long(n));
        const std::string e = parseError(cut);
        EXPECT_FALSE(e.empty()) << n;
    }
    std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 1);
    EXPECT_NE(parseError(cut).find("truncated"), std::string::npos);
    EXPECT_NE(parseError({}).find("empty file"), std::string::npos);
}

TEST_F(SnapshotCorruption, FlippedBitsAreRejected)
{
    for (size_t at : {size_t(5), size_t(9), size_t(20), size_t(40), bytes.size() / 2, bytes.size() - 1})
    {
        std::vector<uint8_t> bad = bytes;
        bad[at] ^= 0x10;
        EXPECT_FALSE(parseError(bad).empty()) << at;
    }
    std::vector<uint8_t> bad = bytes;
    bad[bytes.size() - 3] ^= 0x01;  // inside the last float array: only the checksum can tell
    EXPECT_NE(parseError(bad).find("checksum"), std::string::npos);
}

TEST_F(SnapshotCorruption, ForeignAndFutureFilesAreRejected)
{
    const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    EXPECT_NE(parseError(png).find("not a weather snapshot"), std::string::npos);
    std::vector<uint8_t> grib(bytes.size(), 0);
    std::memcpy(grib.data(), "GRIB", 4);
    EXPECT_NE(parseError(grib).find("not a weather snapshot"), std::string::npos);
    // A trailing byte is as wrong as a missing one.
    std::vector<uint8_t> longer = bytes;
    longer.push_back(0);
    EXPECT_NE(parseError(longer).find("trailing"), std::string::npos);
}

TEST(SnapshotFile, MissingFileAndDirectoryGiveErrors)
{
    std::vector<WeatherSnapshot> out;
    std::string error;
    EXPECT_FALSE(readSnapshotFile("/nonexistent/x.skywx", out, error));
    EXPECT_NE(error.find("/nonexistent/x.skywx"), std::string::npos);
    EXPECT_FALSE(readSnapshotFile(std::filesystem::temp_directory_path().string(), out, error));
}

TEST(SnapshotFile, FailedWriteLeavesExistingFileUntouched)
{
    const std::string path = test::tempPath("keep.skywx");
    std::string error;
    ASSERT_TRUE(writeSnapshotFile(path, {test::makeSnapshot(0, 0.5f)}, error)) << error;
    const std::vector<uint8_t> before = test::readBytes(path);
    WeatherSnapshot bad = test::makeSnapshot(0, 0.5f);
    bad.layers[0].coverage.pop_back();  // wrong length: refused before anything is written
    EXPECT_FALSE(writeSnapshotFile(path, {bad}, error));
    EXPECT_NE(error.find("layers/0/coverage"), std::string::npos) << error;
    EXPECT_EQ(test::readBytes(path), before);
    EXPECT_FALSE(writeSnapshotFile("/nonexistent-dir/x.skywx", {test::makeSnapshot(0, 0.5f)}, error));
}

TEST(SnapshotFile, ValidationRefusesAbsurdGridsAndTypes)
{
    std::string error;
    WeatherSnapshot s = test::makeSnapshot(0, 0.5f);
    s.grid.nLat = 100000;
    s.grid.nLon = 100000;
    EXPECT_FALSE(validateSnapshot(s, error));
    EXPECT_NE(error.find("exceeds"), std::string::npos);
    s = test::makeSnapshot(0, 0.5f);
    s.layers[0].type[0] = 11;
    EXPECT_FALSE(validateSnapshot(s, error));
    s = test::makeSnapshot(0, 0.5f);
    s.grid.dLonDeg = 0;
    EXPECT_FALSE(validateSnapshot(s, error));
    s = test::makeSnapshot(0, 0.5f);
    s.layers.resize(kMaxCloudLayers + 1);
    EXPECT_FALSE(validateSnapshot(s, error));
}

}  // namespace
}  // namespace sky

namespace sky
{
namespace
{

// Format 2 adds only the optional dataWeight array: files without it stay version 1 (readable by older
// builds), files with it are version 2 and round-trip it; a weight outside [0, 1] is refused.
TEST(SnapshotFile, DataWeightIsVersionTwoAndVersionOneStaysReadable)
{
    const WeatherSnapshot plain = test::makeSnapshot(1000, 0.5f);
    WeatherSnapshot regional = test::makeSnapshot(2000, 0.5f);
    regional.dataWeight.assign(regional.grid.cellCount(), 1.0f);
    regional.dataWeight[0] = 0.0f;
    regional.dataWeight[1] = 0.25f;
    const std::string v1 = test::tempPath("v1.skywx"), v2 = test::tempPath("v2.skywx");
    std::string error;
    ASSERT_TRUE(writeSnapshotFile(v1, {plain}, error)) << error;
    ASSERT_TRUE(writeSnapshotFile(v2, {plain, regional}, error)) << error;
    const auto version = [](const std::string& path) {
        const std::vector<uint8_t> b = test::readBytes(path);
        uint32_t v = 0;
        std::memcpy(&v, b.data() + 8, 4);
        return v;
    };
    EXPECT_EQ(version(v1), 1u);
    EXPECT_EQ(version(v2), 2u);
    std::vector<WeatherSnapshot> back;
    ASSERT_TRUE(readSnapshotFile(v1, back, error)) << error;
    EXPECT_TRUE(back.at(0).dataWeight.empty());
    ASSERT_TRUE(readSnapshotFile(v2, back, error)) << error;
    EXPECT_TRUE(back.at(0).dataWeight.empty());
    EXPECT_EQ(back.at(1).dataWeight, regional.dataWeight);

    WeatherSnapshot bad = regional;
    bad.dataWeight[2] = 1.5f;
    EXPECT_FALSE(validateSnapshot(bad, error));
    EXPECT_NE(error.find("dataWeight"), std::string::npos) << error;
}

}  // namespace
}  // namespace sky
