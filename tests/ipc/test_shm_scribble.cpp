// SPDX-License-Identifier: MIT
// A ring whose header or slot fields were scribbled over: whoever may read the ring may be
// able to write it (socket_mode 0o666). The reader never addresses or sizes a read outside the mapping.
#include "skyservice/ipc/shm_ring.h"
#include "tests/ipc/ipc_test_util.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sky
{
namespace
{

/// A read-write mapping of the whole ring, as a hostile local process could make.
struct Scribbler
{
    void* base = MAP_FAILED;
    size_t bytes = 0;
    explicit Scribbler(const std::string& name)
    {
        const int fd = ::shm_open(name.c_str(), O_RDWR | O_CLOEXEC, 0);
        struct stat st{};
        if (fd >= 0 && ::fstat(fd, &st) == 0)
        {
            bytes = size_t(st.st_size);
            base = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        }
        if (fd >= 0)
            ::close(fd);
    }
    ~Scribbler()
    {
        if (base != MAP_FAILED)
            ::munmap(base, bytes);
    }
    SkyShmHeader* header() const { return static_cast<SkyShmHeader*>(base); }
    SkyShmSlot* latestSlot() const
    {
        const SkyShmHeader* h = header();
        return reinterpret_cast<SkyShmSlot*>(static_cast<uint8_t*>(base) + h->slots_offset +
                                             h->latest_slot * h->slot_stride);
    }
};

// Regression: a slot's width/height/row_bytes and shadow size were handed to the client unchecked
// (the shm example read past the mapping), and the reader recomputed slot addresses from the header's
// slots_offset/slot_stride at every acquire (scribbling them crashed it).
TEST(ShmRing, ScribbledSlotAndHeaderFieldsNeverLeadOutsideTheMapping)
{
    ShmRingConfig config;
    config.name = test::uniqueShmName();
    config.slotCount = 3;
    config.maxWidth = 64;
    config.maxHeight = 32;
    config.maxShadowSize = 16;
    ShmRingWriter w;
    std::string error;
    ASSERT_TRUE(w.create(config, error)) << error;
    std::vector<uint8_t> pixels(size_t(40) * 20 * 4, 7);
    std::vector<float> shadow(16 * 16, 0.5f);
    ShmFrame f;
    f.frameId = 1;
    f.width = 40;
    f.height = 20;
    f.pixels = pixels.data();
    f.shadowTransmittance = shadow.data();
    f.shadow.size_texels = 16;
    ASSERT_TRUE(w.publish(f, error)) << error;

    ShmRingReader r;
    ASSERT_TRUE(r.open(config.name, error)) << error;
    Scribbler evil(config.name);
    ASSERT_NE(evil.base, MAP_FAILED);
    SkyShmSlot* s = evil.latestSlot();
    ShmFrameView v;
    ASSERT_TRUE(r.acquire(v));

    auto refusedWith = [&](auto&& scribble, auto&& restore) {
        scribble();
        ShmFrameView bad;
        const bool got = r.acquire(bad);
        restore();
        return !got && bad.corrupt;
    };
    const SkyShmSlot saved = *s;
    EXPECT_TRUE(refusedWith([&] { s->view.width = 100000; }, [&] { *s = saved; })) << "width past the slot";
    EXPECT_TRUE(refusedWith([&] { s->view.height = 5000; }, [&] { *s = saved; })) << "height past the slot";
    EXPECT_TRUE(refusedWith([&] { s->row_bytes = 4; }, [&] { *s = saved; })) << "rows shorter than the width";
    EXPECT_TRUE(refusedWith([&] { s->shadow.size_texels = 4000; }, [&] { *s = saved; })) << "shadow past the slot";
    EXPECT_TRUE(refusedWith([&] { s->image_offset = uint64_t(1) << 40; }, [&] { *s = saved; })) << "offset";
    ASSERT_TRUE(r.acquire(v));

    // The geometry is the reader's own copy from open(): scribbling the header changes nothing.
    evil.header()->slot_stride = uint64_t(1) << 40;
    evil.header()->slots_offset = uint64_t(1) << 41;
    ASSERT_TRUE(r.acquire(v));
    EXPECT_EQ(v.slot->frame_id, 1u);
    EXPECT_EQ(v.pixels[40 * 20 * 4 - 1], 7);
    EXPECT_TRUE(r.stillValid(v));
    EXPECT_EQ(r.slot(3), nullptr);
}

}  // namespace
}  // namespace sky
