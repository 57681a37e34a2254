// SPDX-License-Identifier: MIT
#include "weather_ingest/curvilinear_resampler.h"

#include "weather_ingest/regular_grid.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sky
{
namespace
{

struct Point
{
    double x;  // longitude * cos(lat0), degrees
    double y;  // latitude, degrees
};

/// Inverse bilinear map of p in the quad (p00, p10, p01, p11): returns (a, b) with
/// p = (1-a)(1-b) p00 + a(1-b) p10 + (1-a) b p01 + a b p11, by Newton iteration from the centre.
bool inverseBilinear(const Point& p, const Point& p00, const Point& p10, const Point& p01, const Point& p11, double& a,
                     double& b)
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
    const double eps = 1e-9;
    return a >= -eps && a <= 1 + eps && b >= -eps && b <= 1 + eps;
}

}  // namespace

CurvilinearResampler::CurvilinearResampler(const std::vector<float>& latDeg, const std::vector<float>& lonDeg,
                                           size_t ny, size_t nx, size_t maxCells)
{
    if (ny < 2 || nx < 2 || latDeg.size() != ny * nx || lonDeg.size() != ny * nx)
        throw std::invalid_argument("2D coordinates need at least 2 x 2 points and ny * nx values");
    const double lonRef = lonDeg[0];
    std::vector<double> lon(ny * nx);
    double latMin = 90, latMax = -90, lonMin = 1e9, lonMax = -1e9, latSum = 0;
    for (size_t i = 0; i < lon.size(); ++i)
    {
        if (!std::isfinite(latDeg[i]) || !std::isfinite(lonDeg[i]) || std::abs(latDeg[i]) > 90.0f)
            throw std::invalid_argument("2D coordinates contain a missing or invalid latitude/longitude");
        lon[i] = lonRef + wrapLongitudeDeg(double(lonDeg[i]) - lonRef);
        latMin = std::min(latMin, double(latDeg[i]));
        latMax = std::max(latMax, double(latDeg[i]));
        lonMin = std::min(lonMin, lon[i]);
        lonMax = std::max(lonMax, lon[i]);
        latSum += double(latDeg[i]);
    }
    const double lat0 = latSum / double(lon.size());
    const double cosLat0 = std::max(std::cos(lat0 * std::numbers::pi / 180.0), 0.01);
    const auto point = [&](size_t j, size_t i) { return Point{lon[j * nx + i] * cosLat0, double(latDeg[j * nx + i])}; };

    double stepSum = 0;
    size_t steps = 0;
    for (size_t j = 0; j + 1 < ny; ++j)
        for (size_t i = 0; i + 1 < nx; ++i)
        {
            const Point p = point(j, i), px = point(j, i + 1), py = point(j + 1, i);
            stepSum += std::hypot(px.x - p.x, px.y - p.y) + std::hypot(py.x - p.x, py.y - p.y);
            steps += 2;
        }
    const double stepDeg = stepSum / double(steps);
    if (!(stepDeg > 1e-6))
        throw std::invalid_argument("2D coordinates do not span an area");
    grid_.lat0Deg = latMin;
    grid_.dLatDeg = stepDeg;
    grid_.lon0Deg = lonMin;
    grid_.dLonDeg = stepDeg / cosLat0;
    const double nLat = std::floor((latMax - latMin) / grid_.dLatDeg) + 1;
    const double nLon = std::floor((lonMax - lonMin) / grid_.dLonDeg) + 1;
    if (nLat * nLon > double(maxCells))
        throw std::length_error("resampled grid too large");
    grid_.nLat = static_cast<uint32_t>(nLat);
    grid_.nLon = static_cast<uint32_t>(nLon);
    weights_.assign(grid_.cellCount(), Weights{});

    for (size_t j = 0; j + 1 < ny; ++j)
        for (size_t i = 0; i + 1 < nx; ++i)
        {
            const Point p00 = point(j, i), p10 = point(j, i + 1), p01 = point(j + 1, i), p11 = point(j + 1, i + 1);
            const double yMin = std::min({p00.y, p10.y, p01.y, p11.y}), yMax = std::max({p00.y, p10.y, p01.y, p11.y});
            const double xMin = std::min({p00.x, p10.x, p01.x, p11.x}) / cosLat0;
            const double xMax = std::max({p00.x, p10.x, p01.x, p11.x}) / cosLat0;
            const auto r0 = static_cast<long>(std::ceil((yMin - grid_.lat0Deg) / grid_.dLatDeg - 1e-9));
            const auto r1 = static_cast<long>(std::floor((yMax - grid_.lat0Deg) / grid_.dLatDeg + 1e-9));
            const auto c0 = static_cast<long>(std::ceil((xMin - grid_.lon0Deg) / grid_.dLonDeg - 1e-9));
            const auto c1 = static_cast<long>(std::floor((xMax - grid_.lon0Deg) / grid_.dLonDeg + 1e-9));
            for (long r = std::max(r0, 0L); r <= std::min(r1, long(grid_.nLat) - 1); ++r)
                for (long c = std::max(c0, 0L); c <= std::min(c1, long(grid_.nLon) - 1); ++c)
                {
                    Weights& w = weights_[size_t(r) * grid_.nLon + size_t(c)];
                    if (w.weight[0] + w.weight[1] + w.weight[2] + w.weight[3] > 0)
                        continue;  // already inside a neighbouring quad (shared edge)
                    const Point p{(grid_.lon0Deg + double(c) * grid_.dLonDeg) * cosLat0,
                                  grid_.lat0Deg + double(r) * grid_.dLatDeg};
                    double a = 0, b = 0;
                    if (!inverseBilinear(p, p00, p10, p01, p11, a, b))
                        continue;
                    a = std::clamp(a, 0.0, 1.0);
                    b = std::clamp(b, 0.0, 1.0);
                    w.index = {uint32_t(j * nx + i), uint32_t(j * nx + i + 1), uint32_t((j + 1) * nx + i),
                               uint32_t((j + 1) * nx + i + 1)};
                    w.weight = {float((1 - a) * (1 - b)), float(a * (1 - b)), float((1 - a) * b), float(a * b)};
                    if (w.weight[0] + w.weight[1] + w.weight[2] + w.weight[3] <= 0)
                        w.weight[0] = 1e-30f;  // degenerate but inside: keep it marked
                }
        }
    grid_.lon0Deg = wrapLongitudeDeg(grid_.lon0Deg);
}

std::vector<float> CurvilinearResampler::resample(const std::vector<float>& source) const
{
    std::vector<float> out(weights_.size(), NAN);
    for (size_t t = 0; t < weights_.size(); ++t)
    {
        const Weights& w = weights_[t];
        float sum = 0, wsum = 0;
        for (size_t k = 0; k < 4; ++k)
        {
            const float v = source[w.index[k]];
            if (w.weight[k] > 0 && std::isfinite(v))
            {
                sum += w.weight[k] * v;
                wsum += w.weight[k];
            }
        }
        if (wsum > 0)
            out[t] = sum / wsum;
    }
    return out;
}

double CurvilinearResampler::coveredFraction() const
{
    size_t inside = 0;
    for (const Weights& w : weights_)
        inside += (w.weight[0] + w.weight[1] + w.weight[2] + w.weight[3] > 0) ? 1u : 0u;
    return weights_.empty() ? 0.0 : double(inside) / double(weights_.size());
}

}  // namespace sky
