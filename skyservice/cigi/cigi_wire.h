// SPDX-License-Identifier: MIT
// Byte-order-aware reads and writes of CIGI fields. CIGI 3 lets each side send in its own byte order:
// the sender writes the byte-swap magic 0x8000 in its order, and the receiver that reads 0x0080 swaps
// every multi-byte field (ICD 3.3, IG Control "Byte Swap Magic Number"). Bytes and bit fields never swap.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace sky::cigi
{

enum class ByteOrder : uint8_t
{
    Big,
    Little,
};

/// The byte order of the machine this code runs on.
constexpr ByteOrder nativeByteOrder()
{
    return std::endian::native == std::endian::big ? ByteOrder::Big : ByteOrder::Little;
}

/// Reads fixed-offset fields of one packet. The caller has checked that the packet holds `size` bytes.
class WireReader
{
public:
    WireReader(const uint8_t* packet, ByteOrder order) : p_(packet), order_(order) {}

    uint8_t u8(size_t offset) const { return p_[offset]; }
    int8_t i8(size_t offset) const { return static_cast<int8_t>(p_[offset]); }
    uint16_t u16(size_t offset) const { return static_cast<uint16_t>(unsignedAt(offset, 2)); }
    uint32_t u32(size_t offset) const { return static_cast<uint32_t>(unsignedAt(offset, 4)); }
    float f32(size_t offset) const { return std::bit_cast<float>(u32(offset)); }
    double f64(size_t offset) const { return std::bit_cast<double>(unsignedAt(offset, 8)); }
    /// `bits` bits of byte `offset` starting at bit `shift` (bit 0 = least significant, as in the ICD).
    uint8_t bits(size_t offset, unsigned shift, unsigned bits) const
    {
        return static_cast<uint8_t>((p_[offset] >> shift) & ((1u << bits) - 1u));
    }
    bool flag(size_t offset, unsigned shift) const { return bits(offset, shift, 1) != 0; }

private:
    uint64_t unsignedAt(size_t offset, size_t n) const
    {
        uint64_t v = 0;
        for (size_t i = 0; i < n; ++i)
        {
            const size_t byte = order_ == ByteOrder::Big ? i : n - 1 - i;
            v = (v << 8) | p_[offset + byte];
        }
        return v;
    }
    const uint8_t* p_;
    ByteOrder order_;
};

/// Appends one packet of a fixed size; fields are written at their ICD offsets, reserved bytes stay zero.
class WireWriter
{
public:
    WireWriter(std::vector<uint8_t>& out, size_t packetSize, ByteOrder order)
        : out_(out), base_(out.size()), order_(order)
    {
        out_.resize(base_ + packetSize, 0);
    }

    void u8(size_t offset, uint8_t v) { out_[base_ + offset] = v; }
    void i8(size_t offset, int8_t v) { out_[base_ + offset] = static_cast<uint8_t>(v); }
    void u16(size_t offset, uint16_t v) { unsignedAt(offset, 2, v); }
    void u32(size_t offset, uint32_t v) { unsignedAt(offset, 4, v); }
    void f32(size_t offset, float v) { u32(offset, std::bit_cast<uint32_t>(v)); }
    void f64(size_t offset, double v) { unsignedAt(offset, 8, std::bit_cast<uint64_t>(v)); }
    /// ORs `value` (masked to `bits` bits) into byte `offset` at bit `shift`.
    void bits(size_t offset, unsigned shift, unsigned bits, unsigned value)
    {
        out_[base_ + offset] |= static_cast<uint8_t>((value & ((1u << bits) - 1u)) << shift);
    }
    void flag(size_t offset, unsigned shift, bool value) { bits(offset, shift, 1, value ? 1u : 0u); }

private:
    void unsignedAt(size_t offset, size_t n, uint64_t v)
    {
        for (size_t i = 0; i < n; ++i)
        {
            const size_t byte = order_ == ByteOrder::Big ? n - 1 - i : i;
            out_[base_ + offset + byte] = static_cast<uint8_t>(v >> (8 * i));
        }
    }
    std::vector<uint8_t>& out_;
    size_t base_;
    ByteOrder order_;
};

} // namespace sky::cigi
