// SPDX-License-Identifier: MIT
#include "weather_ingest/ingest_error.h"

namespace sky
{
namespace
{

std::string compose(const std::string& file, const std::string& location, const std::string& field,
                    const std::string& detail)
{
    std::string s = file;
    if (!location.empty())
        s += ": " + location;
    if (!field.empty())
        s += ": " + field;
    return s + ": " + detail;
}

}  // namespace

IngestError::IngestError(IngestErrorKind kind, const std::string& file, const std::string& location,
                         const std::string& field, const std::string& detail)
    : std::runtime_error(compose(file, location, field, detail)), kind_(kind), file_(file), location_(location),
      field_(field)
{
}

int exitCodeFor(IngestErrorKind kind)
{
    switch (kind)
    {
    case IngestErrorKind::Io: return 3;
    case IngestErrorKind::NotRecognized: return 4;
    case IngestErrorKind::Corrupt: return 5;
    case IngestErrorKind::UnsupportedGrid: return 6;
    case IngestErrorKind::TooLarge: return 6;
    case IngestErrorKind::MissingFields: return 7;
    case IngestErrorKind::BadValues: return 8;
    case IngestErrorKind::Output: return 9;
    }
    return 1;
}

const char* kindName(IngestErrorKind kind)
{
    switch (kind)
    {
    case IngestErrorKind::Io: return "io";
    case IngestErrorKind::NotRecognized: return "not-recognized";
    case IngestErrorKind::Corrupt: return "corrupt";
    case IngestErrorKind::UnsupportedGrid: return "unsupported-grid";
    case IngestErrorKind::TooLarge: return "too-large";
    case IngestErrorKind::MissingFields: return "missing-fields";
    case IngestErrorKind::BadValues: return "bad-values";
    case IngestErrorKind::Output: return "output";
    }
    return "?";
}

}  // namespace sky
