// SPDX-License-Identifier: MIT
// The EGM96 geoid's height above the WGS 84 ellipsoid (the undulation N), read from the 15' grid Debian's
// proj-data package ships (/usr/share/proj/egm96_15.gtx), so that altitudes above mean sea level from a CIGI
// host become ellipsoid heights: h = H + N.
//
// GTX format (NOAA VDatum; what PROJ's vgridshift reads): a 40-byte big-endian header of the lower-left
// latitude and longitude, the latitude and longitude spacing (float64, degrees), the row and column counts
// (int32), then rows x cols big-endian float32 values in metres, row by row from the southernmost, each row
// west to east. egm96_15.gtx: -90, -180, 0.25, 0.25, 721 rows, 1440 columns (the last column is 179.75°:
// longitudes wrap). Values are interpolated bilinearly, as PROJ does.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sky::cigi
{

class GeoidGrid
{
public:
    /// Reads a GTX file; false + error (naming the file and what is wrong) leaves the grid empty.
    bool load(const std::string& path, std::string& error);
    /// Parses GTX bytes (the file's whole content); `name` is for messages.
    bool parse(const uint8_t* data, size_t size, const std::string& name, std::string& error);
    bool loaded() const { return !values_.empty(); }

    /// N (metres) at a geodetic latitude/longitude (degrees; latitude clamped to the grid, longitude
    /// wrapped when the grid spans 360°). NaN when nothing is loaded or the point lies off a partial grid.
    double undulationM(double latDeg, double lonDeg) const;
    /// Height above the ellipsoid (metres) of a point `altitudeMslM` above mean sea level.
    double ellipsoidHeightM(double latDeg, double lonDeg, double altitudeMslM) const
    {
        return altitudeMslM + undulationM(latDeg, lonDeg);
    }

    double lowerLeftLatDeg() const { return lat0Deg_; }
    double lowerLeftLonDeg() const { return lon0Deg_; }
    int rows() const { return rows_; }
    int cols() const { return cols_; }

private:
    float at(int row, int col) const { return values_[static_cast<size_t>(row) * static_cast<size_t>(cols_) +
                                                      static_cast<size_t>(col)]; }
    double lat0Deg_ = 0, lon0Deg_ = 0, dLatDeg_ = 0, dLonDeg_ = 0;
    int rows_ = 0, cols_ = 0;
    bool wrapsLon_ = false;
    std::vector<float> values_;
};

/// The path of Debian's EGM96 grid (proj-data).
const char* defaultEgm96GridPath();

} // namespace sky::cigi
