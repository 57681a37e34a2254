// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_fields.h"

#include "weather_ingest/ingest_error.h"

#include <filesystem>

namespace sky
{
namespace
{

using R = GribRole;

// Short names and level types as ecCodes 2.x names them. NCEP writes layer cloud cover as "tcc" on
// lowCloudLayer etc.; newer ecCodes call the same parameters "lcc"/"mcc"/"hcc", hence both.
const std::vector<GribRoleRow> kTable = {
    {R::CoverLow, "tcc|lcc", "lowCloudLayer", 0, "GFS", "low cloud cover (%)", "layers[0].coverage"},
    {R::CoverLow, "lcc", "*", 1, "ECMWF", "low cloud cover (0-1)", "layers[0].coverage"},
    {R::CoverBoundaryLayer, "tcc", "boundaryLayerCloudLayer", 0, "GFS", "boundary-layer cloud cover (%)",
     "layers[0].coverage = max(low, boundary layer)"},
    {R::CoverMiddle, "tcc|mcc", "middleCloudLayer", 0, "GFS", "middle cloud cover (%)", "layers[1].coverage"},
    {R::CoverMiddle, "mcc", "*", 1, "ECMWF", "medium cloud cover (0-1)", "layers[1].coverage"},
    {R::CoverConvective, "tcc", "convectiveCloudLayer", 0, "GFS", "convective cloud cover (%)",
     "layers[2].coverage"},
    {R::CoverHigh, "tcc|hcc", "highCloudLayer", 0, "GFS", "high cloud cover (%)", "high.coverage"},
    {R::CoverHigh, "hcc", "*", 1, "ECMWF", "high cloud cover (0-1)", "high.coverage"},
    {R::CoverTotal, "tcc", "atmosphereSingleLayer|entireAtmosphere|surface", 2, "GFS, ECMWF", "total cloud cover",
     "provenance only (layers carry the cover)"},
    {R::PresLowBottom, "pres", "lowCloudBottom", 0, "GFS", "low cloud bottom pressure (Pa)",
     "layers[0].baseAltitudeM"},
    {R::PresLowTop, "pres", "lowCloudTop", 0, "GFS", "low cloud top pressure (Pa)", "layers[0].topAltitudeM"},
    {R::PresMiddleBottom, "pres", "middleCloudBottom", 0, "GFS", "middle cloud bottom pressure (Pa)",
     "layers[1].baseAltitudeM"},
    {R::PresMiddleTop, "pres", "middleCloudTop", 0, "GFS", "middle cloud top pressure (Pa)", "layers[1].topAltitudeM"},
    {R::PresConvBottom, "pres", "convectiveCloudBottom", 0, "GFS", "convective cloud bottom pressure (Pa)",
     "layers[2].baseAltitudeM"},
    {R::PresConvTop, "pres", "convectiveCloudTop", 0, "GFS", "convective cloud top pressure (Pa)",
     "layers[2].topAltitudeM"},
    {R::PresHighBottom, "pres", "highCloudBottom", 0, "GFS", "high cloud bottom pressure (Pa)",
     "high.altitudeM (mid-layer)"},
    {R::PresHighTop, "pres", "highCloudTop", 0, "GFS", "high cloud top pressure (Pa)", "high.altitudeM (mid-layer)"},
    {R::Cape, "cape", "surface", 0, "GFS, ECMWF", "CAPE (J/kg)", "capeJKg; cloud-type rules"},
    {R::Cape, "cape", "*", 1, "GFS", "CAPE of a layer above ground (J/kg)", "capeJKg when no surface CAPE"},
    {R::PrecipRate, "prate", "surface", 0, "GFS", "precipitation rate (kg m-2 s-1)",
     "large-scale part (prate - cprat) to layer 0 or 1"},
    {R::ConvPrecipRate, "cprat", "surface", 0, "GFS", "convective precipitation rate (kg m-2 s-1)",
     "layers[2].precipitationMmH; cloud-type rules"},
    {R::TotalPrecipAcc, "tp", "surface", 0, "GFS, ECMWF", "total precipitation, accumulated (kg m-2 or m)",
     "rate = amount / accumulation period, when no prate"},
    {R::ConvPrecipAcc, "cp|acpcp", "surface", 0, "ECMWF, GFS", "convective precipitation, accumulated",
     "convective rate, when no cprat"},
    {R::LargeScalePrecipAcc, "lsp|ncpcp", "surface", 0, "ECMWF", "large-scale precipitation, accumulated",
     "large-scale rate, when no prate/tp"},
    {R::TropopausePressure, "trpp|pres", "tropopause", 0, "GFS", "tropopause pressure (Pa)",
     "tropopauseAltitudeM when no height"},
    {R::TropopauseHeight, "gh", "tropopause", 0, "GFS", "tropopause geopotential height (gpm)",
     "tropopauseAltitudeM"},
    {R::CloudBaseHeight, "cbh", "*", 0, "ECMWF", "cloud base height above ground (m)",
     "layers[0].baseAltitudeM (+ orography)"},
    {R::Orography, "orog", "surface", 0, "GFS", "orography (m)", "ground for above-ground heights"},
    {R::SurfaceGeopotential, "z", "surface", 0, "ECMWF", "surface geopotential (m2 s-2)",
     "ground for above-ground heights"},
    {R::LevelHeight, "gh", "isobaricInhPa|isobaricInPa", 0, "GFS", "geopotential height on pressure levels (gpm)",
     "pressure -> altitude (log-pressure interpolation)"},
    {R::LevelGeopotential, "z", "isobaricInhPa|isobaricInPa", 0, "ECMWF", "geopotential on pressure levels (m2 s-2)",
     "pressure -> altitude (/ 9.80665)"},
    {R::LevelU, "u", "isobaricInhPa|isobaricInPa", 0, "GFS, ECMWF", "eastward wind on pressure levels (m/s)",
     "windEastMS of each layer at its mid-layer pressure"},
    {R::LevelV, "v", "isobaricInhPa|isobaricInPa", 0, "GFS, ECMWF", "northward wind on pressure levels (m/s)",
     "windNorthMS of each layer at its mid-layer pressure"},
    {R::LevelCloudMixingRatio, "clwmr", "isobaricInhPa|isobaricInPa", 0, "GFS", "cloud mixing ratio (kg/kg)",
     "levelFields 'cloudMixingRatio' (--with-3d)"},
    {R::LevelCloudCover, "cc", "isobaricInhPa|isobaricInPa", 0, "ECMWF", "fraction of cloud cover on levels (0-1)",
     "base/top of layers 0, 1 and high; levelFields 'cloudCover' (--with-3d)"},
    {R::LevelCloudLiquid, "clwc", "isobaricInhPa|isobaricInPa", 0, "ECMWF", "cloud liquid water content (kg/kg)",
     "levelFields 'cloudLiquidWater' (--with-3d)"},
    {R::LevelCloudIce, "ciwc", "isobaricInhPa|isobaricInPa", 0, "ECMWF", "cloud ice water content (kg/kg)",
     "levelFields 'cloudIceWater' (--with-3d)"},
};

bool listed(const char* list, const std::string& name)
{
    const std::string l = std::string("|") + list + "|";
    return l == "|*|" || l.find("|" + name + "|") != std::string::npos;
}

}  // namespace

const std::vector<GribRoleRow>& gribRoleTable() { return kTable; }

bool isLevelRole(GribRole role) { return role >= GribRole::LevelHeight && role < GribRole::Count; }

std::optional<GribRoleRow> gribRoleOf(const GribMessageInfo& info)
{
    for (const GribRoleRow& row : kTable)
        if (listed(row.shortNames, info.shortName) && listed(row.typeOfLevels, info.typeOfLevel))
            return row;
    return std::nullopt;
}

std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress)
{
    const std::string base = std::filesystem::path(file.path()).filename().string();
    std::vector<GribRecord> records;
    GribMessage message;
    while (file.next(message))
    {
        const GribMessageInfo& info = message.info();
        if (progress)
            progress(file.fractionRead(), "message " + std::to_string(info.number) + " " + info.label());
        const std::optional<GribRoleRow> row = gribRoleOf(info);
        if (!row)
            continue;
        GribRecord r;
        r.info = info;
        r.row = *row;
        if (isLevelRole(row->role))
            r.levelPa = info.typeOfLevel == "isobaricInPa" ? double(info.level) : double(info.level) * 100.0;
        r.file = file.path();
        r.source = base + " message " + std::to_string(info.number) + " " + info.label();
        r.field = message.decode(maxCells);
        records.push_back(std::move(r));
    }
    if (file.messagesRead() == 0)
        throw IngestError(IngestErrorKind::NotRecognized, file.path(), "", "", "no GRIB message found");
    return records;
}

}  // namespace sky
