// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_framing.h"

#include <algorithm>
#include <cstring>

namespace sky
{
namespace
{

uint64_t be(const uint8_t* p, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i)
        v = (v << 8) | p[i];
    return v;
}

bool endMarker(const uint8_t* p) { return std::memcmp(p, "7777", 4) == 0; }

/// GRIB1 (WMO Manual on Codes, FM 92 GRIB edition 1): IS (8) + PDS + [GDS] + [BMS] + BDS + "7777".
bool checkGrib1(const uint8_t* m, size_t total, std::string& error)
{
    size_t pos = 8;
    if (total < 8 + 28 + 11 + 4 || pos + 8 > total)
        return (error = "GRIB1 message too short"), false;
    const size_t pdsLength = be(m + pos, 3);
    if (pdsLength < 28 || pos + pdsLength > total)
        return (error = "GRIB1 product definition section length " + std::to_string(pdsLength) + " is invalid"), false;
    const uint8_t flags = m[pos + 7];
    pos += pdsLength;
    for (const bool present : {(flags & 0x80) != 0, (flags & 0x40) != 0, true})  // GDS, BMS, BDS
    {
        if (!present)
            continue;
        if (pos + 3 > total)
            return (error = "GRIB1 section runs past the message end"), false;
        const size_t length = be(m + pos, 3);
        if (length < 6 || pos + length > total - 4)
            return (error = "GRIB1 section length " + std::to_string(length) + " runs past the message end"), false;
        pos += length;
    }
    if (pos + 4 != total || !endMarker(m + pos))
        return (error = "GRIB1 sections do not end at the '7777' marker"), false;
    return true;
}

/// GRIB2 (FM 92 GRIB edition 2): sections 0, 1, then repeated [2] [3] 4 5 6 7, then "7777". Each field
/// becomes 0 1 [2] 3 4 5 6 7 8 with the latest sections 2 and 3; a bitmap indicator 254 ("the previous
/// bitmap applies") is replaced by that bitmap so the field stands alone.
bool splitGrib2(const uint8_t* m, size_t total, GribFrame& frame, std::string& error)
{
    struct Section
    {
        const uint8_t* p = nullptr;
        size_t length = 0;
    };
    Section s1, s2, s3, s4, s5, s6, lastBitmap;
    size_t pos = 16;
    int previous = 0;
    while (true)
    {
        if (pos + 4 > total)
            return (error = "GRIB2 message ends without the '7777' marker"), false;
        if (endMarker(m + pos))
        {
            if (pos + 4 != total)
                return (error = "GRIB2 '7777' marker before the declared end"), false;
            if (previous != 7)
                return (error = "GRIB2 message ends before a complete field"), false;
            return true;
        }
        if (pos + 5 > total)
            return (error = "GRIB2 section header runs past the message end"), false;
        const size_t length = be(m + pos, 4);
        const int number = m[pos + 4];
        if (length < 5 || length > total - pos - 4)
            return (error = "GRIB2 section " + std::to_string(number) + " length " + std::to_string(length) +
                            " runs past the message end"),
                   false;
        // Allowed order: 1 after 0; 2 or 3 after 1; 3 after 2; 4 after 3; 5, 6, 7 in turn; 2, 3 or 4 after 7.
        const bool ok = (number == 1 && previous == 0) || (number == 2 && (previous == 1 || previous == 7)) ||
                        (number == 3 && (previous == 1 || previous == 2 || previous == 7)) ||
                        (number == 4 && (previous == 3 || previous == 7)) || (number == 5 && previous == 4) ||
                        (number == 6 && previous == 5) || (number == 7 && previous == 6);
        if (!ok)
            return (error = "GRIB2 section " + std::to_string(number) + " after section " + std::to_string(previous)),
                   false;
        const Section sec{m + pos, length};
        switch (number)
        {
        case 1: s1 = sec; break;
        case 2: s2 = sec; break;
        case 3: s3 = sec; break;
        case 4: s4 = sec; break;
        case 5: s5 = sec; break;
        case 6:
            if (length < 6)
                return (error = "GRIB2 bitmap section too short"), false;
            s6 = sec;
            if (sec.p[5] == 0)
                lastBitmap = sec;
            else if (sec.p[5] == 254 && !lastBitmap.p)
                return (error = "GRIB2 field refers to a previous bitmap that does not exist"), false;
            break;
        case 7:
        {
            const Section bitmap = s6.p[5] == 254 ? lastBitmap : s6;
            const size_t fieldTotal = 16 + s1.length + s2.length + s3.length + s4.length + s5.length + bitmap.length +
                                      length + 4;
            std::vector<uint8_t> field(m, m + 16);
            for (int i = 0; i < 8; ++i)
                field[size_t(8 + i)] = uint8_t(fieldTotal >> (56 - 8 * i));
            for (const Section& part : {s1, s2, s3, s4, s5, bitmap, sec})
                field.insert(field.end(), part.p, part.p + part.length);
            field.insert(field.end(), {'7', '7', '7', '7'});
            frame.fields.push_back(std::move(field));
            break;
        }
        default: break;
        }
        previous = number;
        pos += length;
    }
}

}  // namespace

int nextGribFrame(const uint8_t* data, size_t size, size_t& offset, GribFrame& frame, std::string& error)
{
    static const uint8_t kMagic[] = {'G', 'R', 'I', 'B'};
    const uint8_t* found = std::search(data + std::min(offset, size), data + size, kMagic, kMagic + 4);
    if (found == data + size)
    {
        offset = size;
        return 0;
    }
    const size_t start = size_t(found - data);
    frame = GribFrame{};
    frame.offset = start;
    if (size - start < 16)
        return (error = "truncated: the file ends inside a GRIB header"), -1;
    frame.edition = found[7];
    uint64_t total = 0;
    if (frame.edition == 1)
    {
        total = be(found + 4, 3);
        if (total & 0x800000)
            return (error = "GRIB1 message over 8 MB (ECMWF large-message coding) is not supported"), -1;
    }
    else if (frame.edition == 2)
    {
        total = be(found + 8, 8);
    }
    else
    {
        return (error = "unknown GRIB edition " + std::to_string(frame.edition)), -1;
    }
    if (total > size - start)
        return (error = "truncated: the message declares " + std::to_string(total) + " bytes, the file has " +
                        std::to_string(size - start) + " left"),
               -1;
    const bool ok = frame.edition == 1 ? checkGrib1(found, size_t(total), error)
                                       : splitGrib2(found, size_t(total), frame, error);
    if (!ok)
        return -1;
    if (frame.edition == 1)
        frame.fields.emplace_back(found, found + total);
    offset = start + size_t(total);
    return 1;
}

}  // namespace sky
