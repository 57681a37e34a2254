// SPDX-License-Identifier: MIT
// What sky-service-bench reads about the host around a measurement: a process's CPU time (/proc) and the
// GPU's SM clock (nvidia-smi, where it exists).
#pragma once

#include <string>
#include <sys/types.h>

namespace sky
{

/**
 * CPU time a process has used so far, all its threads together (user + system).
 *
 * @param[in] pid the process.
 * @return seconds of CPU time (utime + stime of /proc/PID/stat), or -1 when unreadable (no /proc, gone).
 **********************************************************************/
double processCpuTimeS(pid_t pid);

/**
 * The first GPU's current SM clock, as `nvidia-smi --query-gpu=clocks.sm` reports it.
 *
 * @return the clock in MHz as text (e.g. "1980"), or "n/a" where nvidia-smi is absent or says nothing.
 **********************************************************************/
std::string gpuSmClockMhz();

} // namespace sky
