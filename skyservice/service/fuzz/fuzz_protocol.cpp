// SPDX-License-Identifier: MIT
// libFuzzer target: parseRequest must answer any line with a request or an error that says why, never
// crash, and the error reply must be one line of JSON (the framing of PROTOCOL.md).
#include "skyservice/ipc/protocol.h"

#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string_view line(reinterpret_cast<const char*>(data), size);
    sky::ProtocolLimits limits;
    sky::Request request;
    sky::ProtocolError error;
    if (sky::parseRequest(line, limits, request, error))
    {
        if (request.path.find('\0') != std::string::npos || request.clientName.find('\0') != std::string::npos)
            std::abort();  // NUL is refused: a C string would silently cut the text there
        return 0;
    }
    if (error.code.empty() || error.message.empty())
        std::abort();
    const std::string reply = sky::errorReply(error);
    if (reply.find('\n') != std::string::npos || nlohmann::json::parse(reply, nullptr, false).is_discarded())
        std::abort();
    return 0;
}
