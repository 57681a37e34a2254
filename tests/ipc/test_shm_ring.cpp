// SPDX-License-Identifier: MIT
// The shared-memory frame ring (skyservice/ipc/shm_ring.h, shm_layout.h): layout, round trip, torn-read
// detection, a concurrent writer/reader stress, a reader killed mid-read, stale and live objects.
#include "skyservice/ipc/shm_ring.h"
#include "tests/ipc/ipc_test_util.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <vector>

extern "C" size_t skyTestCLayout(int what);

namespace sky
{
namespace
{

ShmRingConfig smallConfig(uint32_t slots = 3)
{
    ShmRingConfig c;
    c.name = test::uniqueShmName();
    c.slotCount = slots;
    c.maxWidth = 64;
    c.maxHeight = 32;
    c.maxShadowSize = 16;
    return c;
}

/// A frame whose every pixel byte and shadow texel encode its id (so any mix of two frames shows).
struct TestFrame
{
    std::vector<uint8_t> pixels;
    std::vector<float> shadow;
    ShmFrame frame;
    TestFrame(uint64_t id, uint32_t width, uint32_t height, uint32_t shadowSize)
    {
        pixels.assign(size_t(width) * height * 4, uint8_t(id & 0xff));
        shadow.assign(size_t(shadowSize) * shadowSize, float(id % 1000));
        frame.frameId = id;
        frame.simTimeUnixS = 1.75e9 + double(id);
        frame.exposure = 2.5;
        frame.view.lat_deg = 47.5;
        frame.view.fov_deg = 60;
        frame.width = width;
        frame.height = height;
        frame.pixels = pixels.data();
        frame.shadowTransmittance = shadowSize ? shadow.data() : nullptr;
        frame.shadow.size_texels = shadowSize;
        frame.shadow.extent_m = 40000;
    }
};

TEST(ShmRing, LayoutHasNoPaddingAndMatchesC)
{
    EXPECT_EQ(skyTestCLayout(0), sizeof(SkyShmHeader));
    EXPECT_EQ(skyTestCLayout(1), sizeof(SkyShmSlot));
    EXPECT_EQ(skyTestCLayout(2), sizeof(SkyShmView));
    EXPECT_EQ(skyTestCLayout(3), sizeof(SkyShmShadowGeoRef));
    EXPECT_EQ(skyTestCLayout(4), offsetof(SkyShmHeader, latest_frame_id));
    EXPECT_EQ(skyTestCLayout(5), offsetof(SkyShmSlot, shadow));
    EXPECT_EQ(skyTestCLayout(6), offsetof(SkyShmSlot, image_offset));
    EXPECT_EQ(skyTestCLayout(7), offsetof(SkyShmView, left_deg));
    EXPECT_EQ(skyTestCLayout(8), offsetof(SkyShmView, asymmetric));
    EXPECT_EQ(skyTestCLayout(9), offsetof(SkyShmHeader, publish_futex));
    EXPECT_EQ(sizeof(SkyShmHeader), 152u);
    EXPECT_EQ(offsetof(SkyShmSlot, sequence), 0u);

    ShmRingWriter w;
    std::string error;
    ShmRingConfig config = smallConfig();
    ASSERT_TRUE(w.create(config, error)) << error;
    ShmRingReader r;
    ASSERT_TRUE(r.open(config.name, error)) << error;
    const SkyShmHeader& h = *r.header();
    EXPECT_EQ(h.magic, SKY_SHM_MAGIC);
    EXPECT_EQ(h.version, SKY_SHM_VERSION);
    EXPECT_EQ(h.slot_count, 3u);
    EXPECT_EQ(h.slots_offset % 4096, 0u);
    EXPECT_EQ(h.slot_stride % 4096, 0u);
    EXPECT_GE(h.slot_stride, 4096u + 64u * 32u * 4u + 16u * 16u * 4u);
    EXPECT_EQ(h.total_bytes, w.totalBytes());
    EXPECT_EQ(h.writer_pid, uint32_t(::getpid()));
    EXPECT_EQ(r.latestFrameId(), 0u);
    ShmFrameView v;
    EXPECT_FALSE(r.acquire(v)) << "nothing is published yet";
    // The configured mode, whatever the umask.
    struct stat st{};
    ASSERT_EQ(::stat(("/dev/shm" + config.name).c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
}

TEST(ShmRing, RoundTrip)
{
    ShmRingWriter w;
    std::string error;
    ShmRingConfig config = smallConfig();
    ASSERT_TRUE(w.create(config, error)) << error;
    TestFrame f(7, 40, 20, 16);
    f.frame.view.lon_deg = 8.25;
    ASSERT_TRUE(w.publish(f.frame, error)) << error;

    ShmRingReader r;
    ASSERT_TRUE(r.open(config.name, error)) << error;
    EXPECT_EQ(r.latestFrameId(), 7u);
    ShmFrameView v;
    ASSERT_TRUE(r.acquire(v));
    EXPECT_EQ(v.sequence % 2, 0u);
    EXPECT_EQ(v.slot->frame_id, 7u);
    EXPECT_EQ(v.slot->view.width, 40u);
    EXPECT_EQ(v.slot->view.height, 20u);
    EXPECT_EQ(v.slot->view.lon_deg, 8.25);
    EXPECT_EQ(v.slot->row_bytes, 160u);
    EXPECT_EQ(v.slot->image_bytes, 40u * 20u * 4u);
    EXPECT_EQ(v.slot->exposure, 2.5);
    EXPECT_EQ(v.slot->shadow.size_texels, 16u);
    EXPECT_EQ(v.slot->shadow.extent_m, 40000.0);
    EXPECT_EQ(v.slot->image_offset % 4096, 0u);
    ASSERT_NE(v.pixels, nullptr);
    ASSERT_NE(v.shadow, nullptr);
    EXPECT_EQ(std::vector<uint8_t>(v.pixels, v.pixels + f.pixels.size()), f.pixels);
    EXPECT_EQ(v.shadow[255], 7.0f);
    EXPECT_TRUE(r.stillValid(v));

    // A padded source row is copied tight; a frame without a shadow map says so.
    std::vector<uint8_t> padded(size_t(10) * 100, 0xee);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 80; ++x)
            padded[size_t(y) * 100 + size_t(x)] = uint8_t(y);
    ShmFrame g;
    g.frameId = 8;
    g.width = 20;
    g.height = 10;
    g.rowBytes = 100;
    g.pixels = padded.data();
    ASSERT_TRUE(w.publish(g, error)) << error;
    ASSERT_TRUE(r.acquire(v));
    EXPECT_EQ(v.slot->frame_id, 8u);
    EXPECT_EQ(v.shadow, nullptr);
    EXPECT_EQ(v.slot->shadow_bytes, 0u);
    EXPECT_EQ(v.pixels[9 * 80 + 79], 9);
}

// A reader waiting for a frame sleeps on the ring's publish futex and is woken by the publish itself:
// each publish counts in publish_futex, and a wait for a frame not yet published returns with that frame
// long before its 60 s timeout (which would mean it slept through the wake).
TEST(ShmRing, AWaitingReaderIsWokenByThePublish)
{
    ShmRingWriter w;
    std::string error;
    ShmRingConfig config = smallConfig();
    ASSERT_TRUE(w.create(config, error)) << error;
    ShmRingReader r;
    ASSERT_TRUE(r.open(config.name, error)) << error;
    ASSERT_TRUE(r.canWaitForPublish());
    EXPECT_EQ(r.header()->publish_futex, 0u);
    TestFrame first(1, 8, 4, 0);
    ASSERT_TRUE(w.publish(first.frame, error)) << error;
    EXPECT_EQ(r.header()->publish_futex, 1u);
    EXPECT_EQ(r.waitForFrameAfter(0, 60000), 1u) << "a frame already there returns at once";

    std::atomic<bool> waiting{false};
    uint64_t seen = 0;
    const auto start = std::chrono::steady_clock::now();
    std::thread reader([&] {
        waiting = true;
        do  // a spurious wake (a signal) returns early: wait again
            seen = r.waitForFrameAfter(1, 60000);
        while (seen < 2 && std::chrono::steady_clock::now() - start < std::chrono::seconds(60));
    });
    while (!waiting)
        std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let it fall asleep (not required)
    TestFrame second(2, 8, 4, 0);
    ASSERT_TRUE(w.publish(second.frame, error)) << error;
    reader.join();
    const double waitedS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(seen, 2u);
    EXPECT_LT(waitedS, 30.0) << "the reader slept until its timeout: the publish did not wake it";
    EXPECT_EQ(r.header()->publish_futex, 2u);
}

TEST(ShmRing, OversizedFrameIsRefusedAndNotPublished)
{
    ShmRingWriter w;
    std::string error;
    ASSERT_TRUE(w.create(smallConfig(), error)) << error;
    TestFrame ok(1, 8, 8, 0);
    ASSERT_TRUE(w.publish(ok.frame, error));
    TestFrame big(2, 65, 8, 0);
    EXPECT_FALSE(w.publish(big.frame, error));
    EXPECT_NE(error.find("65x8"), std::string::npos) << error;
    TestFrame bigShadow(3, 8, 8, 17);
    error.clear();
    EXPECT_FALSE(w.publish(bigShadow.frame, error));
    EXPECT_NE(error.find("shadow"), std::string::npos) << error;
    ShmRingReader r;
    ASSERT_TRUE(r.open(w.name(), error));
    EXPECT_EQ(r.latestFrameId(), 1u);
    ShmFrameView v;
    ASSERT_TRUE(r.acquire(v));
    EXPECT_EQ(v.slot->frame_id, 1u);
    // The refused slot's sequence is even again: the next frame goes through.
    TestFrame next(4, 8, 8, 0);
    EXPECT_TRUE(w.publish(next.frame, error)) << error;
    EXPECT_EQ(r.latestFrameId(), 4u);
}

TEST(ShmRing, HeldFrameSurvivesSlotCountMinusOneFramesThenIsTorn)
{
    ShmRingWriter w;
    std::string error;
    ASSERT_TRUE(w.create(smallConfig(3), error)) << error;
    ShmRingReader r;
    ASSERT_TRUE(r.open(w.name(), error)) << error;
    TestFrame f1(1, 16, 16, 4);
    ASSERT_TRUE(w.publish(f1.frame, error));
    ShmFrameView held;
    ASSERT_TRUE(r.acquire(held));
    for (uint64_t id = 2; id <= 3; ++id)
    {
        TestFrame f(id, 16, 16, 4);
        ASSERT_TRUE(w.publish(f.frame, error));
        EXPECT_TRUE(r.stillValid(held)) << "frame " << id << " went to another slot";
    }
    EXPECT_EQ(held.pixels[0], 1);
    TestFrame f4(4, 16, 16, 4);  // the writer laps the ring: back in the held slot
    ASSERT_TRUE(w.publish(f4.frame, error));
    EXPECT_FALSE(r.stillValid(held));
    // While the writer is inside a slot, a reader holding that slot sees it torn too.
    ShmFrameView latest;
    ASSERT_TRUE(r.acquire(latest));
    TestFrame f5(5, 16, 16, 4), f6(6, 16, 16, 4);
    ASSERT_TRUE(w.publish(f5.frame, error));
    ASSERT_TRUE(w.publish(f6.frame, error));
    uint32_t open = w.beginSlot();
    EXPECT_EQ(open, latest.slotIndex);
    EXPECT_FALSE(r.stillValid(latest));
    TestFrame f7(7, 16, 16, 4);
    ASSERT_TRUE(w.endSlot(f7.frame, error));
}

TEST(ShmRing, ConcurrentWriterAndReaderNeverAcceptAMixedFrame)
{
    ShmRingWriter w;
    std::string error;
    ShmRingConfig config = smallConfig(3);
    ASSERT_TRUE(w.create(config, error)) << error;
    constexpr uint64_t kFrames = 5000;
    std::atomic<bool> done{false}, started{false};
    std::atomic<uint64_t> accepted{0}, torn{0}, bad{0};
    std::thread reader([&] {
        ShmRingReader r;
        std::string e;
        started = true;
        if (!r.open(config.name, e))
        {
            bad = 1000000;
            return;
        }
        std::vector<uint8_t> copy;
        while (!done.load())
        {
            ShmFrameView v;
            if (!r.acquire(v))
                continue;
            const uint64_t id = v.slot->frame_id;
            const uint32_t width = v.slot->view.width, height = v.slot->view.height;
            const size_t bytes = size_t(width) * height * 4;
            if (!v.pixels || bytes > 64 * 32 * 4)
            {
                if (r.stillValid(v))
                    ++bad;
                continue;
            }
            copy.assign(v.pixels, v.pixels + bytes);
            const float texel = v.shadow ? v.shadow[15] : -1.0f;
            if (!r.stillValid(v))
            {
                ++torn;
                continue;
            }
            ++accepted;
            bool consistent = texel == float(id % 1000) && width == 8 + id % 57 && height == 4 + id % 29;
            for (uint8_t b : copy)
                consistent = consistent && b == uint8_t(id & 0xff);
            if (!consistent)
                ++bad;
        }
    });
    while (!started.load())
        std::this_thread::yield();
    // At least kFrames, and on until the reader got a fair number of reads in (a fast writer on an
    // idle core could otherwise finish before the reader ran at all).
    for (uint64_t id = 1; id <= kFrames || (accepted.load() < 200 && id < 50 * kFrames); ++id)
    {
        TestFrame f(id, uint32_t(8 + id % 57), uint32_t(4 + id % 29), 4);
        ASSERT_TRUE(w.publish(f.frame, error)) << error;
    }
    done = true;
    reader.join();
    EXPECT_EQ(bad.load(), 0u) << "a read that passed the sequence check had mixed content";
    EXPECT_GT(accepted.load(), 10u);
    std::printf("stress: %llu accepted, %llu torn (detected) reads\n", (unsigned long long)accepted.load(),
                (unsigned long long)torn.load());
}

TEST(ShmRing, WriterNeverWaitsForAReaderKilledMidRead)
{
    // The reader is forked before the writer exists (a writer starts copy threads; a child forked while a
    // thread starts may inherit a held lock and hang) and opens the ring when told it is published.
    ShmRingConfig config = smallConfig(2);
    int ready[2], go[2];
    ASSERT_EQ(::pipe(ready), 0);
    ASSERT_EQ(::pipe(go), 0);
    pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0)
    {
        // The reader: maps, acquires, and is killed while it holds the frame.
        char start = 0;
        if (::read(go[0], &start, 1) != 1)
            ::_exit(1);
        ShmRingReader r;
        std::string e;
        ShmFrameView v;
        char ok = r.open(config.name, e) && r.acquire(v) ? 'y' : 'n';
        if (::write(ready[1], &ok, 1) != 1)
            ::_exit(1);
        ::sleep(60);
        ::_exit(0);
    }
    ::close(go[0]);
    ShmRingWriter w;
    std::string error;
    ASSERT_TRUE(w.create(config, error)) << error;
    TestFrame first(1, 32, 16, 8);
    ASSERT_TRUE(w.publish(first.frame, error));
    ASSERT_EQ(::write(go[1], "g", 1), 1);
    ::close(go[1]);
    ::close(ready[1]);
    char ok = 0;
    ASSERT_EQ(::read(ready[0], &ok, 1), 1);
    ::close(ready[0]);
    EXPECT_EQ(ok, 'y');
    // The writer laps the held slot many times while the reader is alive, then after it is killed.
    const auto start = std::chrono::steady_clock::now();
    for (uint64_t id = 2; id <= 200; ++id)
    {
        if (id == 100)
        {
            ::kill(child, SIGKILL);
            int status = 0;
            ::waitpid(child, &status, 0);
            EXPECT_TRUE(WIFSIGNALED(status));
        }
        TestFrame f(id, 32, 16, 8);
        ASSERT_TRUE(w.publish(f.frame, error)) << error;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(ms, 2000.0) << "199 publishes should never wait on a reader";
    ShmRingReader r;
    ASSERT_TRUE(r.open(config.name, error)) << error;
    ShmFrameView v;
    ASSERT_TRUE(r.acquire(v));
    EXPECT_EQ(v.slot->frame_id, 200u);
    EXPECT_EQ(v.pixels[100], 200);
    EXPECT_TRUE(r.stillValid(v));
}

TEST(ShmRing, StaleObjectIsReplacedLiveOneRefused)
{
    // Both children are forked before this process makes a writer: a writer starts copy threads, and a
    // child forked while another thread may hold the allocator's lock (ASan's especially) can hang in it.
    const std::string name = test::uniqueShmName();
    // A "crashed service": creates the ring and exits without destroying it.
    pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0)
    {
        auto* w = new ShmRingWriter;  // leaked on purpose: _exit runs no destructor anyway
        std::string e;
        ShmRingConfig c = smallConfig();
        c.name = name;
        ::_exit(w->create(c, e) ? 0 : 1);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    // A live writer in another process.
    const std::string liveName = test::uniqueShmName();
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    pid_t live = ::fork();
    ASSERT_GE(live, 0);
    if (live == 0)
    {
        auto* lw = new ShmRingWriter;
        std::string e;
        ShmRingConfig lc = smallConfig();
        lc.name = liveName;
        char ok = lw->create(lc, e) ? 'y' : 'n';
        if (::write(ready[1], &ok, 1) != 1)
            ::_exit(1);
        ::sleep(60);
        ::_exit(0);
    }
    ::close(ready[1]);
    char ok = 0;
    ASSERT_EQ(::read(ready[0], &ok, 1), 1);
    ::close(ready[0]);
    ASSERT_EQ(ok, 'y');

    ShmRingReader stale;
    std::string error;
    ASSERT_TRUE(stale.open(name, error)) << "the crashed writer's object should still exist";
    EXPECT_EQ(stale.header()->writer_pid, uint32_t(child));
    ShmRingConfig c = smallConfig(4);
    c.name = name;
    ShmRingWriter w;
    ASSERT_TRUE(w.create(c, error)) << error;
    ShmRingReader fresh;
    ASSERT_TRUE(fresh.open(name, error)) << error;
    EXPECT_EQ(fresh.header()->slot_count, 4u);
    EXPECT_EQ(fresh.header()->writer_pid, uint32_t(::getpid()));
    // The old mapping stays what it was (the object was unlinked, not rewritten).
    EXPECT_EQ(stale.header()->slot_count, 3u);

    // The live writer keeps its object.
    ShmRingConfig second = smallConfig();
    second.name = liveName;
    ShmRingWriter other;
    error.clear();
    EXPECT_FALSE(other.create(second, error));
    EXPECT_NE(error.find("running process " + std::to_string(live)), std::string::npos) << error;
    ::kill(live, SIGKILL);
    ::waitpid(live, &status, 0);
    EXPECT_TRUE(other.create(second, error)) << error;  // now stale
}

TEST(ShmRing, ReaderRefusesForeignObjectsAndBadConfigsAreNamed)
{
    const std::string name = test::uniqueShmName();
    int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::ftruncate(fd, 8192), 0);
    ::close(fd);
    ShmRingReader r;
    std::string error;
    EXPECT_FALSE(r.open(name, error));
    EXPECT_NE(error.find("magic"), std::string::npos) << error;
    ::shm_unlink(name.c_str());
    error.clear();
    EXPECT_FALSE(r.open(test::uniqueShmName(), error));
    EXPECT_NE(error.find("shm_open"), std::string::npos) << error;

    ShmRingWriter w;
    ShmRingConfig c = smallConfig();
    c.name = "no-slash";
    EXPECT_FALSE(w.create(c, error));
    EXPECT_NE(error.find("no-slash"), std::string::npos) << error;
    c = smallConfig(1);
    EXPECT_FALSE(w.create(c, error));
    EXPECT_NE(error.find("slot count 1"), std::string::npos) << error;
    c = smallConfig();
    c.mode = 0640;
    ASSERT_TRUE(w.create(c, error)) << error;
    struct stat st{};
    ASSERT_EQ(::stat(("/dev/shm" + c.name).c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
    w.destroy();
    EXPECT_NE(::stat(("/dev/shm" + c.name).c_str(), &st), 0) << "destroy unlinks the name";
    w.destroy();  // twice is fine
}

}  // namespace
}  // namespace sky
