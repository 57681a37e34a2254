// SPDX-License-Identifier: MIT
// File outputs (skyservice/output/): atomic writes, PNG, EXR and JSON round trips, contact sheets, cloud luminance.
#include "skyservice/output/atomic_file.h"
#include "skyservice/output/bitmap_font.h"
#include "skyservice/output/cloud_luminance.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/output/image_files.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <unistd.h>

namespace
{

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class Outputs : public ::testing::Test
{
protected:
    void SetUp() override
    {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        folder = fs::temp_directory_path() /
                 ("sky_out_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(folder);
        fs::create_directories(folder);
    }
    void TearDown() override { fs::remove_all(folder); }

    std::string path(const std::string& name) const { return (folder / name).string(); }
    std::set<std::string> entries() const
    {
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(folder))
            names.insert(e.path().filename().string());
        return names;
    }
    static std::string slurp(const std::string& p)
    {
        std::ifstream in(p, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    fs::path folder;
};

TEST_F(Outputs, AtomicWriteCreatesAndReplaces)
{
    std::string error;
    const std::string target = path("a.bin");
    ASSERT_TRUE(sky::writeFileAtomic(target, "first", 5, error)) << error;
    EXPECT_EQ(slurp(target), "first");
    ASSERT_TRUE(sky::writeFileAtomic(target, "second!", 7, error)) << error;
    EXPECT_EQ(slurp(target), "second!");
    ASSERT_TRUE(sky::writeFileAtomic(path("empty"), nullptr, 0, error)) << error;
    EXPECT_EQ(fs::file_size(path("empty")), 0u);
    EXPECT_EQ(entries(), (std::set<std::string>{"a.bin", "empty"}));  // no temporary file left
    // Readable by others (an IG runs as another user), not mkstemp's 0600.
    EXPECT_NE(fs::status(target).permissions() & fs::perms::others_read, fs::perms::none);
}

TEST_F(Outputs, AtomicWriteErrorsNameThePath)
{
    std::string error;
    const std::string missing = path("no/such/folder/x.png");
    EXPECT_FALSE(sky::writeFileAtomic(missing, "x", 1, error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    error.clear();
    EXPECT_FALSE(sky::writeFileAtomic(path("") + "/", "x", 1, error));
    EXPECT_FALSE(error.empty());
    EXPECT_TRUE(entries().empty());
    // Rename onto an existing folder fails after the temporary file was written: it must be removed.
    fs::create_directories(folder / "occupied" / "child");
    error.clear();
    EXPECT_FALSE(sky::writeFileAtomic(path("occupied"), "x", 1, error));
    EXPECT_NE(error.find(path("occupied")), std::string::npos) << error;
    EXPECT_EQ(entries(), (std::set<std::string>{"occupied"}));
}

TEST_F(Outputs, FailedWriterLeavesOldFileAndNoTemporary)
{
    std::string error;
    const std::string target = path("frame.exr");
    ASSERT_TRUE(sky::writeFileAtomic(target, "old", 3, error));
    std::string seenTemp;
    const bool ok = sky::writeFileAtomicWith(
        target,
        [&](const std::string& tempPath, std::string& writerError) {
            seenTemp = tempPath;
            std::ofstream(tempPath) << "partial";  // half-written, then the writer fails
            writerError = "disk on fire";
            return false;
        },
        error);
    EXPECT_FALSE(ok);
    EXPECT_NE(error.find(target), std::string::npos) << error;
    EXPECT_NE(error.find("disk on fire"), std::string::npos) << error;
    EXPECT_EQ(fs::path(seenTemp).parent_path(), folder);  // same folder: rename cannot cross devices
    EXPECT_EQ(slurp(target), "old");
    EXPECT_EQ(entries(), (std::set<std::string>{"frame.exr"}));

    EXPECT_FALSE(sky::writeFileAtomicWith(
        target, [](const std::string&, std::string&) -> bool { throw std::runtime_error("thrown"); }, error));
    EXPECT_NE(error.find("thrown"), std::string::npos) << error;
    EXPECT_EQ(slurp(target), "old");
    EXPECT_EQ(entries(), (std::set<std::string>{"frame.exr"}));

    ASSERT_TRUE(sky::writeFileAtomicWith(
        target, [](const std::string& tempPath, std::string&) { return bool(std::ofstream(tempPath) << "new"); },
        error))
        << error;
    EXPECT_EQ(slurp(target), "new");
    EXPECT_EQ(entries(), (std::set<std::string>{"frame.exr"}));
}

sky::ImageRgba8 pattern(uint32_t width, uint32_t height)
{
    sky::ImageRgba8 image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
        {
            uint8_t* p = image.pixel(x, y);
            p[0] = uint8_t(x * 7 + y);
            p[1] = uint8_t(y * 13);
            p[2] = uint8_t((x ^ y) * 3);
            p[3] = uint8_t(255 - x);
        }
    return image;
}

TEST_F(Outputs, PngRoundTrip)
{
    const sky::ImageRgba8 image = pattern(37, 21);
    std::string error;
    ASSERT_TRUE(sky::writePng(path("p.png"), image, error)) << error;
    EXPECT_EQ(slurp(path("p.png")).substr(1, 3), "PNG");
    sky::ImageRgba8 back;
    ASSERT_TRUE(sky::readPng(path("p.png"), back, error)) << error;
    EXPECT_EQ(back.width, 37u);
    EXPECT_EQ(back.height, 21u);
    EXPECT_EQ(back.pixels, image.pixels);
    EXPECT_EQ(entries(), (std::set<std::string>{"p.png"}));
}

TEST_F(Outputs, PngErrors)
{
    std::string error;
    sky::ImageRgba8 bad{4, 4, std::vector<uint8_t>(10)};
    EXPECT_FALSE(sky::writePng(path("bad.png"), bad, error));
    EXPECT_NE(error.find(path("bad.png")), std::string::npos) << error;
    const std::string missing = path("nowhere/x.png");
    EXPECT_FALSE(sky::writePng(missing, pattern(2, 2), error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    sky::ImageRgba8 back;
    EXPECT_FALSE(sky::readPng(missing, back, error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    ASSERT_TRUE(sky::writeFileAtomic(path("text.png"), "not a png", 9, error));
    EXPECT_FALSE(sky::readPng(path("text.png"), back, error));
    EXPECT_NE(error.find(path("text.png")), std::string::npos) << error;
    EXPECT_EQ(entries(), (std::set<std::string>{"text.png"}));
}

TEST_F(Outputs, ExrRoundTripHalfAndFloat)
{
    const uint32_t w = 19;
    const uint32_t h = 11;
    std::vector<float> rgba(size_t(w) * h * 4);
    std::vector<float> depth(size_t(w) * h);
    for (size_t p = 0; p < depth.size(); ++p)
    {
        for (size_t k = 0; k < 4; ++k)
            rgba[p * 4 + k] = float(p) * 0.01f + float(k) * 0.25f;
        depth[p] = 700000.5f - float(p) * 1234.25f;  // beyond half's 65504
    }
    const std::vector<sky::ExrChannel> channels = {
        {"R", sky::ExrPixelType::Half, rgba.data() + 0, 4}, {"G", sky::ExrPixelType::Half, rgba.data() + 1, 4},
        {"B", sky::ExrPixelType::Half, rgba.data() + 2, 4}, {"A", sky::ExrPixelType::Half, rgba.data() + 3, 4},
        {"Z", sky::ExrPixelType::Float, depth.data(), 1},   {"sky.R", sky::ExrPixelType::Half, rgba.data() + 2, 4},
    };
    std::string error;
    ASSERT_TRUE(sky::writeExr(path("f.exr"), w, h, channels, error, {{"skyView", "{\"lat\":45}"}})) << error;
    EXPECT_EQ(entries(), (std::set<std::string>{"f.exr"}));
    sky::ExrImage back;
    ASSERT_TRUE(sky::readExr(path("f.exr"), back, error)) << error;
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    ASSERT_EQ(back.channels.size(), 6u);
    EXPECT_EQ(back.channels.at("R").type, sky::ExrPixelType::Half);
    EXPECT_EQ(back.channels.at("Z").type, sky::ExrPixelType::Float);
    EXPECT_EQ(back.stringAttributes.at("skyView"), "{\"lat\":45}");
    const char* names[] = {"R", "G", "B", "A"};
    for (size_t p = 0; p < depth.size(); ++p)
    {
        for (size_t k = 0; k < 4; ++k)
        {
            const float expected = rgba[p * 4 + k];
            ASSERT_NEAR(back.channels.at(names[k]).values[p], expected, expected * 1e-3f + 1e-4f);  // half: 11 bits
        }
        ASSERT_NEAR(back.channels.at("sky.R").values[p], rgba[p * 4 + 2], rgba[p * 4 + 2] * 1e-3f + 1e-4f);
        ASSERT_EQ(back.channels.at("Z").values[p], depth[p]);  // float is exact
    }
}

TEST_F(Outputs, ExrErrors)
{
    std::vector<float> data(16, 1.0f);
    std::string error;
    const std::string missing = path("nowhere/f.exr");
    EXPECT_FALSE(sky::writeExr(missing, 4, 4, {{"R", sky::ExrPixelType::Half, data.data(), 1}}, error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    EXPECT_FALSE(sky::writeExr(path("dup.exr"), 4, 4,
                               {{"R", sky::ExrPixelType::Half, data.data(), 1},
                                {"R", sky::ExrPixelType::Float, data.data(), 1}},
                               error));
    EXPECT_NE(error.find("'R'"), std::string::npos) << error;
    EXPECT_FALSE(sky::writeExr(path("zero.exr"), 0, 4, {{"R", sky::ExrPixelType::Half, data.data(), 1}}, error));
    EXPECT_TRUE(entries().empty());
    sky::ExrImage back;
    EXPECT_FALSE(sky::readExr(missing, back, error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    ASSERT_TRUE(sky::writeFileAtomic(path("junk.exr"), "v/1\x01junk", 9, error));
    EXPECT_FALSE(sky::readExr(path("junk.exr"), back, error));
    EXPECT_NE(error.find(path("junk.exr")), std::string::npos) << error;
}

TEST_F(Outputs, JsonRoundTrip)
{
    nlohmann::json document = {{"view", {{"lat", 45.3}, {"lon", 8.5}}},
                               {"nan", std::numeric_limits<double>::quiet_NaN()},
                               {"name", "sky"}};
    std::string error;
    ASSERT_TRUE(sky::writeJsonAtomic(path("s.json"), document, error)) << error;
    const std::string text = slurp(path("s.json"));
    EXPECT_EQ(text.back(), '\n');
    const nlohmann::json back = nlohmann::json::parse(text);
    EXPECT_EQ(back["view"]["lon"], 8.5);
    EXPECT_EQ(back["name"], "sky");
    EXPECT_TRUE(back["nan"].is_null());
    EXPECT_FALSE(sky::writeJsonAtomic(path("nowhere/s.json"), document, error));
    EXPECT_NE(error.find(path("nowhere/s.json")), std::string::npos) << error;
}

TEST(BitmapFont, GlyphsAreDistinctAndDrawn)
{
    std::set<std::array<uint8_t, sky::kGlyphHeight>> seen;
    for (char c = ' '; c <= '~'; ++c)
    {
        const auto& rows = sky::glyphRows(c);
        bool any = false;
        for (uint8_t row : rows)
        {
            EXPECT_EQ(row & ~0x1Fu, 0u) << c;  // 5 columns
            any = any || row != 0;
        }
        EXPECT_EQ(any, c != ' ') << c;
        EXPECT_TRUE(seen.insert(rows).second) << "glyph of '" << c << "' duplicates another";
    }
    EXPECT_EQ(sky::glyphRows('\n'), sky::glyphRows('?'));
    EXPECT_EQ(sky::textWidthPixels("", 1), 0u);
    EXPECT_EQ(sky::textWidthPixels("AB", 2), 22u);

    // 'T' at scale 2: the top bar is 10 pixels wide, the stem 2 pixels wide.
    sky::ImageRgba8 image{12, 16, std::vector<uint8_t>(12 * 16 * 4, 0)};
    sky::drawText(image, 1, 1, "T", 2, {255, 0, 0, 255});
    size_t lit = 0;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 12; ++x)
            lit += image.pixel(x, y)[0] == 255 ? 1 : 0;
    EXPECT_EQ(lit, size_t(4 * (5 + 6)));
    EXPECT_EQ(image.pixel(1, 1)[0], 255);
    EXPECT_EQ(image.pixel(10, 2)[0], 255);
    EXPECT_EQ(image.pixel(5, 14)[0], 255);
    EXPECT_EQ(image.pixel(1, 14)[0], 0);
    sky::drawText(image, -100, -100, "clipped", 3, {255, 255, 255, 255});  // must not crash
}

sky::ImageRgba8 solid(uint32_t w, uint32_t h, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255)
{
    sky::ImageRgba8 image{w, h, std::vector<uint8_t>(size_t(w) * h * 4)};
    for (size_t p = 0; p < image.pixels.size(); p += 4)
    {
        image.pixels[p] = r;
        image.pixels[p + 1] = g;
        image.pixels[p + 2] = b;
        image.pixels[p + 3] = a;
    }
    return image;
}

TEST(ContactSheet, TilesAndCaptions)
{
    const std::vector<sky::ImageRgba8> images = {solid(40, 20, 255, 0, 0), solid(40, 20, 0, 255, 0),
                                                 solid(20, 10, 0, 0, 255), solid(40, 20, 255, 255, 255, 0)};
    const sky::ImageRgba8 sheet = sky::makeContactSheet(images, {"RED", "", "BLUE 3"}, 2);
    const uint32_t m = sky::kContactSheetMarginPx;
    ASSERT_EQ(sheet.width, 2 * 40 + 3 * m);
    const uint32_t cellHeight = (sheet.height - 3 * m) / 2;
    ASSERT_EQ(sheet.height, 2 * cellHeight + 3 * m);
    ASSERT_GT(cellHeight, 20u + sky::kGlyphHeight);
    auto rgb = [&](uint32_t x, uint32_t y) {
        const uint8_t* p = sheet.pixel(x, y);
        EXPECT_EQ(p[3], 255);
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(rgb(m + 20, m + 10), (std::array<int, 3>{255, 0, 0}));
    EXPECT_EQ(rgb(2 * m + 40 + 20, m + 10), (std::array<int, 3>{0, 255, 0}));
    EXPECT_EQ(rgb(m + 20, 2 * m + cellHeight + 10), (std::array<int, 3>{0, 0, 255}));  // centred small tile
    EXPECT_EQ(rgb(m + 2, 2 * m + cellHeight + 2)[2], sky::kContactSheetBackground);      // around it
    EXPECT_EQ(rgb(2 * m + 60, 2 * m + cellHeight + 10)[0], sky::kContactSheetBackground);  // transparent tile

    auto captionPixels = [&](uint32_t column, uint32_t row) {
        size_t n = 0;
        const uint32_t left = m + column * (40 + m);
        const uint32_t top = m + row * (cellHeight + m) + 20;
        for (uint32_t y = top; y < top + cellHeight - 20; ++y)
            for (uint32_t x = left; x < left + 40; ++x)
                n += sheet.pixel(x, y)[0] > 200 ? 1 : 0;
        return n;
    };
    EXPECT_GT(captionPixels(0, 0), 20u);   // "RED"
    EXPECT_EQ(captionPixels(1, 0), 0u);    // empty caption
    EXPECT_GT(captionPixels(0, 1), 20u);   // "BLUE 3", cut to fit
    EXPECT_EQ(captionPixels(1, 1), 0u);    // no caption given

    EXPECT_EQ(sky::makeContactSheet({}, {}, 3).width, 0u);
    const sky::ImageRgba8 one = sky::makeContactSheet({solid(8, 8, 1, 2, 3)}, {}, 0);
    EXPECT_EQ(one.width, 8 + 2 * m);
}

// Small renders go on the reference-pairs sheet enlarged: each pixel becomes a factor x factor block.
TEST(ContactSheet, EnlargedImageRepeatsEachPixel)
{
    sky::ImageRgba8 two = solid(2, 1, 10, 20, 30);
    two.pixel(1, 0)[0] = 200;
    const sky::ImageRgba8 big = sky::enlargeImage(two, 3);
    ASSERT_EQ(big.width, 6u);
    ASSERT_EQ(big.height, 3u);
    EXPECT_EQ(big.pixel(2, 2)[0], 10);
    EXPECT_EQ(big.pixel(3, 0)[0], 200);
    EXPECT_EQ(big.pixel(5, 2)[0], 200);
    EXPECT_EQ(big.pixel(5, 2)[2], 30);
    EXPECT_EQ(sky::enlargeImage(two, 0).pixels, two.pixels);
}

// The median cloud luminance of a render (the captions of the reference pairs): over the pixels more than half
// covered, of radiance / alpha.
TEST(CloudLuminance, MedianOverThePixelsMoreThanHalfCovered)
{
    sky::RenderResult r;
    r.width = 4;
    r.height = 1;
    // Premultiplied grey radiance and alpha: luminance 1 (alpha 1), skipped (0.25), skipped (0.5), 0.5 (0.8).
    const float pixels[4][2] = {{1.0f, 1.0f}, {0.2f, 0.25f}, {0.5f, 0.5f}, {0.4f, 0.8f}};
    for (const auto& p : pixels)
        for (float v : {p[0], p[0], p[0], p[1]})
            r.cloudRgbaHalf.push_back(glm::packHalf1x16(v));
    const std::vector<sky::CloudPixel> cloud = sky::cloudPixels(r);
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud[1].index, 3u);
    EXPECT_NEAR(cloud[0].luminance, 1.0, 1e-3);
    EXPECT_NEAR(cloud[1].luminance, 0.5, 1e-3);
    EXPECT_NEAR(sky::medianCloudLuminance(r), 1.0, 1e-3);  // the upper of two
    EXPECT_EQ(sky::medianOf({3.0, 1.0, 2.0}), 2.0);
    r.cloudRgbaHalf.clear();
    EXPECT_EQ(sky::medianCloudLuminance(r), 0.0);
}

}  // namespace
