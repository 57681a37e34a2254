// SPDX-License-Identifier: MIT
// The on-disk weather snapshot format (".skywx"): versioned, checksummed, several valid times per file.
//
// Layout (all integers little-endian; README "Snapshot format" is the normative description):
//
//   offset  size  field
//   0       8     magic 0x89 'S' 'K' 'Y' 'W' 'X' '\r' '\n'  (PNG-style: catches text-mode and 7-bit damage)
//   8       4     format version (kSnapshotFormatVersion)
//   12      4     number of snapshots
//   16      8     payload size in bytes (the file is exactly 32 + this long)
//   24      4     CRC-32C of the payload
//   28      4     CRC-32C of bytes 0..27
//   32      ...   payload: per snapshot, u32 metadata size, metadata (UTF-8 JSON: valid time, grid, layer
//                 names, provenance, 3D level pressures and the list of arrays that follow), then each
//                 listed array as raw little-endian float32 or uint8 values, in the listed order.
//
// Reading never trusts a size before checking it against the bytes that are left (and, for a file, that
// are really stored: holes do not count), so a corrupted, truncated, sparse or foreign file is rejected
// with a message and no large allocation.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

/// Newest version: 2 adds the optional per-cell array "dataWeight" (WeatherSnapshot::dataWeight).
/// writeSnapshotFile() writes version 1 (byte-identical to older builds) when no snapshot has a
/// dataWeight, else version 2; readSnapshotFile() reads both.
inline constexpr uint32_t kSnapshotFormatVersion = 2;
/// Oldest version readSnapshotFile() accepts.
inline constexpr uint32_t kSnapshotFormatOldestVersion = 1;

/// Largest grid a snapshot may hold (cells): 0.05° global is 25.9 M cells. Larger grids are refused
/// on write and read, so a corrupt header cannot make the reader allocate gigabytes.
inline constexpr size_t kMaxSnapshotCells = 64u * 1024u * 1024u;

/// Largest number of snapshots (valid times) in one file.
inline constexpr uint32_t kMaxSnapshotsPerFile = 4096;

/// Checks that a snapshot is self-consistent: a sane grid (nLat, nLon >= 1, cellCount <=
/// kMaxSnapshotCells, finite lat0/lon0/dLat, dLon > 0, every latitude within [-90, 90]), at most
/// kMaxCloudLayers layers, every non-empty vector of grid.cellCount() values (level fields:
/// pressurePa.size() * cellCount), cloud types <= 10, dataWeight within [0, 1].
///
/// @param[in] snapshot the snapshot to check.
/// @param[out] error what is wrong (names the field), untouched on success.
/// @return true when the snapshot can be written and rendered.
bool validateSnapshot(const WeatherSnapshot& snapshot, std::string& error);

/// Reads every snapshot of a file. The file is opened without following a symbolic link and without
/// blocking, and anything but a regular file (a FIFO, a device, a folder) is refused at once.
///
/// @param[in] path the file.
/// @param[out] out the snapshots in file order; cleared first, and left empty on failure.
/// @param[out] error on failure a message naming the file and what is wrong (truncated, checksum
///   mismatch, unknown version, not a snapshot file, bad field size…).
/// @return true on success. Never throws: a file that is sparse (over 16 MiB long with under an eighth
///   of it stored) or whose payload checksum is wrong is refused before any array is allocated, arrays
///   grow only as their bytes are read, and an allocation that still fails is this file's error.
bool readSnapshotFile(const std::string& path, std::vector<WeatherSnapshot>& out, std::string& error);

/// Parses snapshots from bytes already in memory (same rules as readSnapshotFile; used by the fuzzer).
///
/// @param[in] name shown in error messages.
bool parseSnapshotBytes(const void* data, size_t size, const std::string& name, std::vector<WeatherSnapshot>& out,
                        std::string& error);

/// Writes snapshots atomically: to "<path>.tmp.<pid>" in the same folder, flushed and fsync'ed, then
/// renamed over path. On failure nothing is left behind and an existing file at path is untouched.
///
/// @param[in] path destination.
/// @param[in] snapshots at least one; each must pass validateSnapshot().
/// @param[out] error on failure, why (names the file or the field).
/// @return true on success.
bool writeSnapshotFile(const std::string& path, const std::vector<WeatherSnapshot>& snapshots, std::string& error);

}  // namespace sky
