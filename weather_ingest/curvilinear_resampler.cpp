// SPDX-License-Identifier: MIT
#include "weather_ingest/curvilinear_resampler.h"

#include "weather_ingest/regular_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sky
{
namespace
{

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// Quads with a corner beyond this latitude are solved in the gnomonic projection (see below).
constexpr double kGnomonicAboveDeg = 80.0;

using Vec3 = std::array<double, 3>;

Vec3 unitVector(double latDeg, double lonDeg)
{
    const double cl = std::cos(latDeg * kRadPerDeg);
    return {cl * std::cos(lonDeg * kRadPerDeg), cl * std::sin(lonDeg * kRadPerDeg), std::sin(latDeg * kRadPerDeg)};
}

double dot(const Vec3& a, const Vec3& b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec3 cross(const Vec3& a, const Vec3& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool normalise(Vec3& v)
{
    const double n = std::sqrt(dot(v, v));
    if (!(n > 1e-15))
        return false;
    v = {v[0] / n, v[1] / n, v[2] / n};
    return true;
}

/// Angle between two unit vectors (radians), from the chord (accurate for small angles).
double angleRad(const Vec3& a, const Vec3& b)
{
    const Vec3 d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(dot(d, d))));
}

struct Point
{
    double x;
    double y;
};

/// Inverse bilinear map of p in the quad (p00, p10, p01, p11): returns (a, b) with
/// p = (1-a)(1-b) p00 + a(1-b) p10 + (1-a) b p01 + a b p11, by Newton iteration from the centre.
bool inverseBilinear(const Point& p, const Point& p00, const Point& p10, const Point& p01, const Point& p11, double& a,
                     double& b, double eps)
{
    a = 0.5;
    b = 0.5;
    for (int it = 0; it < 12; ++it)
    {
        const double fx = (1 - a) * (1 - b) * p00.x + a * (1 - b) * p10.x + (1 - a) * b * p01.x + a * b * p11.x - p.x;
        const double fy = (1 - a) * (1 - b) * p00.y + a * (1 - b) * p10.y + (1 - a) * b * p01.y + a * b * p11.y - p.y;
        const double dxa = (1 - b) * (p10.x - p00.x) + b * (p11.x - p01.x);
        const double dya = (1 - b) * (p10.y - p00.y) + b * (p11.y - p01.y);
        const double dxb = (1 - a) * (p01.x - p00.x) + a * (p11.x - p10.x);
        const double dyb = (1 - a) * (p01.y - p00.y) + a * (p11.y - p10.y);
        const double det = dxa * dyb - dxb * dya;
        if (std::abs(det) < 1e-300)
            return false;
        const double da = (fx * dyb - fy * dxb) / det;
        const double db = (dxa * fy - dya * fx) / det;
        a -= da;
        b -= db;
        if (std::abs(da) + std::abs(db) < 1e-12)
            break;
    }
    return a >= -eps && a <= 1 + eps && b >= -eps && b <= 1 + eps;
}

/// The gnomonic projection centred on a quad: great circles become straight lines.
struct Gnomonic
{
    Vec3 centre{}, east{}, north{};

    bool setUp(const Vec3& c)
    {
        centre = c;
        east = cross(Vec3{0, 0, 1}, c);
        if (!normalise(east))
            east = {1, 0, 0}; // centred on a pole: any tangent direction will do
        north = cross(c, east);
        return true;
    }
    /// @return false for points 90° or more away from the centre.
    bool project(const Vec3& v, Point& p) const
    {
        const double d = dot(v, centre);
        if (!(d > 1e-6))
            return false;
        p = {dot(v, east) / d, dot(v, north) / d};
        return true;
    }
};

/// +1 when the closed boundary of the grid winds once round the north-south axis (it encloses a pole).
bool boundaryEnclosesPole(const std::vector<double>& lon, size_t ny, size_t nx)
{
    std::vector<size_t> ring;
    for (size_t i = 0; i < nx; ++i)
        ring.push_back(i);
    for (size_t j = 1; j < ny; ++j)
        ring.push_back(j * nx + nx - 1);
    for (size_t i = nx - 1; i-- > 0;)
        ring.push_back((ny - 1) * nx + i);
    for (size_t j = ny - 1; j-- > 1;)
        ring.push_back(j * nx);
    double turn = 0;
    for (size_t k = 0; k < ring.size(); ++k)
        turn += wrapLongitudeDeg(lon[ring[(k + 1) % ring.size()]] - lon[ring[k]]);
    return std::abs(turn) > 180.0;
}

/// The source points in degrees and as unit vectors, checked.
struct SourcePoints
{
    std::vector<double> lat, lon;
    std::vector<Vec3> unit;
    double latSum = 0;
};

SourcePoints readSourcePoints(const std::vector<float>& latDeg, const std::vector<float>& lonDeg, size_t n)
{
    SourcePoints s;
    s.lat.resize(n);
    s.lon.resize(n);
    s.unit.resize(n);
    for (size_t k = 0; k < n; ++k)
    {
        if (!std::isfinite(latDeg[k]) || !std::isfinite(lonDeg[k]) || std::abs(latDeg[k]) > 90.0f)
            throw std::invalid_argument("2D coordinates contain a missing or invalid latitude/longitude");
        s.lat[k] = latDeg[k];
        s.lon[k] = lonDeg[k];
        s.unit[k] = unitVector(s.lat[k], s.lon[k]);
        s.latSum += s.lat[k];
    }
    return s;
}

/// Mean spacing (degrees of great circle) between neighbours along rows and columns.
double meanNeighbourStepDeg(const std::vector<Vec3>& v, size_t ny, size_t nx)
{
    double stepSum = 0;
    size_t steps = 0;
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i)
        {
            if (i + 1 < nx)
                stepSum += angleRad(v[j * nx + i], v[j * nx + i + 1]), ++steps;
            if (j + 1 < ny)
                stepSum += angleRad(v[j * nx + i], v[(j + 1) * nx + i]), ++steps;
        }
    const double stepDeg = stepSum / double(steps) / kRadPerDeg;
    if (!(stepDeg > 1e-6))
        throw std::invalid_argument("2D coordinates do not span an area");
    return stepDeg;
}

/// Columns that close on themselves: the middle row's last point is about one step from its first.
bool columnsCloseOnThemselves(const std::vector<Vec3>& v, size_t ny, size_t nx)
{
    const size_t jm = ny / 2;
    double rowStep = 0;
    for (size_t i = 0; i + 1 < nx; ++i)
        rowStep += angleRad(v[jm * nx + i], v[jm * nx + i + 1]);
    rowStep /= double(nx - 1);
    return nx >= 3 && angleRad(v[jm * nx], v[jm * nx + nx - 1]) < 1.5 * rowStep;
}

/// The regular target grid at the source's mean spacing, covering its latitudes and longitudes (all of them
/// round the globe for periodic columns or a boundary round a pole). lon0Deg is not yet wrapped.
LatLonGrid chooseTargetGrid(const SourcePoints& s, size_t ny, size_t nx, double stepDeg, bool periodic, bool pole,
                            size_t maxCells)
{
    const bool global = periodic || pole;
    double latMin = *std::min_element(s.lat.begin(), s.lat.end());
    double latMax = *std::max_element(s.lat.begin(), s.lat.end());
    const double meanLat = s.latSum / double(s.lat.size());
    if (pole)
        (meanLat > 0 ? latMax : latMin) = meanLat > 0 ? 90.0 : -90.0;
    const double cosLat0 = std::max(std::cos(meanLat * kRadPerDeg), 0.01);
    LatLonGrid grid;
    grid.lat0Deg = latMin;
    grid.dLatDeg = stepDeg;
    double nLon = 0;
    if (periodic)
    {
        nLon = double(nx);
        grid.lon0Deg = s.lon[0];
    }
    else if (pole)
    {
        nLon = std::ceil(360.0 / (stepDeg / cosLat0));
        grid.lon0Deg = -180.0;
    }
    else
    {
        const size_t jm = ny / 2;
        const double lonRef = s.lon[jm * nx + nx / 2];
        double lonMin = 1e9, lonMax = -1e9;
        for (const double l : s.lon)
        {
            const double u = lonRef + wrapLongitudeDeg(l - lonRef);
            lonMin = std::min(lonMin, u);
            lonMax = std::max(lonMax, u);
        }
        grid.lon0Deg = lonMin;
        grid.dLonDeg = stepDeg / cosLat0;
        nLon = std::floor((lonMax - lonMin) / grid.dLonDeg + 1e-9) + 1;
    }
    if (global)
        grid.dLonDeg = 360.0 / nLon;
    const double nLat = std::floor((latMax - latMin) / grid.dLatDeg + 1e-9) + 1;
    if (nLat * nLon > double(maxCells))
        throw std::length_error("resampled grid too large");
    grid.nLat = static_cast<uint32_t>(nLat);
    grid.nLon = static_cast<uint32_t>(nLon);
    return grid;
}

/// Sines and cosines of the target grid's row latitudes and column longitudes.
struct TargetTrig
{
    std::vector<double> sinLat, cosLat, sinLon, cosLon;

    explicit TargetTrig(const LatLonGrid& grid)
        : sinLat(grid.nLat), cosLat(grid.nLat), sinLon(grid.nLon), cosLon(grid.nLon)
    {
        for (uint32_t r = 0; r < grid.nLat; ++r)
        {
            const double phi = (grid.lat0Deg + double(r) * grid.dLatDeg) * kRadPerDeg;
            sinLat[r] = std::sin(phi);
            cosLat[r] = std::cos(phi);
        }
        for (uint32_t c = 0; c < grid.nLon; ++c)
        {
            const double lambda = (grid.lon0Deg + double(c) * grid.dLonDeg) * kRadPerDeg;
            sinLon[c] = std::sin(lambda);
            cosLon[c] = std::cos(lambda);
        }
    }

    Vec3 unit(size_t row, size_t col) const
    {
        return {cosLat[row] * cosLon[col], cosLat[row] * sinLon[col], sinLat[row]};
    }
};

/// What every quad's search needs to know of the source and target grids.
struct QuadSearch
{
    const SourcePoints& source;
    const LatLonGrid& grid;
    size_t nx;
    bool pole;           ///< the source boundary winds round a pole
    bool global;         ///< the target grid wraps round in longitude
    double meanLat;      ///< mean source latitude (degrees): its sign says which pole
    double targetSpanDeg;  ///< longitude from the target's first column to its last
};

/// One source quad, projected onto a plane, and the target rows and columns it may cover.
struct QuadFootprint
{
    std::array<size_t, 4> k{};  ///< corner indices: (i, j), (i+1, j), (i, j+1), (i+1, j+1)
    bool gnomonic = false;
    Gnomonic g;
    double lon00 = 0, cosC = 0, latC = 0;
    std::array<Point, 4> corners{};
    long r0 = 0, r1 = 0, c0 = 0, c1 = 0;
    double tolerance = 0;

    // Away from the poles a quad is taken with straight edges in longitude and latitude (scaled by
    // cos(latitude)), so rows of a lat/lon-aligned grid (Mercator, Gaussian) keep their exact latitude; near
    // a pole, and round it, in the gnomonic projection (only set up there: most quads of most grids never
    // need it).
    bool project(const Vec3& unit, double pointLat, double pointLon, Point& out) const
    {
        if (gnomonic)
            return g.project(unit, out);
        out = {wrapLongitudeDeg(pointLon - lon00) * cosC, pointLat - latC};
        return true;
    }
};

struct QuadBounds
{
    double latLo = 90, latHi = -90, lonLo = 0, lonHi = 0;  ///< longitudes relative to corner 0
};

QuadBounds quadBounds(const SourcePoints& s, const std::array<size_t, 4>& k)
{
    QuadBounds b;
    for (size_t q = 0; q < 4; ++q)
    {
        b.latLo = std::min(b.latLo, s.lat[k[q]]);
        b.latHi = std::max(b.latHi, s.lat[k[q]]);
        const double rel = wrapLongitudeDeg(s.lon[k[q]] - s.lon[k[0]]);
        b.lonLo = std::min(b.lonLo, rel);
        b.lonHi = std::max(b.lonHi, rel);
    }
    return b;
}

/// True when the pole lies inside the quad, seen in its gnomonic projection g.
bool quadHoldsPole(const Gnomonic& g, const std::vector<Vec3>& unit, const std::array<size_t, 4>& k, double meanLat)
{
    std::array<Point, 4> gp{};
    Point pp{};
    double a = 0, b = 0;
    const Vec3 poleVector{0, 0, meanLat > 0 ? 1.0 : -1.0};
    bool ok = g.project(poleVector, pp);
    for (size_t q = 0; q < 4; ++q)
        ok = ok && g.project(unit[k[q]], gp[q]);
    return ok && inverseBilinear(pp, gp[0], gp[1], gp[2], gp[3], a, b, 0.0);
}

/// The target columns c0..c1 (not yet wrapped when global) that the quad's longitudes span.
void quadColumns(const QuadSearch& t, const QuadBounds& b, QuadFootprint& f)
{
    const LatLonGrid& grid = t.grid;
    double off = std::fmod(t.source.lon[f.k[0]] + b.lonLo - grid.lon0Deg, 360.0);
    if (off < 0)
        off += 360.0;
    if (!t.global && off > t.targetSpanDeg + 0.5 * (360.0 - t.targetSpanDeg))
        off -= 360.0; // the quad starts west of the target's first column
    f.c0 = static_cast<long>(std::ceil(off / grid.dLonDeg - 1e-9));
    f.c1 = static_cast<long>(std::floor((off + b.lonHi - b.lonLo) / grid.dLonDeg + 1e-9));
    if (!t.global)
    {
        f.c0 = std::max(f.c0, 0L);
        f.c1 = std::min(f.c1, long(grid.nLon) - 1);
    }
}

/// Projects the quad whose first corner is (i, j) and finds the target rows and columns it may cover.
/// @return false for a degenerate quad or one that cannot be projected.
bool locateQuad(const QuadSearch& t, size_t j, size_t i, QuadFootprint& f)
{
    const SourcePoints& s = t.source;
    const size_t nx = t.nx;
    const size_t i1 = (i + 1) % nx;
    f.k = {j * nx + i, j * nx + i1, (j + 1) * nx + i, (j + 1) * nx + i1};
    Vec3 c{0, 0, 0};
    for (const size_t q : f.k)
        for (int d = 0; d < 3; ++d)
            c[size_t(d)] += s.unit[q][size_t(d)];
    if (!normalise(c))
        return false;
    QuadBounds b = quadBounds(s, f.k);
    const double poleLat = std::max(std::abs(b.latLo), std::abs(b.latHi));
    f.gnomonic = poleLat > kGnomonicAboveDeg;
    const bool nearEnclosedPole = t.pole && poleLat > 45.0;
    double edgeRad = 0;
    if (f.gnomonic || nearEnclosedPole)
    {
        f.g.setUp(c);
        for (size_t q = 0; q < 4; ++q)
            edgeRad = std::max(edgeRad, angleRad(s.unit[f.k[q]], s.unit[f.k[(q + 1) % 4]]));
    }
    f.cosC = std::cos(0.5 * (b.latLo + b.latHi) * kRadPerDeg);
    f.lon00 = s.lon[f.k[0]];
    f.latC = 0.5 * (b.latLo + b.latHi);
    bool allColumns = false;
    if (nearEnclosedPole && quadHoldsPole(f.g, s.unit, f.k, t.meanLat))
    {
        f.gnomonic = allColumns = true;
        (t.meanLat > 0 ? b.latHi : b.latLo) = t.meanLat > 0 ? 90.0 : -90.0;
    }
    bool ok = true;
    for (size_t q = 0; q < 4; ++q)
        ok = ok && f.project(s.unit[f.k[q]], s.lat[f.k[q]], s.lon[f.k[q]], f.corners[q]);
    if (!ok)
        return false;
    // Great-circle edges bulge polewards of their end points by up to about L^2/8 tan(lat).
    const double bulgeDeg =
        f.gnomonic ? edgeRad * edgeRad * (1.0 + std::tan(std::min(poleLat, 89.0) * kRadPerDeg)) / kRadPerDeg : 0.0;
    f.r0 = static_cast<long>(std::ceil((b.latLo - bulgeDeg - t.grid.lat0Deg) / t.grid.dLatDeg - 1e-9));
    f.r1 = static_cast<long>(std::floor((b.latHi + bulgeDeg - t.grid.lat0Deg) / t.grid.dLatDeg + 1e-9));
    f.c0 = 0;
    f.c1 = long(t.grid.nLon) - 1;
    if (!allColumns)
        quadColumns(t, b, f);
    // Where the two kinds of quads meet their edges differ slightly: a small tolerance closes the gap.
    f.tolerance = poleLat > kGnomonicAboveDeg - 1.0 ? 1e-3 : 1e-9;
    return true;
}

} // namespace

