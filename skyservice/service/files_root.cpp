// SPDX-License-Identifier: MIT
#include "skyservice/service/files_root.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

namespace sky
{
namespace
{

/// Set on every file the daemon writes: the mark that it may replace the file later (also after a restart).
constexpr const char* kOwnedAttribute = "user.skyservice.written";
constexpr size_t kMaxRemembered = 1u << 16;

std::vector<std::string> splitPath(const std::string& path)
{
    std::vector<std::string> parts;
    size_t at = 0;
    while (at <= path.size())
    {
        const size_t slash = std::min(path.find('/', at), path.size());
        parts.push_back(path.substr(at, slash - at));
        at = slash + 1;
    }
    return parts;
}

std::string sysError(const std::string& what)
{
    return what + ": " + std::strerror(errno);
}

}  // namespace

std::string defaultFilesRoot()
{
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    if (runtime && *runtime)
        return std::string(runtime) + "/skyservice/frames";
    return "/tmp/skyservice-" + std::to_string(getuid()) + "/frames";
}

FilesFolder::~FilesFolder()
{
    if (fd >= 0)
        ::close(fd);
}

std::string FilesFolder::pathOf(const std::string& name) const
{
    return "/proc/self/fd/" + std::to_string(fd) + "/" + name;
}

FilesRoot::~FilesRoot()
{
    if (fd_ >= 0)
        ::close(fd_);
}

bool FilesRoot::open(const std::string& path, std::string& error)
{
    if (path.empty() || path[0] != '/')
    {
        error = "files_root '" + path + "' must be an absolute path";
        return false;
    }
    // Missing folders are made private; existing ones are the operator's choice.
    for (size_t slash = path.find('/', 1); ; slash = path.find('/', slash + 1))
    {
        const std::string part = path.substr(0, slash);
        if (::mkdir(part.c_str(), 0700) != 0 && errno != EEXIST)
        {
            error = sysError("files_root: cannot create " + part);
            return false;
        }
        if (slash == std::string::npos)
            break;
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
    {
        error = sysError("files_root " + path + " (must be a folder, not a link)");
        return false;
    }
    struct stat st{};
    if (::fstat(fd, &st) != 0 || st.st_uid != ::geteuid())
    {
        ::close(fd);
        error = "files_root " + path + " belongs to another user";
        return false;
    }
    if (fd_ >= 0)
        ::close(fd_);
    fd_ = fd;
    path_ = path;
    return true;
}

bool FilesRoot::checkName(const std::string& name, const std::string& what, std::string& error)
{
    if (name.empty() || name[0] == '/')
    {
        error = what + " '" + name + "' must be a relative name beneath the service's files_root";
        return false;
    }
    for (const char c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        {
            error = what + " contains a control character";
            return false;
        }
    for (const std::string& part : splitPath(name))
        if (part.empty() || part == "." || part == ".." || part.size() > 200)
        {
            error = what + " '" + name + "' has an empty, '.', '..' or over-long component";
            return false;
        }
    return true;
}

bool FilesRoot::openFolder(const std::string& relativeDir, FilesFolder& out, std::string& error) const
{
    if (fd_ < 0)
    {
        error = "no files_root: the service writes no files";
        return false;
    }
    if (!relativeDir.empty() && !checkName(relativeDir, "dir", error))
        return false;
    int fd = ::fcntl(fd_, F_DUPFD_CLOEXEC, 0);
    if (fd < 0)
    {
        error = sysError("files_root");
        return false;
    }
    std::string shown = path_;
    if (!relativeDir.empty())
        for (const std::string& part : splitPath(relativeDir))
        {
            shown += "/" + part;
            const int next = ::openat(fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            ::close(fd);
            if (next < 0)
            {
                error = errno == ELOOP || errno == ENOTDIR ? shown + " is not a folder (links are not followed)"
                                                          : sysError(shown);
                return false;
            }
            fd = next;
        }
    if (out.fd >= 0)
        ::close(out.fd);
    out.fd = fd;
    out.shown = shown;
    return true;
}

bool FilesRoot::ours(int dirFd, const std::string& name) const
{
    struct stat st{};
    if (::fstatat(dirFd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
        return false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (written_.count({uint64_t(st.st_dev), uint64_t(st.st_ino)}))
            return true;
    }
    const std::string path = "/proc/self/fd/" + std::to_string(dirFd) + "/" + name;
    char value[2] = {};
    return ::lgetxattr(path.c_str(), kOwnedAttribute, value, sizeof value) == 1 && value[0] == '1';
}

bool FilesRoot::prepare(const std::string& prefix, const std::vector<std::string>& suffixes, FilesFolder& folder,
                        std::string& base, std::string& error)
{
    if (!checkName(prefix, "prefix", error))
        return false;
    const size_t slash = prefix.find_last_of('/');
    const std::string dir = slash == std::string::npos ? std::string() : prefix.substr(0, slash);
    base = slash == std::string::npos ? prefix : prefix.substr(slash + 1);
    if (!openFolder(dir, folder, error))
        return false;
    for (const std::string& suffix : suffixes)
    {
        const std::string name = base + suffix;
        struct stat st{};
        if (::fstatat(folder.fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
        {
            if (errno == ENOENT)
                continue;
            error = sysError(folder.shown + "/" + name);
            return false;
        }
        if (!ours(folder.fd, name))
        {
            error = folder.shown + "/" + name + " exists and was not written by this service: not replaced";
            return false;
        }
    }
    return true;
}

void FilesRoot::markWritten(const FilesFolder& folder, const std::string& base,
                            const std::vector<std::string>& suffixes)
{
    for (const std::string& suffix : suffixes)
    {
        const std::string name = base + suffix;
        struct stat st{};
        if (::fstatat(folder.fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
            continue;
        if (::lsetxattr(folder.pathOf(name).c_str(), kOwnedAttribute, "1", 1, 0) == 0)
            continue;
        // No user attributes on this file system: remember the file for this run (a bounded list).
        std::lock_guard<std::mutex> lock(mutex_);
        if (written_.size() >= kMaxRemembered)
            written_.erase(written_.begin());
        written_.insert({uint64_t(st.st_dev), uint64_t(st.st_ino)});
    }
}

bool FilesRoot::writeBeneath(const std::string& prefix, const std::vector<std::string>& suffixes,
                             const std::function<bool(const std::string& resolvedPrefix, std::string& error)>& write,
                             std::string& error)
{
    FilesFolder folder;
    std::string base;
    if (!prepare(prefix, suffixes, folder, base, error))
        return false;
    const bool ok = write(folder.pathOf(base), error);
    if (!ok)  // messages name the folder, not the descriptor it was written through
    {
        const std::string through = folder.pathOf(""), shown = folder.shown + "/";
        for (size_t at; (at = error.find(through)) != std::string::npos;)
            error.replace(at, through.size(), shown);
    }
    markWritten(folder, base, suffixes);
    return ok;
}

}  // namespace sky
