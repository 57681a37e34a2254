// SPDX-License-Identifier: MIT
// The EGM96 reader: a synthetic GTX grid (header, bilinear weights, longitude wrap, bad files), then the
// real Debian grid against PROJ's own answer from cs2cs at places where the undulation is large.
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/cigi/cigi_wire.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

namespace sky::cigi
{
namespace
{

// A GTX file: `rows` x `cols` values v(row, col) = 10 * row + col, from (lat0, lon0) with spacing d.
std::vector<uint8_t> syntheticGtx(double lat0, double lon0, double d, int rows, int cols)
{
    std::vector<uint8_t> bytes;
    WireWriter header(bytes, 40, ByteOrder::Big);
    header.f64(0, lat0);
    header.f64(8, lon0);
    header.f64(16, d);
    header.f64(24, d);
    header.u32(32, static_cast<uint32_t>(rows));
    header.u32(36, static_cast<uint32_t>(cols));
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
        {
            WireWriter cell(bytes, 4, ByteOrder::Big);
            cell.f32(0, static_cast<float>(10 * r + c));
        }
    return bytes;
}

TEST(Geoid, SyntheticGridIsInterpolatedBilinearly)
{
    const std::vector<uint8_t> gtx = syntheticGtx(10.0, 20.0, 0.5, 3, 4);
    GeoidGrid grid;
    std::string error;
    ASSERT_TRUE(grid.parse(gtx.data(), gtx.size(), "synthetic", error)) << error;
    EXPECT_EQ(grid.rows(), 3);
    EXPECT_EQ(grid.cols(), 4);
    EXPECT_DOUBLE_EQ(grid.undulationM(10.0, 20.0), 0.0);    // south-west node
    EXPECT_DOUBLE_EQ(grid.undulationM(11.0, 21.5), 23.0);   // north-east node
    EXPECT_DOUBLE_EQ(grid.undulationM(10.5, 20.5), 11.0);   // an inner node
    EXPECT_DOUBLE_EQ(grid.undulationM(10.25, 20.25), 5.5);  // middle of the first cell: mean of 0, 1, 10, 11
    EXPECT_DOUBLE_EQ(grid.undulationM(10.0, 20.125), 0.25); // along the south row
    EXPECT_TRUE(std::isnan(grid.undulationM(10.0, 25.0)));  // east of a grid that does not wrap
    EXPECT_DOUBLE_EQ(grid.ellipsoidHeightM(10.5, 20.5, 1000.0), 1011.0);
}

TEST(Geoid, GlobalGridWrapsLongitude)
{
    // 4 columns of 90°: -180, -90, 0, 90; east of 90 the last column blends into the first.
    const std::vector<uint8_t> gtx = syntheticGtx(-90.0, -180.0, 90.0, 3, 4);
    GeoidGrid grid;
    std::string error;
    ASSERT_TRUE(grid.parse(gtx.data(), gtx.size(), "global", error)) << error;
    EXPECT_DOUBLE_EQ(grid.undulationM(-90.0, 135.0), 1.5);   // between column 3 (value 3) and column 0 (0)
    EXPECT_DOUBLE_EQ(grid.undulationM(-90.0, 180.0), 0.0);   // 180 is -180
    EXPECT_DOUBLE_EQ(grid.undulationM(-90.0, 270.0), 1.0);   // 270 is -90
    EXPECT_DOUBLE_EQ(grid.undulationM(0.0, -540.0), 10.0);   // -540 is -180; latitude 0 is row 1
}

TEST(Geoid, BadFilesSayWhatIsWrong)
{
    GeoidGrid grid;
    std::string error;
    std::vector<uint8_t> gtx = syntheticGtx(10.0, 20.0, 0.5, 3, 4);
    EXPECT_FALSE(grid.parse(gtx.data(), 39, "short.gtx", error));
    EXPECT_NE(error.find("shorter than a GTX header"), std::string::npos) << error;
    EXPECT_FALSE(grid.parse(gtx.data(), gtx.size() - 4, "cut.gtx", error));
    EXPECT_NE(error.find("3 x 4"), std::string::npos) << error;
    gtx[16] = 0xFF;  // spacing becomes NaN
    EXPECT_FALSE(grid.parse(gtx.data(), gtx.size(), "nan.gtx", error));
    EXPECT_NE(error.find("not a grid"), std::string::npos) << error;
    EXPECT_FALSE(grid.loaded());
    EXPECT_FALSE(grid.load("/nonexistent/egm96_15.gtx", error));
    EXPECT_NE(error.find("proj-data"), std::string::npos) << error;
    EXPECT_TRUE(std::isnan(grid.undulationM(0, 0)));
}

// N from PROJ: cs2cs converts an ellipsoidal height of 0 (EPSG:4979) to an EGM96 height (EPSG:5773), which
// is -N; PROJ finds the same egm96_15.gtx from proj-data. NaN when cs2cs gives no number.
double cs2csUndulationM(double latDeg, double lonDeg)
{
    char command[256];
    std::snprintf(command, sizeof command, "echo '%.6f %.6f 0' | cs2cs -d 6 EPSG:4979 EPSG:4326+5773 2>/dev/null",
                  latDeg, lonDeg);
    std::string out;
    if (FILE* pipe = popen(command, "r"))
    {
        char buffer[256];
        while (fgets(buffer, sizeof buffer, pipe))
            out += buffer;
        pclose(pipe);
    }
    std::istringstream fields(out);
    std::string lat, lon, height;
    fields >> lat >> lon >> height;
    char* end = nullptr;
    const double h = std::strtod(height.c_str(), &end);
    return height.empty() || *end != '\0' ? std::nan("") : -h;
}

TEST(Geoid, Egm96MatchesProjWhereTheUndulationIsLarge)
{
    if (!std::filesystem::exists(defaultEgm96GridPath()))
        GTEST_SKIP() << defaultEgm96GridPath() << " is missing (Debian package proj-data): EGM96 check skipped";
    if (std::system("command -v cs2cs >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "cs2cs is not installed (Debian package proj-bin): EGM96 check against PROJ skipped";
    GeoidGrid grid;
    std::string error;
    ASSERT_TRUE(grid.load(defaultEgm96GridPath(), error)) << error;
    EXPECT_EQ(grid.rows(), 721);
    EXPECT_EQ(grid.cols(), 1440);
    struct Place
    {
        const char* name;
        double latDeg, lonDeg;
        double roughN;  ///< what published EGM96 maps show, to catch a PROJ that fell back to no grid
    };
    const Place places[] = {
        {"south of India (the geoid low)", 4.7, 78.8, -107},
        {"Sri Lanka", 7.0, 80.0, -100},
        {"Iceland", 64.5, -19.0, 67},
        {"New Guinea", -5.0, 145.0, 70},
        {"New Guinea highlands, between grid nodes", -5.37, 143.61, 80},
        {"across the antimeridian (Fiji)", -17.8, 179.93, 50},
    };
    for (const Place& p : places)
    {
        SCOPED_TRACE(p.name);
        const double proj = cs2csUndulationM(p.latDeg, p.lonDeg);
        ASSERT_FALSE(std::isnan(proj)) << "cs2cs gave no height";
        EXPECT_NEAR(proj, p.roughN, 12.0) << "PROJ did not use the EGM96 grid?";
        EXPECT_NEAR(grid.undulationM(p.latDeg, p.lonDeg), proj, 0.01);
    }
}

} // namespace
} // namespace sky::cigi
