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
    {R::CoverLow, "CLCL", "*", 1, "ICON", "low cloud cover (%)", "layers[0].coverage"},
    {R::CoverBoundaryLayer, "tcc", "boundaryLayerCloudLayer", 0, "GFS", "boundary-layer cloud cover (%)",
     "layers[0].coverage = max(low, boundary layer)"},
    {R::CoverMiddle, "tcc|mcc", "middleCloudLayer", 0, "GFS", "middle cloud cover (%)", "layers[1].coverage"},
    {R::CoverMiddle, "mcc", "*", 1, "ECMWF", "medium cloud cover (0-1)", "layers[1].coverage"},
    {R::CoverMiddle, "CLCM", "*", 1, "ICON", "medium cloud cover (%)", "layers[1].coverage"},
    {R::CoverConvective, "tcc", "convectiveCloudLayer", 0, "GFS", "convective cloud cover (%)", "layers[2].coverage"},
    {R::CoverHigh, "tcc|hcc", "highCloudLayer", 0, "GFS", "high cloud cover (%)", "high.coverage"},
    {R::CoverHigh, "hcc", "*", 1, "ECMWF", "high cloud cover (0-1)", "high.coverage"},
    {R::CoverHigh, "CLCH", "*", 1, "ICON", "high cloud cover (%)", "high.coverage"},
    {R::CoverTotal, "tcc", "atmosphereSingleLayer|entireAtmosphere|surface", 2, "GFS, HRRR, ECMWF", "total cloud cover",
     "provenance only (layers carry the cover)"},
    {R::CoverTotal, "CLCT", "*", 2, "ICON", "total cloud cover (%)", "provenance only (layers carry the cover)"},
    {R::PresLowBottom, "pres", "lowCloudBottom", 0, "GFS", "low cloud bottom pressure (Pa)", "layers[0].baseAltitudeM"},
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
    {R::Cape, "cape", "*", 1, "GFS, HRRR", "CAPE of a layer above ground (J/kg)", "capeJKg when no surface CAPE"},
    {R::Cape, "CAPE_ML|CAPE_CON", "*", 1, "ICON", "CAPE, mean layer or convective (J/kg)", "capeJKg"},
    {R::PrecipRate, "prate", "surface", 0, "GFS, HRRR", "precipitation rate (kg m-2 s-1)",
     "large-scale part (prate - cprat) to layer 0 or 1"},
    {R::ConvPrecipRate, "cprat", "surface", 0, "GFS", "convective precipitation rate (kg m-2 s-1)",
     "layers[2].precipitationMmH; cloud-type rules"},
    {R::TotalPrecipAcc, "tp", "surface", 0, "GFS, ECMWF", "total precipitation, accumulated (kg m-2 or m)",
     "rate = amount / accumulation period, when no prate"},
    {R::TotalPrecipAcc, "TOT_PREC", "*", 0, "ICON", "total precipitation, accumulated (kg m-2)",
     "rate = amount / accumulation period"},
    {R::ConvPrecipAcc, "RAIN_CON", "*", 1, "ICON", "convective rain, accumulated (kg m-2)", "convective rate"},
    {R::LargeScalePrecipAcc, "RAIN_GSP", "*", 1, "ICON", "grid-scale rain, accumulated (kg m-2)",
     "large-scale rate, when no TOT_PREC"},
    {R::ConvPrecipAcc, "cp|acpcp", "surface", 0, "ECMWF, GFS", "convective precipitation, accumulated",
     "convective rate, when no cprat"},
    {R::LargeScalePrecipAcc, "lsp|ncpcp", "surface", 0, "ECMWF", "large-scale precipitation, accumulated",
     "large-scale rate, when no prate/tp"},
    {R::TropopausePressure, "trpp|pres", "tropopause", 0, "GFS", "tropopause pressure (Pa)",
     "tropopauseAltitudeM when no height"},
    {R::TropopauseHeight, "gh", "tropopause", 0, "GFS", "tropopause geopotential height (gpm)", "tropopauseAltitudeM"},
    {R::CloudBaseHeight, "cbh", "*", 0, "ECMWF", "cloud base height above ground (m)",
     "base of the lowest layer present (low, else middle) (+ orography)"},
    {R::CloudBaseHeight, "CEILING", "*", 1, "ICON", "ceiling above ground (m)", "as cbh, when no cbh"},
    {R::CloudBaseHeightMsl, "gh", "cloudBase", 0, "HRRR", "cloud base height (gpm)",
     "base of the lowest layer present (low, else middle)"},
    {R::CloudBaseHeightMsl, "gh", "cloudCeiling", 1, "HRRR", "cloud ceiling height (gpm)", "as cloud base, when none"},
    {R::CloudBaseHeightMsl, "HBAS_CON", "*", 2, "ICON", "convective cloud base above sea level (m)",
     "as cloud base, when none"},
    {R::CloudTopHeightMsl, "gh", "cloudTop", 0, "HRRR", "cloud top height (gpm)",
     "layers[0].topAltitudeM where low cloud is the only volumetric layer"},
    {R::CloudTopHeightMsl, "HTOP_CON", "*", 1, "ICON", "convective cloud top above sea level (m)",
     "as cloud top, when none"},
    {R::Visibility, "vis", "surface", 0, "HRRR", "visibility (m)", "provenance only (not rendered yet)"},
    {R::Orography, "orog", "surface", 0, "GFS", "orography (m)", "ground for above-ground heights"},
    {R::Orography, "HSURF", "*", 1, "ICON", "surface height (m)", "ground for above-ground heights"},
    {R::SurfaceGeopotential, "z", "surface", 0, "ECMWF", "surface geopotential (m2 s-2)",
     "ground for above-ground heights"},
    {R::LevelHeight, "gh", "isobaricInhPa|isobaricInPa", 0, "GFS", "geopotential height on pressure levels (gpm)",
     "pressure -> altitude (log-pressure interpolation)"},
    {R::LevelGeopotential, "z|FI", "isobaricInhPa|isobaricInPa", 0, "ECMWF", "geopotential on pressure levels (m2 s-2)",
     "pressure -> altitude (/ 9.80665)"},
    {R::LevelU, "u|U", "isobaricInhPa|isobaricInPa", 0, "GFS, HRRR, ECMWF, ICON",
     "eastward wind on pressure levels (m/s)", "windEastMS of each layer at its mid-layer pressure"},
    {R::LevelV, "v|V", "isobaricInhPa|isobaricInPa", 0, "GFS, HRRR, ECMWF, ICON",
     "northward wind on pressure levels (m/s)", "windNorthMS of each layer at its mid-layer pressure"},
    {R::LevelCloudMixingRatio, "clwmr", "isobaricInhPa|isobaricInPa", 0, "GFS", "cloud mixing ratio (kg/kg)",
     "levelFields 'cloudMixingRatio' (--with-3d)"},
    {R::LevelCloudCover, "cc|CLC", "isobaricInhPa|isobaricInPa", 0, "ECMWF, ICON", "cloud cover on levels (0-1 or %)",
     "base/top of layers 0, 1 and high; levelFields 'cloudCover' (--with-3d)"},
    {R::LevelCloudLiquid, "clwc|QC", "isobaricInhPa|isobaricInPa", 0, "ECMWF, ICON",
     "cloud liquid water content (kg/kg)", "levelFields 'cloudLiquidWater' (--with-3d)"},
    {R::LevelCloudIce, "ciwc|QI", "isobaricInhPa|isobaricInPa", 0, "ECMWF, ICON", "cloud ice water content (kg/kg)",
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

std::string mappingName(long centre, const std::string& gridType)
{
    const bool regional = gridType != "regular_ll" && gridType.find("_gg") == std::string::npos;
    switch (centre)
    {
    case 7:
        return regional ? "NCEP HRRR/NAM/RAP (regional)" : "NCEP GFS";
    case 98:
        return "ECMWF IFS";
    case 78:
        return "DWD ICON";
    default:
        return "WMO names (centre " + std::to_string(centre) + ")";
    }
}

namespace
{

/// Turns grid-relative u/v pairs (same level, grid and time) to east/north.
void rotateGridRelativeWinds(std::vector<GribRecord>& records)
{
    for (GribRecord& u : records)
    {
        if (u.row.role != GribRole::LevelU || !u.info.uvRelativeToGrid || !u.grid)
            continue;
        for (GribRecord& v : records)
            if (v.row.role == GribRole::LevelV && v.info.uvRelativeToGrid && v.grid == u.grid &&
                v.levelPa == u.levelPa && v.info.validTimeUnixS == u.info.validTimeUnixS)
            {
                u.grid->rotateToEarth(u.field.values, v.field.values);
                u.source += " (grid-relative, turned to east)";
                v.source += " (grid-relative, turned to north)";
                break;
            }
    }
}

} // namespace

std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress)
{
    GribGridCache grids;
    return readGribRecords(file, maxCells, progress, grids);
}

std::vector<GribRecord> readGribRecords(GribFile& file, size_t maxCells, const ProgressFn& progress,
                                        GribGridCache& grids)
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
        r.field = message.decode(maxCells, grids, &r.grid);
        records.push_back(std::move(r));
    }
    rotateGridRelativeWinds(records);
    if (file.messagesRead() == 0)
        throw IngestError(IngestErrorKind::NotRecognized, file.path(), "", "", "no GRIB message found");
    return records;
}

}  // namespace sky
