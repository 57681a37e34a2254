// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_host_metrics.h"

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace sky
{

double processCpuTimeS(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line))
        return -1;
    // The command name (field 2) is in parentheses and may hold spaces: count fields after the last ')'.
    size_t close = line.rfind(')');
    if (close == std::string::npos)
        return -1;
    std::istringstream fields(line.substr(close + 1));
    std::string field;
    unsigned long long utimeTicks = 0, stimeTicks = 0;
    // After ')' come field 3 (state) .. : utime is field 14, stime field 15.
    for (int index = 3; index <= 15 && fields >> field; ++index)
    {
        if (index == 14)
            utimeTicks = std::stoull(field);
        else if (index == 15)
            stimeTicks = std::stoull(field);
    }
    long ticksPerS = sysconf(_SC_CLK_TCK);
    if (!fields || ticksPerS <= 0)
        return -1;
    return double(utimeTicks + stimeTicks) / double(ticksPerS);
}

std::string gpuSmClockMhz()
{
    std::FILE* pipe = popen("nvidia-smi --query-gpu=clocks.sm --format=csv,noheader,nounits 2>/dev/null", "r");
    if (pipe == nullptr)
        return "n/a";
    char line[64] = {};
    bool got = std::fgets(line, sizeof line, pipe) != nullptr;
    pclose(pipe);
    std::string text = got ? line : "";
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
    bool digits = !text.empty();
    for (char c : text)
        digits = digits && std::isdigit(static_cast<unsigned char>(c));
    return digits ? text : "n/a";
}

} // namespace sky
