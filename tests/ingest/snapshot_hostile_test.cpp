// SPDX-License-Identifier: MIT
// Hostile snapshot files: a valid header and metadata declaring arrays far larger than the
// bytes stored. The reader must refuse them with a message, never throw, and never allocate by the
// declared size.
#include "weather_ingest/crc32c.h"
#include "weather_ingest/snapshot_file.h"

#include "snapshot_test_util.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <future>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sky
{
namespace
{

/// Writes a header with a correct header checksum, the metadata, then extends the file with a hole to
/// `totalBytes` (so the file is long enough for what the metadata declares but stores almost nothing).
void writeCrafted(const std::string& path, const nlohmann::json& meta, uint64_t totalBytes, uint32_t payloadCrc = 0)
{
    const std::string text = meta.dump();
    uint8_t header[32] = {0x89, 'S', 'K', 'Y', 'W', 'X', '\r', '\n'};
    const uint32_t version = 1, count = 1;
    const uint64_t payloadBytes = totalBytes - 32;
    std::memcpy(header + 8, &version, 4);
    std::memcpy(header + 12, &count, 4);
    std::memcpy(header + 16, &payloadBytes, 8);
    std::memcpy(header + 24, &payloadCrc, 4);
    const uint32_t headerCrc = crc32c(header, 28);
    std::memcpy(header + 28, &headerCrc, 4);
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    const auto metaBytes = static_cast<uint32_t>(text.size());
    ASSERT_EQ(::write(fd, header, 32), 32);
    ASSERT_EQ(::write(fd, &metaBytes, 4), 4);
    ASSERT_EQ(::write(fd, text.data(), text.size()), ssize_t(text.size()));
    ASSERT_EQ(::ftruncate(fd, off_t(totalBytes)), 0);
    ::close(fd);
}

/// 8192 x 8192 cells (the most a snapshot may hold), no layers.
nlohmann::json bigGridMeta()
{
    return {{"validTimeUnixS", 0},
            {"grid", {{"lat0Deg", 81.9}, {"lon0Deg", 0.0}, {"dLatDeg", -0.02}, {"dLonDeg", 0.04}, {"nLat", 8192},
                      {"nLon", 8192}}},
            {"layers", nlohmann::json::array()},
            {"levelFields", nlohmann::json::array()},
            {"provenance", nlohmann::json::object()},
            {"arrays", nlohmann::json::array()}};
}

long peakRssKb()
{
    rusage u = {};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

// Regression: the reader resized the level field to the declared 64 G floats (256 GB) because the
// sparse file is that long: std::bad_alloc escaped (and killed the daemon's loader thread).
TEST(SnapshotHostile, HugeDeclaredLevelFieldInASparseFileIsRefusedWithoutThrowing)
{
    const std::string path = test::tempPath("huge-level.skywx");
    nlohmann::json meta = bigGridMeta();
    meta["levelFields"] = {{{"name", "q"}, {"units", "kg/kg"}, {"pressurePa", std::vector<float>(1000, 50000.f)}}};
    const uint64_t values = uint64_t(8192) * 8192 * 1000;
    meta["arrays"] = {{{"name", "levelFields/0/values"}, {"type", "f32"}, {"count", values}}};
    writeCrafted(path, meta, 32 + 4 + meta.dump().size() + values * 4);
    std::vector<WeatherSnapshot> out;
    std::string error;
    bool ok = true;
    EXPECT_NO_THROW(ok = readSnapshotFile(path, out, error));
    EXPECT_FALSE(ok);
    EXPECT_TRUE(out.empty());
    EXPECT_NE(error.find("huge-level.skywx"), std::string::npos) << error;
    std::remove(path.c_str());
}

// A 256 MB array in a sparse file with a wrong payload checksum: refused before its array is read, so
// the reader's memory never grows by the declared size (it once read all of it first).
TEST(SnapshotHostile, SparseOrCorruptFileNeverGrowsMemoryByTheDeclaredSize)
{
    const std::string path = test::tempPath("sparse.skywx");
    nlohmann::json meta = bigGridMeta();
    const uint64_t values = uint64_t(8192) * 8192;
    meta["arrays"] = {{{"name", "capeJKg"}, {"type", "f32"}, {"count", values}}};
    writeCrafted(path, meta, 32 + 4 + meta.dump().size() + values * 4);
    const long before = peakRssKb();
    std::vector<WeatherSnapshot> out;
    std::string error;
    EXPECT_FALSE(readSnapshotFile(path, out, error));
    EXPECT_NE(error.find("sparse.skywx"), std::string::npos) << error;
    EXPECT_LT(peakRssKb() - before, 64 * 1024) << "peak RSS grew by the declared array: " << error;
    std::remove(path.c_str());
}

// Regression: a FIFO made the reader block in open() until a writer came (the daemon's weather
// loader wedged for good). It is refused at once now, as are symbolic links and devices. (If the
// reader ever blocks again, the test unblocks it by opening the FIFO itself and fails.)
TEST(SnapshotHostile, FifosLinksAndDevicesAreRefusedAtOnce)
{
    const std::string fifo = test::tempPath("pipe.skywx");
    std::remove(fifo.c_str());
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto reading = std::async(std::launch::async, [&] {
        std::vector<WeatherSnapshot> out;
        std::string error;
        const bool ok = readSnapshotFile(fifo, out, error);
        return std::make_pair(ok, error);
    });
    if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready)
    {
        const int unblock = ::open(fifo.c_str(), O_WRONLY);  // lets the blocked open() return
        reading.wait();
        ::close(unblock);
        FAIL() << "the reader blocked on a FIFO";
    }
    const auto [ok, error] = reading.get();
    EXPECT_FALSE(ok);
    EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;

    const std::string good = test::tempPath("good.skywx"), link = test::tempPath("link.skywx");
    std::string e;
    ASSERT_TRUE(writeSnapshotFile(good, {test::makeSnapshot(0, 0.5f)}, e)) << e;
    std::remove(link.c_str());
    ASSERT_EQ(::symlink(good.c_str(), link.c_str()), 0);
    std::vector<WeatherSnapshot> out;
    EXPECT_FALSE(readSnapshotFile(link, out, e));
    EXPECT_NE(e.find("symbolic link"), std::string::npos) << e;
    EXPECT_FALSE(readSnapshotFile("/dev/zero", out, e));
    EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
    EXPECT_TRUE(readSnapshotFile(good, out, e)) << e;
}

}  // namespace
}  // namespace sky