CurvilinearResampler::CurvilinearResampler(const std::vector<float>& latDeg, const std::vector<float>& lonDeg,
                                           size_t ny, size_t nx, size_t maxCells)
    : nx_(nx), ny_(ny)
{
    if (ny < 2 || nx < 2 || latDeg.size() != ny * nx || lonDeg.size() != ny * nx)
        throw std::invalid_argument("2D coordinates need at least 2 x 2 points and ny * nx values");
    const size_t n = ny * nx;
    if (n >= kWrapsRound)
        throw std::length_error("more than 2^31 source points");
    const SourcePoints source = readSourcePoints(latDeg, lonDeg, n);
    const double stepDeg = meanNeighbourStepDeg(source.unit, ny, nx);
    periodic_ = columnsCloseOnThemselves(source.unit, ny, nx);
    const bool pole = !periodic_ && boundaryEnclosesPole(source.lon, ny, nx);
    global_ = periodic_ || pole;
    grid_ = chooseTargetGrid(source, ny, nx, stepDeg, periodic_, pole, maxCells);
    cells_.assign(grid_.cellCount(), QuadPosition{});

    const TargetTrig trig(grid_);
    const QuadSearch search{source, grid_, nx, pole, global_, source.latSum / double(n),
                            double(grid_.nLon - 1) * grid_.dLonDeg};
    const size_t quadColumnCount = periodic_ ? nx : nx - 1;
    for (size_t j = 0; j + 1 < ny; ++j)
        for (size_t i = 0; i < quadColumnCount; ++i)
        {
            QuadFootprint f;
            if (!locateQuad(search, j, i, f))
                continue;
            const std::array<Point, 4>& p = f.corners;
            for (long r = std::max(f.r0, 0L); r <= std::min(f.r1, long(grid_.nLat) - 1); ++r)
                for (long cc = f.c0; cc <= f.c1; ++cc)
                {
                    const auto col = size_t(((cc % long(grid_.nLon)) + long(grid_.nLon)) % long(grid_.nLon));
                    QuadPosition& cell = cells_[size_t(r) * grid_.nLon + col];
                    if (cell.quad != kOutside)
                        continue; // already inside a neighbouring quad (shared edge)
                    Point tp{};
                    double a = 0, b = 0;
                    if (!f.project(trig.unit(size_t(r), col), grid_.lat0Deg + double(r) * grid_.dLatDeg,
                                   grid_.lon0Deg + double(col) * grid_.dLonDeg, tp) ||
                        !inverseBilinear(tp, p[0], p[1], p[2], p[3], a, b, f.tolerance))
                        continue;
                    cell.quad = uint32_t(j * nx + i) | (i + 1 < nx ? 0u : kWrapsRound);
                    cell.a = uint16_t(std::lround(std::clamp(a, 0.0, 1.0) * double(kFractionUnit)));
                    cell.b = uint16_t(std::lround(std::clamp(b, 0.0, 1.0) * double(kFractionUnit)));
                }
        }
    grid_.lon0Deg = wrapLongitudeDeg(grid_.lon0Deg);
}

