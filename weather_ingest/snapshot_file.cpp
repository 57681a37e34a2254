// SPDX-License-Identifier: MIT
#include "weather_ingest/snapshot_file.h"

#include "weather_ingest/crc32c.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

static_assert(std::endian::native == std::endian::little, "the snapshot format is little-endian; add byte swapping");

namespace sky
{
namespace
{

constexpr uint8_t kMagic[8] = {0x89, 'S', 'K', 'Y', 'W', 'X', '\r', '\n'};
constexpr size_t kHeaderBytes = 32;
constexpr uint32_t kMaxMetadataBytes = 16u * 1024u * 1024u;  // provenance is text; 16 MB is generous
constexpr uint8_t kMaxCloudType = static_cast<uint8_t>(CloudType::Stratus);
constexpr uint64_t kSparseSlackBytes = 16u << 20;  // files below this are never refused as sparse

/// One array of a snapshot as the file lists it: exactly one of f32/u8 is set.
struct ArrayRef
{
    std::string name;
    std::vector<float>* f32 = nullptr;
    std::vector<uint8_t>* u8 = nullptr;
    size_t expectedCount = 0;  ///< the only non-zero count allowed
};

/// Every array a snapshot can carry, in file order. The snapshot's layers and level fields must
/// already exist (their count comes from the metadata).
std::vector<ArrayRef> listArrays(WeatherSnapshot& s)
{
    const size_t n = s.grid.cellCount();
    std::vector<ArrayRef> refs;
    for (size_t i = 0; i < s.layers.size(); ++i)
    {
        CloudLayerFields& l = s.layers[i];
        const std::string p = "layers/" + std::to_string(i) + "/";
        refs.push_back({p + "coverage", &l.coverage, nullptr, n});
        refs.push_back({p + "baseAltitudeM", &l.baseAltitudeM, nullptr, n});
        refs.push_back({p + "topAltitudeM", &l.topAltitudeM, nullptr, n});
        refs.push_back({p + "type", nullptr, &l.type, n});
        refs.push_back({p + "precipitationMmH", &l.precipitationMmH, nullptr, n});
        refs.push_back({p + "windEastMS", &l.windEastMS, nullptr, n});
        refs.push_back({p + "windNorthMS", &l.windNorthMS, nullptr, n});
    }
    refs.push_back({"high/coverage", &s.high.coverage, nullptr, n});
    refs.push_back({"high/altitudeM", &s.high.altitudeM, nullptr, n});
    refs.push_back({"high/type", nullptr, &s.high.type, n});
    refs.push_back({"high/windEastMS", &s.high.windEastMS, nullptr, n});
    refs.push_back({"high/windNorthMS", &s.high.windNorthMS, nullptr, n});
    refs.push_back({"capeJKg", &s.capeJKg, nullptr, n});
    refs.push_back({"tropopauseAltitudeM", &s.tropopauseAltitudeM, nullptr, n});
    refs.push_back({"dataWeight", &s.dataWeight, nullptr, n}); // version 2
    for (size_t i = 0; i < s.levelFields.size(); ++i)
        refs.push_back({"levelFields/" + std::to_string(i) + "/values", &s.levelFields[i].values, nullptr,
                        n * s.levelFields[i].pressurePa.size()});
    return refs;
}

size_t arraySize(const ArrayRef& r) { return r.f32 ? r.f32->size() : r.u8->size(); }

/// Reads the payload, from memory or a file, keeping the running CRC and the bytes left.
class PayloadReader
{
public:
    PayloadReader(const uint8_t* mem, std::FILE* file, uint64_t bytes) : mem_(mem), file_(file), left_(bytes) {}

    uint64_t left() const { return left_; }
    uint32_t crc() const { return crc_; }

