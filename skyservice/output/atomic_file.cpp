// SPDX-License-Identifier: MIT
#include "skyservice/output/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace sky
{

namespace
{

std::string folderOf(const std::string& path)
{
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos)
        return ".";
    if (slash == 0)
        return "/";
    return path.substr(0, slash);
}

bool fail(std::string& error, const std::string& path, const char* what, int errnoValue)
{
    error = "cannot write '" + path + "': " + what + ": " + std::strerror(errnoValue);
    return false;
}

// A new, empty, uniquely named file beside path (mkstemp: no race with another writer).
bool createTempBeside(const std::string& path, std::string& tempPath, int& fd, std::string& error)
{
    const size_t slash = path.find_last_of('/');
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.empty())
    {
        error = "cannot write '" + path + "': the path names a folder, not a file";
        return false;
    }
    // A leading dot hides the temporary file from globbing readers such as "*.png".
    const std::string prefix = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
    std::string pattern = prefix + "." + name + ".tmp.XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    fd = mkstemp(buffer.data());
    if (fd < 0)
        return fail(error, path, "cannot create a temporary file in its folder", errno);
    tempPath.assign(buffer.data());
    // mkstemp creates 0600; outputs are meant to be read by other users' processes (the IG).
    fchmod(fd, 0644);
    return true;
}

bool syncFile(const std::string& tempPath, const std::string& path, std::string& error)
{
    const int fd = open(tempPath.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return fail(error, path, "cannot reopen the temporary file", errno);
    const bool ok = fsync(fd) == 0;
    const int savedErrno = errno;
    close(fd);
    return ok || fail(error, path, "fsync", savedErrno);
}

bool commit(const std::string& tempPath, const std::string& path, std::string& error)
{
    if (rename(tempPath.c_str(), path.c_str()) != 0)
        return fail(error, path, "rename from the temporary file", errno);
    // Make the rename itself durable; a folder that cannot be opened for reading is not an error.
    const int folder = open(folderOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (folder >= 0)
    {
        fsync(folder);
        close(folder);
    }
    return true;
}

}  // namespace

bool writeFileAtomic(const std::string& path, const void* data, size_t bytes, std::string& error)
{
    std::string tempPath;
    int fd = -1;
    if (!createTempBeside(path, tempPath, fd, error))
        return false;
    const char* cursor = static_cast<const char*>(data);
    size_t left = bytes;
    while (left > 0)
    {
        const ssize_t written = write(fd, cursor, left);
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0)
        {
            const int savedErrno = written < 0 ? errno : EIO;
            close(fd);
            unlink(tempPath.c_str());
            return fail(error, path, "write", savedErrno);
        }
        cursor += written;
        left -= size_t(written);
    }
    if (fsync(fd) != 0)
    {
        const int savedErrno = errno;
        close(fd);
        unlink(tempPath.c_str());
        return fail(error, path, "fsync", savedErrno);
    }
    if (close(fd) != 0)
    {
        const int savedErrno = errno;
        unlink(tempPath.c_str());
        return fail(error, path, "close", savedErrno);
    }
    if (!commit(tempPath, path, error))
    {
        unlink(tempPath.c_str());
        return false;
    }
    return true;
}

bool writeFileAtomicWith(const std::string& path, const FileWriter& writer, std::string& error)
{
    std::string tempPath;
    int fd = -1;
    if (!createTempBeside(path, tempPath, fd, error))
        return false;
    close(fd);
    std::string writerError;
    bool ok = false;
    try
    {
        ok = writer(tempPath, writerError);
    }
    catch (const std::exception& e)
    {
        writerError = e.what();
    }
    if (!ok)
    {
        unlink(tempPath.c_str());
        error = "cannot write '" + path + "': " + (writerError.empty() ? "the writer failed" : writerError);
        return false;
    }
    if (!syncFile(tempPath, path, error) || !commit(tempPath, path, error))
    {
        unlink(tempPath.c_str());
        return false;
    }
    return true;
}

}  // namespace sky
