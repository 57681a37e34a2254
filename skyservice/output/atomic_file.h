// SPDX-License-Identifier: MIT
// Atomic file replacement (skyservice/ipc/PROTOCOL.md): write to a temporary file in the same
// folder, fsync it, rename it over the destination, then fsync the folder. A reader therefore sees
// either the old file or the complete new one, never a partial file; after a failure neither the
// destination nor any temporary file is left changed or behind.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace sky
{

/**
 * Write a block of bytes to a file atomically.
 *
 * @param[in] path destination file; its folder must exist.
 * @param[in] data the bytes to write (may be null when bytes is 0).
 * @param[in] bytes number of bytes.
 * @param[out] error on failure, a message naming the path and the system error.
 * @return true on success.
 **********************************************************************/
bool writeFileAtomic(const std::string& path, const void* data, size_t bytes, std::string& error);

/**
 * Writes a whole file by name (for libraries such as OpenEXR that open the file themselves).
 * Returns false and sets its error message on failure.
 **********************************************************************/
using FileWriter = std::function<bool(const std::string& tempPath, std::string& error)>;

/**
 * Let a writer produce a file under a temporary name, then make it appear atomically at path.
 *
 * @param[in] path destination file; its folder must exist.
 * @param[in] writer called once with the temporary path (an existing empty file in the same folder,
 *   which the writer may truncate and overwrite).
 * @param[out] error on failure, a message naming the path: the writer's message or the system error.
 * @return true on success; on failure the temporary file is removed and path is untouched.
 **********************************************************************/
bool writeFileAtomicWith(const std::string& path, const FileWriter& writer, std::string& error);

}  // namespace sky
