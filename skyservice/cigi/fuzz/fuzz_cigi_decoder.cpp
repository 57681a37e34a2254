// SPDX-License-Identifier: MIT
// libFuzzer target: any byte string is a possible UDP datagram from a host. The decoder must never read
// outside it, must account for every datagram, and whatever it accepts must leave the IG state in range.
#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/cigi_validate.h"

#include <cmath>
#include <cstdlib>

namespace
{

void check(bool ok)
{
    if (!ok)
        std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace sky::cigi;
    static Decoder decoder;  // counters accumulate across inputs, as on a socket
    static CigiState state;
    const uint64_t before = decoder.counters().datagrams;
    const DecodeResult result = decoder.decode(data, size);
    check(decoder.counters().datagrams == before + 1);
    check(result.accepted || (result.packets.empty() && !result.errors.empty()));
    for (const DecodeError& e : result.errors)
        check(!e.message.empty() && e.offset < (size == 0 ? 1 : size));
    // Every packet handed on passes its own range check again.
    for (const HostPacket& p : result.packets)
        std::visit([](const auto& packet) { check(validate(packet).empty()); }, p);
    applyDatagram(state, result, 0);
    if (state.ownship.valid)
        check(std::abs(state.ownship.latDeg) <= 90 && state.ownship.lonDeg >= -180 && state.ownship.lonDeg < 180);
    for (const auto& [id, layer] : state.globalLayers)
        check(layer.coveragePct >= 0 && layer.coveragePct <= 100 && layer.thicknessM >= 0);
    for (const auto& [id, region] : state.regions)
        check(!region.defined || (region.cornerRadiusM >= 0 && 2 * region.cornerRadiusM <= region.sizeXM + 1e-3f &&
                                  2 * region.cornerRadiusM <= region.sizeYM + 1e-3f));
    if (state.pendingRequests.size() > 1000)
        state.pendingRequests.clear();  // the daemon answers them every frame
    return 0;
}
