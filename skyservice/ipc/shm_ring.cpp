// SPDX-License-Identifier: MIT
// The shared-memory frame ring (layout and locking: shm_layout.h). The writer is the service: it never
// waits for a reader, it only bumps each slot's sequence around its writes. Readers detect torn reads.
#include "skyservice/ipc/shm_ring.h"

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <algorithm>
#include <climits>
#include <fcntl.h>
#include <linux/futex.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace sky
{

// The layout is shared with C readers and other compilers: no implicit padding anywhere, 8-byte
// alignment of every 64-bit field, fixed sizes. A change here is a SKY_SHM_VERSION change.
static_assert(sizeof(SkyShmView) == 7 * 8 + 2 * 4 + 4 * 8 + 2 * 4);
static_assert(offsetof(SkyShmView, width) == 56 && offsetof(SkyShmView, height) == 60);
static_assert(offsetof(SkyShmView, left_deg) == 64 && offsetof(SkyShmView, down_deg) == 88);
static_assert(offsetof(SkyShmView, asymmetric) == 96 && offsetof(SkyShmView, reserved) == 100);
static_assert(sizeof(SkyShmShadowGeoRef) == 3 * 8 + 8 * 8 + 2 * 8 + 2 * 4);
static_assert(offsetof(SkyShmShadowGeoRef, size_texels) == 104);
static_assert(sizeof(SkyShmHeader) == 8 + 4 * 4 + 3 * 8 + 4 * 4 + 3 * 8 + 8 * 8);
static_assert(offsetof(SkyShmHeader, slot_stride) == 24);
static_assert(offsetof(SkyShmHeader, max_width) == 48);
static_assert(offsetof(SkyShmHeader, latest_frame_id) == 64);
static_assert(offsetof(SkyShmHeader, latest_slot) == 72);
static_assert(offsetof(SkyShmHeader, writer_heartbeat_ns) == 80);
static_assert(offsetof(SkyShmHeader, features) == 88 && offsetof(SkyShmHeader, publish_futex) == 92);
static_assert(offsetof(SkyShmHeader, reserved) == 96);
static_assert(sizeof(SkyShmLayer) == 24 && offsetof(SkyShmLayer, offset) == 8);
static_assert(sizeof(SkyShmSlot) ==
              4 * 8 + sizeof(SkyShmView) + 2 * 4 + 4 * 8 + sizeof(SkyShmShadowGeoRef) + 4 * 24 + 4 * 8);
static_assert(offsetof(SkyShmSlot, layers) == 72 + sizeof(SkyShmView) + sizeof(SkyShmShadowGeoRef));
static_assert(offsetof(SkyShmSlot, sequence) == 0);
static_assert(offsetof(SkyShmSlot, view) == 32);
static_assert(offsetof(SkyShmSlot, format) == 32 + sizeof(SkyShmView));
static_assert(offsetof(SkyShmSlot, image_offset) == 40 + sizeof(SkyShmView));
static_assert(offsetof(SkyShmSlot, shadow) == 72 + sizeof(SkyShmView));
static_assert(sizeof(SkyShmSlot) % 8 == 0 && sizeof(SkyShmHeader) % 8 == 0);

namespace
{

constexpr uint64_t kPageBytes = 4096;  // slots and images start on page boundaries (x86-64/arm64 base page)
constexpr uint32_t kMaxSlots = 64;     // a sanity bound; the service uses 2 to 4
constexpr uint32_t kMaxDimension = 16384;

uint64_t alignUp(uint64_t value, uint64_t alignment)
{
    return (value + alignment - 1) / alignment * alignment;
}

uint32_t bytesPerPixel(uint32_t format)
{
    switch (format)
    {
    case SKY_FORMAT_RGBA8_SRGB: return 4;
    case SKY_FORMAT_RGBA16F_LINEAR: return 8;
    case SKY_FORMAT_RGBA16F_PREMULTIPLIED: return 8;
    case SKY_FORMAT_R32F_METRES: return 4;
    case SKY_FORMAT_RG32F_METRES: return 8;
    default: return 0;
    }
}

std::string errnoText(const char* what, const std::string& name)
{
    return std::string(what) + " " + name + ": " + std::strerror(errno);
}

/// The format of each compositing layer (shm_layout.h); [SKY_LAYER_DISPLAY] is the ring's own format.
constexpr uint32_t kLayerFormat[SKY_LAYER_COUNT] = {0, SKY_FORMAT_RGBA16F_LINEAR, SKY_FORMAT_RGBA16F_PREMULTIPLIED,
                                                    SKY_FORMAT_RG32F_METRES};

/// Where things lie in one slot's stride.
struct SlotLayout
{
    uint64_t imageOffset, imageCapacity, shadowOffset, shadowCapacity, stride;
    uint64_t layerOffset[SKY_LAYER_COUNT], layerCapacity[SKY_LAYER_COUNT];
};

SlotLayout slotLayout(const ShmRingConfig& c)
{
    SlotLayout l{};
    l.imageOffset = alignUp(sizeof(SkyShmSlot), kPageBytes);
    l.imageCapacity = uint64_t(c.maxWidth) * c.maxHeight * c.bytesPerPixel;
    uint64_t end = l.imageOffset + alignUp(l.imageCapacity, kPageBytes);
    l.layerOffset[SKY_LAYER_DISPLAY] = l.imageOffset;
    l.layerCapacity[SKY_LAYER_DISPLAY] = l.imageCapacity;
    for (uint32_t k = 1; k < SKY_LAYER_COUNT; ++k)
    {
        l.layerOffset[k] = end;
        l.layerCapacity[k] = uint64_t(c.maxWidth) * c.maxHeight * bytesPerPixel(kLayerFormat[k]);
        end += alignUp(l.layerCapacity[k], kPageBytes);
    }
    l.shadowOffset = end;
    l.shadowCapacity = uint64_t(c.maxShadowSize) * c.maxShadowSize * sizeof(float);
    l.stride = l.shadowOffset + alignUp(l.shadowCapacity, kPageBytes);
    return l;
}

bool validName(const std::string& name)
{
    // POSIX: portable names are "/" followed by characters other than "/" (NAME_MAX bounds the rest).
    return name.size() >= 2 && name.size() <= 255 && name[0] == '/' && name.find('/', 1) == std::string::npos;
}

/// True when `pid` names a running process that is not a zombie (a killed service whose parent has not
/// reaped it yet is gone for our purposes).
bool processRunning(uint32_t pid)
{
    if (pid == 0 || pid > uint32_t(INT32_MAX))
        return false;
    if (::kill(pid_t(pid), 0) != 0 && errno != EPERM)
        return false;
    char path[64];
    std::snprintf(path, sizeof path, "/proc/%u/stat", pid);
    FILE* f = std::fopen(path, "r");
    if (!f)
        return true;  // no /proc: trust kill()
    char buffer[512] = {};
    size_t n = std::fread(buffer, 1, sizeof buffer - 1, f);
    std::fclose(f);
    // "pid (comm) S ...": the state follows the last ')' (comm may contain parentheses).
    const char* close = std::strrchr(buffer, ')');
    return !(n > 0 && close && close[1] == ' ' && (close[2] == 'Z' || close[2] == 'X'));
}

/// The pid of the writer of an existing object `name`, 0 when there is none or it cannot be read.
uint32_t existingWriter(const std::string& name)
{
    int fd = ::shm_open(name.c_str(), O_RDONLY | O_CLOEXEC, 0);
    if (fd < 0)
        return 0;
    uint32_t pid = 0;
    struct stat st{};
    if (::fstat(fd, &st) == 0 && uint64_t(st.st_size) >= sizeof(SkyShmHeader))
    {
        void* p = ::mmap(nullptr, sizeof(SkyShmHeader), PROT_READ, MAP_SHARED, fd, 0);
        if (p != MAP_FAILED)
        {
            const auto* h = static_cast<const SkyShmHeader*>(p);
            if (h->magic == SKY_SHM_MAGIC)
                pid = h->writer_pid;
            ::munmap(p, sizeof(SkyShmHeader));
        }
    }
    ::close(fd);
    return pid;
}

uint64_t monotonicNs()
{
    timespec ts{};
    ::clock_gettime(CLOCK_MONOTONIC, &ts);
    return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}

}  // namespace

bool ShmRingWriter::create(const ShmRingConfig& config, std::string& error)
{
    destroy();
    if (!validName(config.name))
    {
        error = "shared-memory name '" + config.name + "' must be '/' followed by 1-254 characters without '/'";
        return false;
    }
    if (config.slotCount < 2 || config.slotCount > kMaxSlots)
    {
        error = "slot count " + std::to_string(config.slotCount) + " is outside [2, " + std::to_string(kMaxSlots) + "]";
        return false;
    }
    if (config.maxWidth == 0 || config.maxHeight == 0 || config.maxWidth > kMaxDimension ||
        config.maxHeight > kMaxDimension || config.maxShadowSize > kMaxDimension)
    {
        error = "ring size " + std::to_string(config.maxWidth) + "x" + std::to_string(config.maxHeight) + " (shadow " +
                std::to_string(config.maxShadowSize) + ") is outside [1, " + std::to_string(kMaxDimension) + "]";
        return false;
    }
    if (config.bytesPerPixel != 4 && config.bytesPerPixel != 8)
    {
        error = "bytes per pixel " + std::to_string(config.bytesPerPixel) + " is neither 4 nor 8";
        return false;
    }
    // An object left by a crashed service is replaced; one whose writer still runs belongs to another
    // service (its clients would lose their frames), so it is refused.
    uint32_t owner = existingWriter(config.name);
    if (owner != 0 && owner != uint32_t(::getpid()) && processRunning(owner))
    {
        error = "shared memory " + config.name + " belongs to running process " + std::to_string(owner);
        return false;
    }
    ::shm_unlink(config.name.c_str());

    const SlotLayout layout = slotLayout(config);
    const uint64_t slotsOffset = alignUp(sizeof(SkyShmHeader), kPageBytes);
    const uint64_t total = slotsOffset + layout.stride * config.slotCount;

    int fd = ::shm_open(config.name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, mode_t(config.mode & 07777));
    if (fd < 0)
    {
        error = errnoText("shm_open", config.name);
        return false;
    }
    // shm_open applies the umask; the configured mode is what was asked for.
    if (::fchmod(fd, mode_t(config.mode & 07777)) != 0 || ::ftruncate(fd, off_t(total)) != 0)
    {
        error = errnoText("sizing", config.name);
        ::close(fd);
        ::shm_unlink(config.name.c_str());
        return false;
    }
    void* p = ::mmap(nullptr, total, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    ::close(fd);
    if (p == MAP_FAILED)
    {
        error = errnoText("mmap", config.name);
        ::shm_unlink(config.name.c_str());
        return false;
    }
    config_ = config;
    totalBytes_ = total;
    header_ = static_cast<SkyShmHeader*>(p);
    slotsOffset_ = slotsOffset;
    slotStride_ = layout.stride;
    // Up to 3 helpers (4 copying threads): beyond that memory bandwidth, not threads, bounds the copy.
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    copier_ = std::make_unique<ParallelCopy>(std::min(3u, cores - 1));
    // ftruncate zero-filled the object: every slot's sequence is 0 (even, never written), no frame yet.
    SkyShmHeader& h = *header_;
    h.version = SKY_SHM_VERSION;
    h.header_bytes = sizeof(SkyShmHeader);
    h.slot_count = config.slotCount;
    h.slot_header_bytes = sizeof(SkyShmSlot);
    h.slot_stride = layout.stride;
    h.slots_offset = slotsOffset;
    h.total_bytes = total;
    h.max_width = config.maxWidth;
    h.max_height = config.maxHeight;
    h.max_shadow_size = config.maxShadowSize;
    h.writer_pid = uint32_t(::getpid());
    h.features = SKY_SHM_FEATURE_PUBLISH_FUTEX;
    slotShadowId_.assign(config.slotCount, 0);
    for (uint32_t i = 0; i < config.slotCount; ++i)
    {
        SkyShmSlot* s = slot(i);
        s->image_offset = layout.imageOffset;
        s->shadow_offset = layout.shadowOffset;
    }
    // The magic last: a reader that sees it sees a complete header.
    __atomic_store_n(&h.magic, SKY_SHM_MAGIC, __ATOMIC_RELEASE);
    openSlot_ = UINT32_MAX;
    return true;
}

void ShmRingWriter::destroy()
{
    if (!header_)
        return;
    ::munmap(header_, totalBytes_);
    ::shm_unlink(config_.name.c_str());
    header_ = nullptr;
    totalBytes_ = 0;
    openSlot_ = UINT32_MAX;
}

uint32_t ShmRingWriter::beginSlot()
{
    if (!header_)
        return 0;
    if (openSlot_ != UINT32_MAX)
        return openSlot_;  // still open: a failed frame is rewritten in the same slot
    // Round robin after the published slot: the newest frame is never overwritten, so a reader has
    // (slot_count - 1) frame intervals before the writer comes back to what it holds.
    const uint64_t latestId = __atomic_load_n(&header_->latest_frame_id, __ATOMIC_RELAXED);
    const uint64_t latest = __atomic_load_n(&header_->latest_slot, __ATOMIC_RELAXED);
    const uint32_t index = latestId == 0 ? 0u : uint32_t((latest + 1) % config_.slotCount);
    SkyShmSlot* s = slot(index);
    const uint64_t seq = __atomic_load_n(&s->sequence, __ATOMIC_RELAXED);
    __atomic_store_n(&s->sequence, seq | 1u, __ATOMIC_RELAXED);
    // The odd sequence must be visible before any byte of the slot changes.
    __atomic_thread_fence(__ATOMIC_RELEASE);
    openSlot_ = index;
    return index;
}

bool ShmRingWriter::endSlot(const ShmFrame& frame, std::string& error)
{
    if (!header_ || openSlot_ == UINT32_MAX)
    {
        error = "no slot is open (beginSlot first)";
        return false;
    }
    const uint32_t index = openSlot_;
    openSlot_ = UINT32_MAX;
    SkyShmSlot* s = slot(index);
    const uint64_t seq = __atomic_load_n(&s->sequence, __ATOMIC_RELAXED);
    const SlotLayout layout = slotLayout(config_);
    const uint32_t bpp = bytesPerPixel(frame.format);
    const uint64_t tightRow = uint64_t(frame.width) * bpp;
    const uint64_t imageBytes = frame.pixels ? tightRow * frame.height : 0;
    const uint32_t shadowSize = frame.shadowTransmittance ? frame.shadow.size_texels : 0;
    const uint64_t shadowBytes = uint64_t(shadowSize) * shadowSize * sizeof(float);
    std::string why;
    if (bpp == 0)
        why = "frame format " + std::to_string(frame.format) + " is not a SKY_FORMAT_*";
    else if (frame.width == 0 || frame.height == 0 || frame.width > config_.maxWidth || frame.height > config_.maxHeight)
        why = "frame " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " does not fit the ring's " +
                std::to_string(config_.maxWidth) + "x" + std::to_string(config_.maxHeight);
    else if (imageBytes > layout.imageCapacity)
        why = "frame of " + std::to_string(imageBytes) + " bytes exceeds the slot's " + std::to_string(layout.imageCapacity);
    else if (frame.pixels && frame.rowBytes != 0 && frame.rowBytes < tightRow)
        why = "frame row of " + std::to_string(frame.rowBytes) + " bytes is shorter than width * pixel size";
    else if (shadowSize > config_.maxShadowSize)
        why = "shadow map of " + std::to_string(shadowSize) + " texels exceeds the ring's " +
                std::to_string(config_.maxShadowSize);
    else if (frame.layers[SKY_LAYER_DISPLAY] != nullptr)
        why = "the display layer is ShmFrame::pixels, not layers[SKY_LAYER_DISPLAY]";
    if (!why.empty())
    {
        __atomic_store_n(&s->sequence, (seq | 1u) + 1u, __ATOMIC_RELEASE);  // even again, not published
        error = why;
        return false;
    }

    s->frame_id = frame.frameId;
    s->sim_time_unix_s = frame.simTimeUnixS;
    s->exposure = frame.exposure;
    s->view = frame.view;
    s->view.width = frame.width;  // the image's size is the view's size (the slot has no other)
    s->view.height = frame.height;
    s->format = frame.format;
    s->row_bytes = uint32_t(tightRow);
    s->image_offset = layout.imageOffset;
    s->image_bytes = imageBytes;
    s->shadow_offset = layout.shadowOffset;
    s->shadow_bytes = shadowBytes;
    s->shadow = frame.shadow;
    s->shadow.size_texels = shadowSize;
    uint8_t* base = reinterpret_cast<uint8_t*>(s);
    s->layers[SKY_LAYER_DISPLAY] = SkyShmLayer{frame.pixels ? frame.format : 0u, uint32_t(tightRow),
                                               layout.imageOffset, imageBytes};
    copies_.clear();
    for (uint32_t k = 1; k < SKY_LAYER_COUNT; ++k)
    {
        const uint64_t row = uint64_t(frame.width) * bytesPerPixel(kLayerFormat[k]);
        const uint64_t bytes = frame.layers[k] ? row * frame.height : 0;  // <= capacity: the size was checked
        s->layers[k] = SkyShmLayer{bytes ? kLayerFormat[k] : 0u, uint32_t(row), layout.layerOffset[k], bytes};
        if (bytes)
            copies_.push_back(CopyJob{base + layout.layerOffset[k], frame.layers[k], size_t(bytes)});
    }
    if (frame.pixels)
    {
        const uint64_t sourceRow = frame.rowBytes != 0 ? frame.rowBytes : tightRow;
        const auto* src = static_cast<const uint8_t*>(frame.pixels);
        if (sourceRow == tightRow)
            copies_.push_back(CopyJob{base + layout.imageOffset, src, size_t(imageBytes)});
        else
            for (uint32_t y = 0; y < frame.height; ++y)
                std::memcpy(base + layout.imageOffset + y * tightRow, src + y * sourceRow, tightRow);
    }
    // A reused shadow map is copied into each slot once (the slot's shadow bytes are only ever written here).
    const bool slotHasShadow = frame.shadowId != 0 && slotShadowId_[index] == frame.shadowId;
    if (shadowBytes && !slotHasShadow)
        copies_.push_back(CopyJob{base + layout.shadowOffset, frame.shadowTransmittance, size_t(shadowBytes)});
    slotShadowId_[index] = shadowBytes ? frame.shadowId : 0;
    copier_->run(copies_);

    __atomic_store_n(&s->sequence, (seq | 1u) + 1u, __ATOMIC_RELEASE);
    // Publish: the slot first, then the id readers poll (a reader checks the slot's own frame_id anyway).
    __atomic_store_n(&header_->latest_slot, uint64_t(index), __ATOMIC_RELEASE);
    __atomic_store_n(&header_->latest_frame_id, frame.frameId, __ATOMIC_RELEASE);
    __atomic_store_n(&header_->writer_heartbeat_ns, monotonicNs(), __ATOMIC_RELEASE);
    // After the id: a reader that loaded the old count before checking the id either saw the new id or
    // finds the count changed when it waits (shm_layout.h). One syscall per frame, waiters or not.
    __atomic_add_fetch(&header_->publish_futex, 1u, __ATOMIC_SEQ_CST);
    ::syscall(SYS_futex, &header_->publish_futex, FUTEX_WAKE, INT_MAX, nullptr, nullptr, 0);
    return true;
}

bool ShmRingWriter::publish(const ShmFrame& frame, std::string& error)
{
    if (!header_)
    {
        error = "the ring is not created";
        return false;
    }
    beginSlot();
    return endSlot(frame, error);
}

bool ShmRingReader::open(const std::string& name, std::string& error)
{
    close();
    int fd = ::shm_open(name.c_str(), O_RDONLY | O_CLOEXEC, 0);
    if (fd < 0)
    {
        error = errnoText("shm_open", name);
        return false;
    }
    struct stat st{};
    if (::fstat(fd, &st) != 0 || uint64_t(st.st_size) < sizeof(SkyShmHeader))
    {
        error = "shared memory " + name + " is smaller than its header";
        ::close(fd);
        return false;
    }
    const uint64_t size = uint64_t(st.st_size);
    void* p = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
    ::close(fd);
    if (p == MAP_FAILED)
    {
        error = errnoText("mmap", name);
        return false;
    }
    const auto* h = static_cast<const SkyShmHeader*>(p);
    const uint64_t end = h->slots_offset + uint64_t(h->slot_count) * h->slot_stride;
    std::string why;
    if (__atomic_load_n(&h->magic, __ATOMIC_ACQUIRE) != SKY_SHM_MAGIC)
        why = "shared memory " + name + ": bad magic (not a sky frame ring, or not yet initialised)";
    else if (h->version != SKY_SHM_VERSION)
        why = "shared memory " + name + ": version " + std::to_string(h->version) + ", this reader knows " +
                std::to_string(SKY_SHM_VERSION);
    else if (h->header_bytes != sizeof(SkyShmHeader) || h->slot_header_bytes != sizeof(SkyShmSlot))
        why = "shared memory " + name + ": header_bytes/slot_header_bytes do not match this reader's layout";
    else if (h->slot_count < 2 || h->slot_count > kMaxSlots || h->slot_stride < sizeof(SkyShmSlot) ||
             h->slots_offset < sizeof(SkyShmHeader) || h->total_bytes != size || end > size)
        why = "shared memory " + name + ": slot_count/slot_stride/slots_offset/total_bytes do not fit its " +
                std::to_string(size) + " bytes";
    if (!why.empty())
    {
        error = why;
        ::munmap(p, size);
        return false;
    }
    header_ = h;
    mappedBytes_ = size;
    slotCount_ = h->slot_count;
    slotsOffset_ = h->slots_offset;
    slotStride_ = h->slot_stride;
    return true;
}

const SkyShmSlot* ShmRingReader::slot(uint32_t index) const
{
    if (!header_ || index >= slotCount_)
        return nullptr;
    return reinterpret_cast<const SkyShmSlot*>(reinterpret_cast<const uint8_t*>(header_) + slotsOffset_ +
                                               uint64_t(index) * slotStride_);
}

void ShmRingReader::close()
{
    if (header_)
        ::munmap(const_cast<SkyShmHeader*>(header_), mappedBytes_);
    header_ = nullptr;
    mappedBytes_ = 0;
    slotCount_ = 0;
    slotsOffset_ = slotStride_ = 0;
}

uint64_t ShmRingReader::latestFrameId() const
{
    return header_ ? __atomic_load_n(&header_->latest_frame_id, __ATOMIC_ACQUIRE) : 0;
}

bool ShmRingReader::canWaitForPublish() const
{
    return header_ && (__atomic_load_n(&header_->features, __ATOMIC_RELAXED) & SKY_SHM_FEATURE_PUBLISH_FUTEX) != 0;
}

uint64_t ShmRingReader::waitForFrameAfter(uint64_t afterFrameId, int timeoutMs) const
{
    if (!header_)
        return 0;
    const uint32_t published = __atomic_load_n(&header_->publish_futex, __ATOMIC_SEQ_CST);
    uint64_t latest = latestFrameId();
    if (latest > afterFrameId || timeoutMs <= 0)
        return latest;
    if (!canWaitForPublish())
    {
        ::usleep(useconds_t(std::min(timeoutMs, 1) * 1000));
        return latestFrameId();
    }
    timespec timeout{timeoutMs / 1000, long(timeoutMs % 1000) * 1000000L};
    // EAGAIN (a publish came in between), EINTR and ETIMEDOUT all end the wait: the caller checks the id.
    ::syscall(SYS_futex, &header_->publish_futex, FUTEX_WAIT, published, &timeout, nullptr, 0);
    return latestFrameId();
}

bool ShmRingReader::acquire(ShmFrameView& out) const
{
    if (!header_ || __atomic_load_n(&header_->latest_frame_id, __ATOMIC_ACQUIRE) == 0)
        return false;
    out.corrupt = false;
    const uint64_t index = __atomic_load_n(&header_->latest_slot, __ATOMIC_ACQUIRE);
    if (index >= slotCount_)
        return false;
    const SkyShmSlot* s = slot(uint32_t(index));
    const uint64_t seq = __atomic_load_n(&s->sequence, __ATOMIC_ACQUIRE);
    if (seq & 1u)
        return false;
    // Every field a client uses is part of the read (checked again at release): bound them by the
    // slot's stride so that a torn or scribbled slot can never point, or size a read, outside it.
    const uint64_t stride = slotStride_;
    const uint64_t imageOffset = s->image_offset, imageBytes = s->image_bytes;
    const uint64_t shadowOffset = s->shadow_offset, shadowBytes = s->shadow_bytes;
    const uint64_t width = s->view.width, height = s->view.height, rowBytes = s->row_bytes;
    const uint64_t shadowTexels = s->shadow.size_texels;
    const uint32_t bppDisplay = bytesPerPixel(s->format);
    const bool slotFits = imageOffset <= stride && imageBytes <= stride - imageOffset && shadowOffset <= stride &&
                      shadowBytes <= stride - shadowOffset &&
                      (imageBytes == 0 || (bppDisplay != 0 && width <= kMaxDimension && height <= kMaxDimension &&
                                           rowBytes >= width * bppDisplay && rowBytes * height <= imageBytes)) &&
                      (shadowBytes == 0 ||
                       (shadowTexels <= kMaxDimension && shadowTexels * shadowTexels * sizeof(float) <= shadowBytes));
    if (!slotFits)
    {
        out.corrupt = true;
        out.slot = s;
        out.sequence = seq;
        return false;
    }
    const auto* base = reinterpret_cast<const uint8_t*>(s);
    out.slot = s;
    out.slotIndex = uint32_t(index);
    out.sequence = seq;
    out.pixels = imageBytes ? base + imageOffset : nullptr;
    out.shadow = shadowBytes ? reinterpret_cast<const float*>(base + shadowOffset) : nullptr;
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
    {
        const SkyShmLayer layer = s->layers[k];
        const uint32_t bpp = bytesPerPixel(layer.format);
        const bool fits = layer.offset <= stride && layer.bytes <= stride - layer.offset && bpp != 0 &&
                          uint64_t(layer.row_bytes) >= uint64_t(s->view.width) * bpp &&
                          uint64_t(layer.row_bytes) * s->view.height <= layer.bytes;
        out.layers[k] = layer.bytes && fits ? base + layer.offset : nullptr;
    }
    return true;
}

bool ShmRingReader::stillValid(const ShmFrameView& view) const
{
    if (!header_ || !view.slot)
        return false;
    // Every load of the slot's data must happen before the second sequence load.
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    return __atomic_load_n(&view.slot->sequence, __ATOMIC_RELAXED) == view.sequence;
}

}  // namespace sky
