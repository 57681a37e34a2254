// SPDX-License-Identifier: MIT
// Every bad input (weather_ingest/README.md) gets a typed error with a clear message (and, through the CLI, a non-zero
// exit and no output file: tests/ingest/cli_test.sh).
#include "weather_ingest/grib_fields.h"
#include "weather_ingest/ingest.h"
#include "weather_ingest/ingest_error.h"

#include "grib_fixtures.h"
#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <netcdf.h>

#include <cmath>

namespace sky
{
namespace
{

struct Outcome
{
    bool failed = false;
    IngestErrorKind kind = IngestErrorKind::Io;
    std::string message;
    std::vector<std::string> warnings;
};

Outcome convert(const std::string& path, bool lenient = false)
{
    Outcome o;
    try
    {
        MappingOptions options;
        options.lenient = lenient;
        o.warnings = convertFiles({path}, options, {}).warnings;
    }
    catch (const IngestError& e)
    {
        o.failed = true;
        o.kind = e.kind();
        o.message = e.what();
    }
    return o;
}

std::string writeFixture(const std::string& name, const std::vector<GribOutField>& fields)
{
    const std::string path = test::tempPath(name);
    writeGribFile(path, fields);
    return path;
}

TEST(BadInput, ZeroLengthFile)
{
    const std::string path = test::tempPath("empty.grib2");
    test::writeBytes(path, {});
    const Outcome o = convert(path);
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::NotRecognized);
    EXPECT_NE(o.message.find("empty file"), std::string::npos) << o.message;
}

TEST(BadInput, PngRenamedGrib2)
{
    const std::string path = test::tempPath("image.grib2");
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    png.resize(300, 0x42);
    test::writeBytes(path, png);
    const Outcome o = convert(path);
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::NotRecognized);
    EXPECT_NE(o.message.find("PNG"), std::string::npos) << o.message;
    EXPECT_NE(o.message.find(path), std::string::npos);
}

TEST(BadInput, TruncatedGribNamesTheMessage)
{
    const std::string full = writeFixture("full.grib2", test::gfsLikeFields(test::smallGlobalGrid()));
    std::vector<uint8_t> bytes = test::readBytes(full);
    for (const double keep : {0.55, 0.97})  // not on a message boundary
    {
        const std::string path = test::tempPath("cut.grib2");
        test::writeBytes(path, {bytes.begin(), bytes.begin() + long(double(bytes.size()) * keep)});
        const Outcome o = convert(path);
        ASSERT_TRUE(o.failed) << keep;
        EXPECT_EQ(o.kind, IngestErrorKind::Corrupt) << o.message;
        EXPECT_NE(o.message.find("message "), std::string::npos) << o.message;
    }
}

TEST(BadInput, CoverageOutside0To100Percent)
{
    const LatLonGrid g = test::smallGlobalGrid();
    std::vector<GribOutField> f = test::gfsLikeFields(g);
    f[1].values[7] = 130;  // middle cloud cover 130 %
    const std::string path = writeFixture("cover.grib2", f);
    const Outcome o = convert(path);
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::BadValues);
    EXPECT_NE(o.message.find("outside [0, 100] %"), std::string::npos) << o.message;
    EXPECT_NE(o.message.find("tcc/middleCloudLayer"), std::string::npos) << o.message;
    const Outcome lenient = convert(path, true);
    EXPECT_FALSE(lenient.failed) << lenient.message;
    ASSERT_EQ(lenient.warnings.size(), 1u);
    EXPECT_NE(lenient.warnings[0].find("clamped"), std::string::npos);
}

TEST(BadInput, CloudBaseAboveTop)
{
    std::vector<GribOutField> f = test::gfsLikeFields(test::smallGlobalGrid());
    f[4].values[3] = 50000;  // low cloud bottom at 500 hPa, top at 800 hPa
    const Outcome o = convert(writeFixture("basetop.grib2", f));
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::BadValues);
    EXPECT_NE(o.message.find("base above cloud top"), std::string::npos) << o.message;
}

TEST(BadInput, NanThatIsNotAMissingValue)
{
    std::vector<GribOutField> f = test::gfsLikeFields(test::smallGlobalGrid());
    f[0].packingType = "grid_ieee";
    f[0].bitsPerValue = 32;
    f[0].nanAsValue = true;
    f[0].values[5] = NAN;
    std::string path;
    try
    {
        path = writeFixture("nan.grib2", f);
    }
    catch (const IngestError& e)
    {
        GTEST_SKIP() << "this ecCodes refuses to encode NaN: " << e.what();
    }
    const Outcome o = convert(path);
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::BadValues);
    EXPECT_NE(o.message.find("NaN"), std::string::npos) << o.message;
}

TEST(BadInput, AbsurdGridSizeIsRefusedBeforeDecoding)
{
    const std::string path = writeFixture("big.grib2", test::gfsLikeFields(test::smallGlobalGrid()));
    GribFile file(path);
    try
    {
        readGribRecords(file, 100, {});  // a limit below the grid's 342 points
        FAIL() << "no error";
    }
    catch (const IngestError& e)
    {
        EXPECT_EQ(e.kind(), IngestErrorKind::TooLarge);
        EXPECT_NE(std::string(e.what()).find("exceeds"), std::string::npos) << e.what();
    }
}

