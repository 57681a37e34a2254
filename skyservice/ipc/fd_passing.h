// SPDX-License-Identifier: MIT
// File descriptors over a Unix domain stream socket (SCM_RIGHTS), shared by the control socket server
// and libskyclient. The fds ride on the first byte of the data sent with them (PROTOCOL.md: on the
// reply line they belong to). Sends never raise SIGPIPE (MSG_NOSIGNAL) and never block (MSG_DONTWAIT).
#pragma once

#include <cstddef>
#include <sys/types.h>
#include <vector>

namespace sky
{

/// Most fds one message carries (the kernel's SCM_MAX_FD is 253; a subscribe needs 2 * slots + 1).
constexpr size_t kMaxFdsPerMessage = 64;

/**
 * Sends `bytes` of `data` with `fdCount` fds attached (none when fdCount is 0).
 *
 * @return the bytes sent (the fds went with them when > 0), or -1 with errno (EAGAIN: try later).
 **********************************************************************/
ssize_t sendWithFds(int socket, const void* data, size_t bytes, const int* fds, size_t fdCount);

/**
 * Receives up to `bytes` without blocking; fds that came along (close-on-exec) are appended to `fds`.
 *
 * @return the bytes received, 0 at end of stream, -1 with errno (EAGAIN: nothing yet).
 **********************************************************************/
ssize_t receiveWithFds(int socket, void* data, size_t bytes, std::vector<int>& fds);

}  // namespace sky