template <typename T> std::vector<float> CurvilinearResampler::resampleValues(const T* source) const
{
    std::vector<float> out(cells_.size(), NAN);
    const size_t nx = nx_;
    for (size_t t = 0; t < cells_.size(); ++t)
    {
        const QuadPosition& cell = cells_[t];
        if (cell.quad == kOutside)
            continue;
        const float a = float(cell.a) / kFractionUnit, b = float(cell.b) / kFractionUnit;
        const size_t k00 = cell.quad & ~kWrapsRound;
        const size_t k01 = (cell.quad & kWrapsRound) != 0 ? k00 + 1 - nx : k00 + 1;
        const std::array<float, 4> x{float(source[k00]), float(source[k01]), float(source[k00 + nx]),
                                     float(source[k01 + nx])};
        const std::array<float, 4> w{(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
        const float all = w[0] * x[0] + w[1] * x[1] + w[2] * x[2] + w[3] * x[3];
        if (std::isfinite(all)) // the usual case: four known corners (divided: a constant field stays exact)
        {
            out[t] = all / (w[0] + w[1] + w[2] + w[3]);
            continue;
        }
        float sum = 0, wsum = 0;
        for (size_t q = 0; q < 4; ++q)
        {
            const bool known = std::isfinite(x[q]);
            sum += known ? w[q] * x[q] : 0.0f;
            wsum += known ? w[q] : 0.0f;
        }
        if (wsum > 0)
            out[t] = sum / wsum;
    }
    return out;
}

std::vector<float> CurvilinearResampler::resample(const std::vector<float>& source) const
{
    return resampleValues(source.data());
}

std::vector<float> CurvilinearResampler::resample(const std::vector<double>& source) const
{
    return resampleValues(source.data());
}

double CurvilinearResampler::coveredFraction() const
{
    size_t inside = 0;
    for (const QuadPosition& c : cells_)
        inside += c.quad != kOutside ? 1u : 0u;
    return cells_.empty() ? 0.0 : double(inside) / double(cells_.size());
}

} // namespace sky
