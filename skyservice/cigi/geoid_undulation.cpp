// SPDX-License-Identifier: MIT
#include "skyservice/cigi/geoid_undulation.h"

#include "skyservice/cigi/cigi_wire.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

namespace sky::cigi
{
namespace
{
constexpr size_t kHeaderBytes = 40;
// Some GTX grids mark missing cells with this value (NOAA VDatum); EGM96 has none, but a partial grid may.
constexpr float kNoData = -88.8888f;
} // namespace

const char* defaultEgm96GridPath()
{
#ifdef SKY_EGM96_GTX_PATH
    return SKY_EGM96_GTX_PATH;
#else
    return "/usr/share/proj/egm96_15.gtx";
#endif
}

bool GeoidGrid::load(const std::string& path, std::string& error)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
        error = path + ": cannot open the geoid grid (Debian package proj-data)";
        return false;
    }
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    return parse(bytes.data(), bytes.size(), path, error);
}

bool GeoidGrid::parse(const uint8_t* data, size_t size, const std::string& name, std::string& error)
{
    values_.clear();
    if (size < kHeaderBytes)
    {
        error = name + ": " + std::to_string(size) + " bytes is shorter than a GTX header (40)";
        return false;
    }
    const WireReader header(data, ByteOrder::Big);
    const double lat0 = header.f64(0), lon0 = header.f64(8), dLat = header.f64(16), dLon = header.f64(24);
    const int32_t rows = static_cast<int32_t>(header.u32(32)), cols = static_cast<int32_t>(header.u32(36));
    if (!(std::isfinite(lat0) && std::isfinite(lon0) && dLat > 0 && dLon > 0 && dLat <= 180 && dLon <= 360) ||
        rows < 2 || cols < 2 || rows > 100000 || cols > 100000)
    {
        error = name + ": GTX header is not a grid (origin " + std::to_string(lat0) + ", " + std::to_string(lon0) +
                ", spacing " + std::to_string(dLat) + " x " + std::to_string(dLon) + ", " + std::to_string(rows) +
                " x " + std::to_string(cols) + ")";
        return false;
    }
    const size_t count = static_cast<size_t>(rows) * static_cast<size_t>(cols);
    if (size != kHeaderBytes + 4 * count)
    {
        error = name + ": " + std::to_string(size) + " bytes, but a " + std::to_string(rows) + " x " +
                std::to_string(cols) + " GTX grid has " + std::to_string(kHeaderBytes + 4 * count);
        return false;
    }
    values_.resize(count);
    const WireReader body(data + kHeaderBytes, ByteOrder::Big);
    for (size_t i = 0; i < count; ++i)
        values_[i] = body.f32(4 * i);
    lat0Deg_ = lat0;
    lon0Deg_ = lon0;
    dLatDeg_ = dLat;
    dLonDeg_ = dLon;
    rows_ = rows;
    cols_ = cols;
    // A grid whose columns cover the whole circle wraps its last column onto its first.
    wrapsLon_ = std::abs(dLon * cols - 360.0) < 1e-6 * dLon;
    return true;
}

double GeoidGrid::undulationM(double latDeg, double lonDeg) const
{
    if (values_.empty() || !std::isfinite(latDeg) || !std::isfinite(lonDeg))
        return std::nan("");
    const double lastRow = rows_ - 1;
    const double y = std::clamp((latDeg - lat0Deg_) / dLatDeg_, 0.0, lastRow);
    double x = (lonDeg - lon0Deg_) / dLonDeg_;
    if (wrapsLon_)
        x = std::fmod(std::fmod(x, cols_) + cols_, cols_);
    else if (x < 0 || x > cols_ - 1)
        return std::nan("");
    const int row = std::min(static_cast<int>(y), rows_ - 2);
    const int col = std::min(static_cast<int>(x), wrapsLon_ ? cols_ - 1 : cols_ - 2);
    const int colEast = wrapsLon_ ? (col + 1) % cols_ : col + 1;
    const double fy = y - row, fx = x - col;
    const float f00 = at(row, col), f01 = at(row, colEast), f10 = at(row + 1, col), f11 = at(row + 1, colEast);
    if (f00 == kNoData || f01 == kNoData || f10 == kNoData || f11 == kNoData)
        return std::nan("");
    const double v00 = f00, v01 = f01, v10 = f10, v11 = f11;
    const double south = v00 + (v01 - v00) * fx, north = v10 + (v11 - v10) * fx;
    return south + (north - south) * fy;
}

} // namespace sky::cigi
