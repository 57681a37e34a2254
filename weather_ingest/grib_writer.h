// SPDX-License-Identifier: MIT
// Writing GRIB with ecCodes: used by the benchmark (a 0.25° GFS-like file) and by tests (fixtures made at
// test time, so no binary fixture is committed; cloud discs per grid type: grib_fixture.h). Not used by
// conversion.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <utility>
#include <vector>

namespace sky
{

/// One message to write.
struct GribOutField
{
    std::string sample = "regular_ll_sfc_grib2";  ///< ecCodes sample the message starts from
    /// Keys set in order before the grid, as text (ecCodes converts numbers), e.g.
    /// {"centre", "kwbc"}, {"typeOfLevel", "lowCloudLayer"}, {"shortName", "tcc"}.
    std::vector<std::pair<std::string, std::string>> keys;
    LatLonGrid grid;                 ///< written in canonical order unless scan flags below say otherwise;
                                     ///< an empty grid keeps the sample's grid and values
    bool iScansNegatively = false;   ///< write columns east to west
    bool jScansPositively = false;   ///< write rows south to north (grid.dLatDeg is then taken positive)
    std::vector<double> values;      ///< grid.cellCount() values in canonical order; NaN -> bitmap hole. With an
                                     ///< empty grid (one set through keys, e.g. gridType lambert): the
                                     ///< values in that grid's scanning order
    long bitsPerValue = 16;
    std::string packingType;         ///< e.g. "grid_ieee" (empty: the sample's)
    bool nanAsValue = false;         ///< write NaN as a value (IEEE packing), not as a bitmap hole (tests)
};

/// Writes all fields into one GRIB file (not atomic: for tests and the benchmark).
/// Throws IngestError(Output) naming the field and key when ecCodes refuses something.
void writeGribFile(const std::string& path, const std::vector<GribOutField>& fields);

}  // namespace sky