// ecCodes loops forever deriving the validity date from a time unit outside its code table; the reader must
// refuse the message first (a fuzzer found it: without the check this test never ends).
TEST(BadInput, UnknownTimeUnitIsRefusedNamingTheKey)
{
    std::vector<GribOutField> f = test::gfsLikeFields(test::smallGlobalGrid());
    f[0].keys.emplace_back("forecastTime", "5");
    f[0].keys.emplace_back("indicatorOfUnitOfTimeRange", "255");
    const Outcome o = convert(writeFixture("time_unit_255.grib2", f));
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::Corrupt);
    EXPECT_NE(o.message.find("indicatorOfUnitOfTimeRange"), std::string::npos) << o.message;
    EXPECT_NE(o.message.find("255"), std::string::npos) << o.message;
}

TEST(BadInput, FieldsOnDifferentGridsCombineAndTheFinerWins)
{
    std::vector<GribOutField> f = test::gfsLikeFields(test::smallGlobalGrid());
    LatLonGrid other = test::smallGlobalGrid();
    other.nLon = 9;
    other.dLonDeg = 40;
    f[2].grid = other;
    f[2].values.assign(other.cellCount(), 10);
    const ConvertResult r = convertFiles({writeFixture("mixed.grib2", f)}, MappingOptions{}, {});
    ASSERT_EQ(r.snapshots.size(), 1u);
    const WeatherSnapshot& s = r.snapshots[0];
    EXPECT_EQ(s.grid.nLon, 18u); // the finer of the two global grids
    EXPECT_TRUE(s.dataWeight.empty());
    // Convective cover exists only on the coarser grid (10 %); the finer one has none there: 0 wins.
    EXPECT_NEAR(s.layers[2].coverage[40], 0.0f, 1e-6f);
    EXPECT_NEAR(s.layers[0].coverage[40], 0.6f, 1e-3f);
}

TEST(BadInput, GribWithoutCloudFields)
{
    const LatLonGrid g = test::smallGlobalGrid();
    const Outcome o = convert(writeFixture("nocloud.grib2", {test::levelField(g, "gh", 500, 5500)}));
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::MissingFields);
    EXPECT_NE(o.message.find("no cloud cover"), std::string::npos);
}

TEST(BadInput, NetCdfWithNoneOfTheNeededVariables)
{
    const std::string path = test::tempPath("other.nc");
    int id = 0, dim = 0, var = 0;
    ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER, &id), NC_NOERR);
    ASSERT_EQ(nc_def_dim(id, "x", 4, &dim), NC_NOERR);
    ASSERT_EQ(nc_def_var(id, "temperature", NC_FLOAT, 1, &dim, &var), NC_NOERR);
    ASSERT_EQ(nc_enddef(id), NC_NOERR);
    const float t[4] = {1, 2, 3, 4};
    ASSERT_EQ(nc_put_var_float(id, var, t), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
    const Outcome o = convert(path);
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::MissingFields);
    EXPECT_NE(o.message.find("none of the variables"), std::string::npos) << o.message;
    // A truncated NetCDF is corrupt, not a crash.
    const std::vector<uint8_t> bytes = test::readBytes(path);
    const std::string cut = test::tempPath("cut.nc");
    test::writeBytes(cut, {bytes.begin(), bytes.begin() + 20});
    const Outcome c = convert(cut);
    ASSERT_TRUE(c.failed);
    EXPECT_NE(c.message.find(cut), std::string::npos);
}

TEST(BadInput, MissingFileIsAnIoError)
{
    const Outcome o = convert("/nonexistent/file.grib2");
    ASSERT_TRUE(o.failed);
    EXPECT_EQ(o.kind, IngestErrorKind::Io);
    EXPECT_EQ(exitCodeFor(o.kind), 3);
}

}  // namespace
}  // namespace sky

namespace sky
{
namespace
{

// Regression: a few kB of GRIB2 holding constant fields on a large grid converted into a snapshot
// hundreds of times its size (a 179-byte file: 300 MB). Decoded fields and output are now each held to
// max(floor, ratio x input bytes), with --allow-large-output (MappingOptions::allowLargeOutput) to pass.
TEST(BadInput, AmplifyingInputIsRefusedUnlessAllowed)
{
    const LatLonGrid g = {.lat0Deg = 89.5, .lon0Deg = 0, .dLatDeg = -0.5, .dLonDeg = 0.5, .nLat = 200, .nLon = 200};
    const std::string path = test::tempPath("amplifying.grib2");
    writeGribFile(path, test::gfsLikeFields(g));
    const uint64_t inputBytes = std::filesystem::file_size(path);
    MappingOptions o;
    o.maxAmplification = 2;
    auto refusal = [&](const MappingOptions& options) -> std::string {
        try
        {
            convertFiles({path}, options, {});
        }
        catch (const IngestError& e)
        {
            EXPECT_EQ(e.kind(), IngestErrorKind::TooLarge) << e.what();
            return e.what();
        }
        return "";
    };
    o.amplificationFloorBytes = 64 * 1024;  // below one decoded field (160 kB): refused before decoding it
    std::string why = refusal(o);
    EXPECT_NE(why.find("--allow-large-output"), std::string::npos) << why;
    o.amplificationFloorBytes = 2500 * 1024;  // below all decoded fields (3.8 MB) and the snapshot (4 MB)
    why = refusal(o);
    EXPECT_NE(why.find("decoding"), std::string::npos) << why << " (input " << inputBytes << " bytes)";
    EXPECT_NE(why.find("--allow-large-output"), std::string::npos) << why;
    o.allowLargeOutput = true;
    EXPECT_EQ(refusal(o), "");
    // The defaults let ordinary inputs through.
    EXPECT_EQ(refusal(MappingOptions{}), "");
}

}  // namespace
}  // namespace sky