    bool read(void* dst, size_t n)
    {
        if (n > left_)
            return false;
        if (mem_)
        {
            std::memcpy(dst, mem_, n);
            mem_ += n;
        }
        else if (n > 0 && std::fread(dst, 1, n, file_) != n)
        {
            return false;
        }
        crc_ = crc32c(dst, n, crc_);
        left_ -= n;
        return true;
    }

private:
    const uint8_t* mem_;
    std::FILE* file_;
    uint64_t left_;
    uint32_t crc_ = 0;
};

template <typename T> T loadLe(const uint8_t* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

bool fail(std::string& error, const std::string& name, const std::string& what)
{
    error = name + ": " + what;
    return false;
}

nlohmann::json metadataOf(const WeatherSnapshot& s, const std::vector<ArrayRef>& arrays)
{
    nlohmann::json m;
    m["validTimeUnixS"] = s.validTimeUnixS;
    m["grid"] = {{"lat0Deg", s.grid.lat0Deg}, {"lon0Deg", s.grid.lon0Deg}, {"dLatDeg", s.grid.dLatDeg},
                 {"dLonDeg", s.grid.dLonDeg}, {"nLat", s.grid.nLat},     {"nLon", s.grid.nLon}};
    m["layers"] = nlohmann::json::array();
    for (const CloudLayerFields& l : s.layers)
        m["layers"].push_back({{"name", l.name}});
    m["levelFields"] = nlohmann::json::array();
    for (const PressureLevelField& f : s.levelFields)
        m["levelFields"].push_back({{"name", f.name}, {"units", f.units}, {"pressurePa", f.pressurePa}});
    m["provenance"] = s.provenance;
    m["arrays"] = nlohmann::json::array();
    for (const ArrayRef& a : arrays)
        if (arraySize(a) > 0)
            m["arrays"].push_back({{"name", a.name}, {"type", a.f32 ? "f32" : "u8"}, {"count", arraySize(a)}});
    return m;
}

/// Builds the snapshot skeleton (grid, layers, level fields) from metadata; arrays are read later.
bool snapshotFromMetadata(const nlohmann::json& m, WeatherSnapshot& s, std::string& error)
{
    try
    {
        s.validTimeUnixS = m.at("validTimeUnixS").get<int64_t>();
        const nlohmann::json& g = m.at("grid");
        s.grid.lat0Deg = g.at("lat0Deg").get<double>();
        s.grid.lon0Deg = g.at("lon0Deg").get<double>();
        s.grid.dLatDeg = g.at("dLatDeg").get<double>();
        s.grid.dLonDeg = g.at("dLonDeg").get<double>();
        s.grid.nLat = g.at("nLat").get<uint32_t>();
        s.grid.nLon = g.at("nLon").get<uint32_t>();
        const nlohmann::json& layers = m.at("layers");
        if (!layers.is_array() || layers.size() > size_t(kMaxCloudLayers))
            return fail(error, "metadata", "more than " + std::to_string(kMaxCloudLayers) + " layers");
        for (const nlohmann::json& l : layers)
        {
            s.layers.emplace_back();
            s.layers.back().name = l.at("name").get<std::string>();
        }
        for (const nlohmann::json& f : m.at("levelFields"))
        {
            PressureLevelField field;
            field.name = f.at("name").get<std::string>();
            field.units = f.at("units").get<std::string>();
            field.pressurePa = f.at("pressurePa").get<std::vector<float>>();
            if (field.pressurePa.size() > 1000)
                return fail(error, "metadata", "level field '" + field.name + "' has over 1000 levels");
            s.levelFields.push_back(std::move(field));
        }
        s.provenance = m.at("provenance").get<std::map<std::string, std::string>>();
    }
    catch (const nlohmann::json::exception& e)
    {
        return fail(error, "metadata", e.what());
    }
    return true;
}

bool gridError(const LatLonGrid& g, std::string& error)
{
    const bool finite = std::isfinite(g.lat0Deg) && std::isfinite(g.lon0Deg) && std::isfinite(g.dLatDeg) &&
                        std::isfinite(g.dLonDeg);
    if (g.nLat == 0 || g.nLon == 0)
        return fail(error, "grid", "empty (" + std::to_string(g.nLat) + " x " + std::to_string(g.nLon) + ")");
    if (g.cellCount() > kMaxSnapshotCells)
        return fail(error, "grid", std::to_string(g.nLat) + " x " + std::to_string(g.nLon) + " cells exceeds the limit of " +
                                       std::to_string(kMaxSnapshotCells));
    if (!finite || !(g.dLonDeg > 0))
        return fail(error, "grid", "non-finite origin or spacing, or dLonDeg <= 0");
    const double lastLatDeg = g.lat0Deg + g.dLatDeg * double(g.nLat - 1);
    if (std::abs(g.lat0Deg) > 90.0 + 1e-6 || std::abs(lastLatDeg) > 90.0 + 1e-6)
        return fail(error, "grid", "latitudes outside [-90, 90]");
    return true;
}

uint32_t versionFor(const std::vector<WeatherSnapshot>& snapshots)
{
    for (const WeatherSnapshot& s : snapshots)
        if (!s.dataWeight.empty())
            return kSnapshotFormatVersion;
    return kSnapshotFormatOldestVersion;
}

struct Header
{
    uint32_t version = 0;
    uint32_t count = 0;
    uint64_t payloadBytes = 0;
    uint32_t payloadCrc = 0;
};

/// Checks the 32-byte header against the file's real length (totalBytes).
bool parseHeader(const uint8_t* header, uint64_t totalBytes, const std::string& name, Header& h, std::string& error)
{
    if (totalBytes < kHeaderBytes || std::memcmp(header, kMagic, 8) != 0)
    {
        if (totalBytes == 0)
            return fail(error, name, "empty file (0 bytes), not a weather snapshot");
        if (totalBytes < 8 || std::memcmp(header, kMagic, 8) != 0)
            return fail(error, name, "not a weather snapshot file (bad magic; expected '\\x89SKYWX\\r\\n')");
        return fail(error, name, "truncated header (" + std::to_string(totalBytes) + " of 32 bytes)");
    }
    h.version = loadLe<uint32_t>(header + 8);
    h.count = loadLe<uint32_t>(header + 12);
    h.payloadBytes = loadLe<uint64_t>(header + 16);
    h.payloadCrc = loadLe<uint32_t>(header + 24);
    if (crc32c(header, 28) != loadLe<uint32_t>(header + 28))
        return fail(error, name, "header checksum mismatch (corrupted file)");
    if (h.version < kSnapshotFormatOldestVersion || h.version > kSnapshotFormatVersion)
        return fail(error, name,
                    "format version " + std::to_string(h.version) + " is not supported (this build reads " +
                        std::to_string(kSnapshotFormatOldestVersion) + " to " + std::to_string(kSnapshotFormatVersion) +
                        ")");
    if (h.payloadBytes != totalBytes - kHeaderBytes)
        return fail(error, name,
                    (h.payloadBytes > totalBytes - kHeaderBytes ? "truncated: header says "
                                                                 : "trailing data: header says ") +
                        std::to_string(h.payloadBytes + kHeaderBytes) + " bytes, file has " +
                        std::to_string(totalBytes));
    if (h.count == 0 || h.count > kMaxSnapshotsPerFile)
        return fail(error, name, "bad snapshot count " + std::to_string(h.count));
    return true;
}

/// Grows `values` to n elements as the bytes arrive, a chunk at a time: the memory touched is never
/// more than what was really read, whatever size was declared.
template <typename T> bool readArray(PayloadReader& in, std::vector<T>& values, uint64_t n)
{
    constexpr size_t kChunkValues = (16u << 20) / sizeof(T);
    values.reserve(size_t(n));
    while (values.size() < n)
    {
        const size_t at = values.size();
        const size_t take = size_t(std::min<uint64_t>(kChunkValues, n - at));
        values.resize(at + take);
        if (!in.read(values.data() + at, take * sizeof(T)))
            return false;
    }
    return true;
}

bool parseSnapshots(const uint8_t* mem, std::FILE* file, const Header& header, const std::string& name,
                    std::vector<WeatherSnapshot>& out, std::string& error)
{
    const uint32_t version = header.version;
    const uint32_t count = header.count;
    const uint32_t payloadCrc = header.payloadCrc;
    PayloadReader in(mem, file, header.payloadBytes);
    std::vector<WeatherSnapshot> snapshots(count);
    for (uint32_t si = 0; si < count; ++si)
    {
        const std::string where = name + ": snapshot " + std::to_string(si);
        uint32_t metaBytes = 0;
        if (!in.read(&metaBytes, 4) || metaBytes > kMaxMetadataBytes || metaBytes > in.left())
            return fail(error, where, "bad or truncated metadata size");
        std::string metaText(metaBytes, '\0');
        if (!in.read(metaText.data(), metaBytes))
            return fail(error, where, "truncated metadata");
        const nlohmann::json meta = nlohmann::json::parse(metaText, nullptr, false);
        if (meta.is_discarded() || !meta.is_object())
            return fail(error, where, "metadata is not valid JSON");
        WeatherSnapshot& s = snapshots[si];
        if (!snapshotFromMetadata(meta, s, error) || !gridError(s.grid, error))
            return fail(error, where, error);
        std::vector<ArrayRef> refs = listArrays(s);
        try
        {
            for (const nlohmann::json& a : meta.at("arrays"))
            {
                const std::string arrayName = a.at("name").get<std::string>();
                const std::string type = a.at("type").get<std::string>();
                const uint64_t n = a.at("count").get<uint64_t>();
                auto it = std::find_if(refs.begin(), refs.end(), [&](const ArrayRef& r) { return r.name == arrayName; });
                if (it == refs.end() || (version < 2 && arrayName == "dataWeight"))
                    return fail(error, where, "unknown array '" + arrayName + "'");
                if (type != (it->f32 ? "f32" : "u8") || n != it->expectedCount || arraySize(*it) != 0)
                    return fail(error, where, "array '" + arrayName + "' has a wrong type, count or is repeated");
                const uint64_t bytes = n * (it->f32 ? 4u : 1u);
                if (bytes > in.left())
                    return fail(error, where, "truncated in array '" + arrayName + "'");
                if (!(it->f32 ? readArray(in, *it->f32, n) : readArray(in, *it->u8, n)))
                    return fail(error, where, "read error in array '" + arrayName + "'");
            }
        }
        catch (const nlohmann::json::exception& e)
        {
            return fail(error, where, std::string("array list: ") + e.what());
        }
    }
    if (in.left() != 0)
        return fail(error, name, std::to_string(in.left()) + " unexplained bytes after the last snapshot");
    if (in.crc() != payloadCrc)
        return fail(error, name, "payload checksum mismatch (corrupted file)");
    for (uint32_t si = 0; si < count; ++si)
        if (!validateSnapshot(snapshots[si], error))
            return fail(error, name + ": snapshot " + std::to_string(si), error);
    out = std::move(snapshots);
    return true;
}

struct FileCloser
{
    void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

bool validateSnapshot(const WeatherSnapshot& snapshot, std::string& error)
{
    if (!gridError(snapshot.grid, error))
        return false;
    if (snapshot.layers.size() > size_t(kMaxCloudLayers))
        return fail(error, "layers", std::to_string(snapshot.layers.size()) + " layers, at most " +
                                         std::to_string(kMaxCloudLayers));
    WeatherSnapshot& s = const_cast<WeatherSnapshot&>(snapshot);  // listArrays only takes addresses
    for (const ArrayRef& a : listArrays(s))
    {
        const size_t n = arraySize(a);
        if (n != 0 && n != a.expectedCount)
            return fail(error, a.name, std::to_string(n) + " values, expected " + std::to_string(a.expectedCount));
        if (a.u8)
            for (uint8_t t : *a.u8)
                if (t > kMaxCloudType)
                    return fail(error, a.name, "cloud type " + std::to_string(t) + " is not a WMO genus (0..10)");
    }
    for (const float w : snapshot.dataWeight)
        if (!(w >= 0.0f && w <= 1.0f))
            return fail(error, "dataWeight", "value " + std::to_string(w) + " outside [0, 1]");
    return true;
}

bool parseSnapshotBytes(const void* data, size_t size, const std::string& name, std::vector<WeatherSnapshot>& out,
                        std::string& error)
{
    out.clear();
    const auto* bytes = static_cast<const uint8_t*>(data);
    uint8_t header[kHeaderBytes] = {};
    if (size > 0)  // an empty buffer may come with a null pointer, which memcpy must never get (UBSan)
        std::memcpy(header, bytes, std::min(size, kHeaderBytes));
    const size_t skip = std::min(size, kHeaderBytes);
    Header h;
    if (!parseHeader(header, size, name, h, error))
        return false;
    try
    {
        return parseSnapshots(bytes + skip, nullptr, h, name, out, error);
    }
    catch (const std::exception& e)  // bad_alloc / length_error: sizes within the limits but not in memory
    {
        out.clear();
        return fail(error, name, std::string("out of memory while reading (") + e.what() + ")");
    }
}

bool readSnapshotFile(const std::string& path, std::vector<WeatherSnapshot>& out, std::string& error)
{
    out.clear();
    // O_NONBLOCK: opening a FIFO must not wait for a writer (it would wedge a loader thread for good);
    // O_NOFOLLOW: a link is refused, not followed. Whatever was opened is then checked before reading.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return fail(error, path, errno == ELOOP ? std::string("is a symbolic link (weather files are not followed)")
                                                : std::string("cannot open: ") + std::strerror(errno));
    struct stat st = {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    {
        ::close(fd);
        return fail(error, path, "not a regular file (FIFOs, devices and folders are refused)");
    }
    std::unique_ptr<std::FILE, FileCloser> f(::fdopen(fd, "rb"));
    if (!f)
    {
        ::close(fd);
        return fail(error, path, std::string("cannot open: ") + std::strerror(errno));
    }
    uint8_t header[kHeaderBytes] = {};
    const size_t got = std::fread(header, 1, kHeaderBytes, f.get());
    const uint64_t total = uint64_t(st.st_size);
    if (got != std::min<uint64_t>(total, kHeaderBytes))
        return fail(error, path, "read error in header");
    Header h;
    if (!parseHeader(header, total, path, h, error))
        return false;
    // A file with holes has a length but not the bytes: its declared arrays would be zeros read from
    // nowhere. Writers never leave holes; some slack allows for filesystems that store zeros compactly.
    const uint64_t storedBytes = uint64_t(st.st_blocks) * 512u;
    if (total > kSparseSlackBytes && storedBytes < total / 8)
        return fail(error, path, "sparse file: " + std::to_string(total) + " bytes long but only " +
                                     std::to_string(storedBytes) + " stored");
    // The payload checksum comes first, before anything is allocated: a corrupted or forged file costs
    // one read through a fixed buffer, never memory by its declared sizes.
    {
        std::vector<uint8_t> buffer(1u << 20);
        uint32_t crc = 0;
        for (uint64_t left = h.payloadBytes; left > 0;)
        {
            const size_t n = size_t(std::min<uint64_t>(left, buffer.size()));
            if (std::fread(buffer.data(), 1, n, f.get()) != n)
                return fail(error, path, "read error in payload");
            crc = crc32c(buffer.data(), n, crc);
            left -= n;
        }
        if (crc != h.payloadCrc)
            return fail(error, path, "payload checksum mismatch (corrupted file)");
        if (std::fseek(f.get(), long(kHeaderBytes), SEEK_SET) != 0)
            return fail(error, path, std::string("seek: ") + std::strerror(errno));
    }
    try
    {
        return parseSnapshots(nullptr, f.get(), h, path, out, error);
    }
    catch (const std::exception& e)  // bad_alloc / length_error: sizes within the file but not in memory
    {
        out.clear();
        return fail(error, path, std::string("out of memory while reading (") + e.what() + ")");
    }
}

bool writeSnapshotFile(const std::string& path, const std::vector<WeatherSnapshot>& snapshots, std::string& error)
{
    if (snapshots.empty() || snapshots.size() > kMaxSnapshotsPerFile)
        return fail(error, path, "nothing to write (or too many snapshots)");
    for (size_t i = 0; i < snapshots.size(); ++i)
        if (!validateSnapshot(snapshots[i], error))
            return fail(error, path + ": snapshot " + std::to_string(i), error);

    const std::string tmp = path + ".tmp." + std::to_string(getpid());
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(tmp.c_str(), "wb"));
    if (!f)
        return fail(error, tmp, std::string("cannot create: ") + std::strerror(errno));
    uint64_t payloadBytes = 0;
    uint32_t crc = 0;
    bool ok = true;
    auto put = [&](const void* p, size_t n) {
        if (ok && n > 0 && std::fwrite(p, 1, n, f.get()) != n)
            ok = false;
        crc = crc32c(p, n, crc);
        payloadBytes += n;
    };
    uint8_t header[kHeaderBytes] = {};
    ok = std::fwrite(header, 1, kHeaderBytes, f.get()) == kHeaderBytes;
    for (const WeatherSnapshot& snapshot : snapshots)
    {
        WeatherSnapshot& s = const_cast<WeatherSnapshot&>(snapshot);  // listArrays only takes addresses
        const std::vector<ArrayRef> arrays = listArrays(s);
        const std::string meta = metadataOf(s, arrays).dump();
        const auto metaBytes = static_cast<uint32_t>(meta.size());
        put(&metaBytes, 4);
        put(meta.data(), meta.size());
        for (const ArrayRef& a : arrays)
        {
            if (a.f32)
                put(a.f32->data(), a.f32->size() * 4);
            else
                put(a.u8->data(), a.u8->size());
        }
    }
    std::memcpy(header, kMagic, 8);
    const uint32_t version = versionFor(snapshots);
    const auto count = static_cast<uint32_t>(snapshots.size());
    std::memcpy(header + 8, &version, 4);
    std::memcpy(header + 12, &count, 4);
    std::memcpy(header + 16, &payloadBytes, 8);
    std::memcpy(header + 24, &crc, 4);
    const uint32_t headerCrc = crc32c(header, 28);
    std::memcpy(header + 28, &headerCrc, 4);
    ok = ok && std::fseek(f.get(), 0, SEEK_SET) == 0 && std::fwrite(header, 1, kHeaderBytes, f.get()) == kHeaderBytes;
    ok = ok && std::fflush(f.get()) == 0 && fsync(fileno(f.get())) == 0;
    const int savedErrno = errno;
    ok = (std::fclose(f.release()) == 0) && ok;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    {
        error = path + ": write failed: " + std::strerror(ok ? errno : savedErrno);
        std::remove(tmp.c_str());
        return false;
    }
    return true;
}

}  // namespace sky
