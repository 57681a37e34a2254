// SPDX-License-Identifier: MIT
// The one folder the daemon writes files under ([service] files_root): write_files prefixes, files
// subscriptions and the config's files_dir are names relative to it. A name is refused when it is
// absolute, has a ".." (or "." or empty) component, or a control character; its folders are opened one
// by one with openat(O_NOFOLLOW) from the root, so no symbolic link is ever followed, and the files are
// then written through that open folder (/proc/self/fd/N/NAME), which a rename elsewhere cannot move.
// A file already there is replaced only when this daemon wrote it (an extended attribute it sets, or
// its own list of files it wrote where the file system keeps no such attributes).
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace sky
{

/// $XDG_RUNTIME_DIR/skyservice/frames, else /tmp/skyservice-<uid>/frames.
std::string defaultFilesRoot();

/// A folder beneath the root, held open while files are written into it.
class FilesFolder
{
public:
    FilesFolder() = default;
    FilesFolder(const FilesFolder&) = delete;
    FilesFolder& operator=(const FilesFolder&) = delete;
    ~FilesFolder();

    /// The path writers open for `name` in this folder (through the open descriptor).
    std::string pathOf(const std::string& name) const;

    int fd = -1;
    std::string shown;  ///< root/relative, for messages and the log
};

class FilesRoot
{
public:
    FilesRoot() = default;
    FilesRoot(const FilesRoot&) = delete;
    FilesRoot& operator=(const FilesRoot&) = delete;
    ~FilesRoot();

    /// Creates the root (and missing parents, mode 0700) and opens it. Refused when it is a link, not a
    /// folder, or owned by another user.
    bool open(const std::string& path, std::string& error);
    bool isOpen() const { return fd_ >= 0; }
    const std::string& path() const { return path_; }

    /// Checks a client's relative name (see the top of this file). `what` names the field in messages.
    static bool checkName(const std::string& name, const std::string& what, std::string& error);

    /// Opens the folder `relativeDir` ("" = the root) beneath the root without following links.
    bool openFolder(const std::string& relativeDir, FilesFolder& out, std::string& error) const;

    /// Resolves a file prefix ("dir/name"): opens its folder and checks that each PREFIX+suffix may be
    /// written (absent, or a regular file this daemon wrote). `base` receives the last component.
    bool prepare(const std::string& prefix, const std::vector<std::string>& suffixes, FilesFolder& folder,
                 std::string& base, std::string& error);

    /// Records that the daemon wrote these files (after a successful write).
    void markWritten(const FilesFolder& folder, const std::string& base, const std::vector<std::string>& suffixes);

    /// prepare(), then write(the prefix to write through, error), then markWritten() (also after a
    /// failed write: what it left may be replaced). Messages name the folder beneath the root.
    bool writeBeneath(const std::string& prefix, const std::vector<std::string>& suffixes,
                      const std::function<bool(const std::string& resolvedPrefix, std::string& error)>& write,
                      std::string& error);

private:
    bool ours(int dirFd, const std::string& name) const;

    int fd_ = -1;
    std::string path_;
    mutable std::mutex mutex_;
    std::set<std::pair<uint64_t, uint64_t>> written_;  ///< (device, inode) of files this process wrote
};

}  // namespace sky
