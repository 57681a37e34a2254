// SPDX-License-Identifier: MIT
#include "skyservice/earth/weather_window.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

namespace sky
{

namespace
{

// Where one point falls on the lat/lon grid: four bilinear corners and the nearest cell.
struct GridSample
{
    bool inside = false;   // within the grid's footprint (always true for global grids)
    size_t corner[4] = {};
    double weight[4] = {};
    size_t nearest = 0;
};

class GridSampler
{
public:
    explicit GridSampler(const LatLonGrid& grid) : grid_(grid)
    {
        const double spanDeg = double(grid.nLon) * grid.dLonDeg;
        // Grids whose longitudes are given as decimal strings (0.1 deg) do not add up to 360 exactly.
        global_ = std::abs(spanDeg - 360.0) < 1e-4;
    }

    GridSample sample(double latDeg, double lonDeg) const
    {
        GridSample s;
        bool inside = true;

        double fy = (latDeg - grid_.lat0Deg) / grid_.dLatDeg;
        const double lastRow = double(grid_.nLat) - 1.0;
        if (fy < -0.5 || fy > lastRow + 0.5)
            inside = global_;  // global grids clamp at the poles
        fy = std::clamp(fy, 0.0, lastRow);

        double dl = std::fmod(lonDeg - grid_.lon0Deg, 360.0);
        if (dl < 0.0)
            dl += 360.0;
        double fx = dl / grid_.dLonDeg;
        const double lastColumn = double(grid_.nLon) - 1.0;
        uint32_t ix0 = 0;
        uint32_t ix1 = 0;
        double tx = 0;
        if (global_)
        {
            const double cell = std::floor(fx);
            tx = fx - cell;
            ix0 = uint32_t(cell) % grid_.nLon;
            ix1 = (ix0 + 1) % grid_.nLon;
        }
        else
        {
            if (fx > lastColumn + 0.5)
            {
                // Beyond the east edge, or just west of column 0: pick the nearer edge.
                const double beyondEast = fx - lastColumn;
                const double beforeWest = 360.0 / grid_.dLonDeg - fx;
                fx = beyondEast <= beforeWest ? fx : -beforeWest;
                if (fx < -0.5 || fx > lastColumn + 0.5)
                    inside = false;
            }
            fx = std::clamp(fx, 0.0, lastColumn);
            const double cell = std::min(std::floor(fx), std::max(lastColumn - 1.0, 0.0));
            tx = fx - cell;
            ix0 = uint32_t(cell);
            ix1 = std::min(ix0 + 1, grid_.nLon - 1);
        }
        const double rowCell = std::min(std::floor(fy), std::max(lastRow - 1.0, 0.0));
        const double ty = fy - rowCell;
        const uint32_t iy0 = uint32_t(rowCell);
        const uint32_t iy1 = std::min(iy0 + 1, grid_.nLat - 1);

        s.inside = inside;
        s.corner[0] = grid_.index(iy0, ix0);
        s.corner[1] = grid_.index(iy0, ix1);
        s.corner[2] = grid_.index(iy1, ix0);
        s.corner[3] = grid_.index(iy1, ix1);
        s.weight[0] = (1.0 - ty) * (1.0 - tx);
        s.weight[1] = (1.0 - ty) * tx;
        s.weight[2] = ty * (1.0 - tx);
        s.weight[3] = ty * tx;
        s.nearest = s.corner[(ty >= 0.5 ? 2 : 0) + (tx >= 0.5 ? 1 : 0)];
        return s;
    }

    size_t cellCount() const { return grid_.cellCount(); }

private:
    const LatLonGrid& grid_;
    bool global_ = false;
};

// Bilinear value of a field, leaving NaN corners out (see the header for the rules).
float interpolate(const std::vector<float>& field, const GridSample& s, size_t cellCount, float fallback)
{
    if (cellCount == 0 || field.size() != cellCount)  // an empty grid (no weather given) has no values
        return fallback;
    double sum = 0;
    double weightSum = 0;
    int heaviest = -1;
    for (int k = 0; k < 4; ++k)
    {
        const float v = field[s.corner[k]];
        if (std::isnan(v))
            continue;
        sum += s.weight[k] * double(v);
        weightSum += s.weight[k];
        if (heaviest < 0 || s.weight[k] > s.weight[heaviest])
            heaviest = k;
    }
    if (weightSum > 0.0)
        return float(sum / weightSum);
    if (heaviest >= 0)
        return field[s.corner[heaviest]];  // only zero-weight corners are valid
    return fallback;
}

// Bilinear coverage where a corner with an unknown coverage, base or top counts as clear.
float interpolateCoverage(const std::vector<float>& coverage, const std::vector<float>& base,
                          const std::vector<float>& top, const GridSample& s, size_t cellCount)
{
    if (!s.inside || coverage.size() != cellCount || base.size() != cellCount || top.size() != cellCount)
        return 0.0f;
    double sum = 0;
    for (int k = 0; k < 4; ++k)
    {
        const size_t c = s.corner[k];
        if (std::isnan(coverage[c]) || std::isnan(base[c]) || std::isnan(top[c]))
            continue;
        sum += s.weight[k] * std::clamp(double(coverage[c]), 0.0, 1.0);
    }
    return float(std::clamp(sum, 0.0, 1.0));
}

float nearestType(const std::vector<uint8_t>& type, const GridSample& s, size_t cellCount)
{
    if (cellCount == 0 || type.size() != cellCount)
        return float(CLOUD_TYPE_NONE);
    const uint8_t t = type[s.nearest];
    return t <= CLOUD_TYPE_STRATUS ? float(t) : float(CLOUD_TYPE_NONE);
}

}  // namespace

namespace
{

// Everything one worker needs to fill rows of the window.
struct ResampleJob
{
    const WeatherSnapshot* snapshot;
    const GridSampler* sampler;
    WeatherWindow* out;
    double centreLatDeg;
    double centreLonDeg;
};

void resampleRows(const ResampleJob& job, uint32_t firstRow, uint32_t endRow)
{
    const WeatherSnapshot& snapshot = *job.snapshot;
    const GridSampler& sampler = *job.sampler;
    WeatherWindow& out = *job.out;
    const size_t cells = sampler.cellCount();
    const GeographicLib::AzimuthalEquidistant projection;  // WGS84 geodesics
    const size_t layerCount = std::min(snapshot.layers.size(), size_t(MAX_CLOUD_LAYERS));
    const HighCloudFields& high = snapshot.high;
    const uint32_t sizeTexels = out.sizeTexels;

    for (uint32_t j = firstRow; j < endRow; ++j)
    {
        for (uint32_t i = 0; i < sizeTexels; ++i)
        {
            double latDeg = 0;
            double lonDeg = 0;
            double azimuthDeg = 0;
            double scale = 0;
            const glm::dvec2 position = out.texelPositionM(i, j);
            projection.Reverse(job.centreLatDeg, job.centreLonDeg, position.x, position.y, latDeg, lonDeg,
                               azimuthDeg, scale);
            const GridSample s = sampler.sample(latDeg, lonDeg);
            const float capeJKg = interpolate(snapshot.capeJKg, s, cells, 0.0f);
            // Outside a regional model's domain there is no data: clear sky, faded in over its soft edge.
            const float dataWeight = std::clamp(interpolate(snapshot.dataWeight, s, cells, 1.0f), 0.0f, 1.0f);

            for (size_t k = 0; k < layerCount; ++k)
            {
                const CloudLayerFields& layer = snapshot.layers[k];
                glm::vec4& shape = out.texels[out.index(uint32_t(2 * k), i, j)];
                shape.x =
                    dataWeight * interpolateCoverage(layer.coverage, layer.baseAltitudeM, layer.topAltitudeM, s, cells);
                shape.y = interpolate(layer.baseAltitudeM, s, cells, 0.0f);
                shape.z = interpolate(layer.topAltitudeM, s, cells, 0.0f);
                shape.w = nearestType(layer.type, s, cells);
                glm::vec4& dynamics = out.texels[out.index(uint32_t(2 * k + 1), i, j)];
                dynamics.x = interpolate(layer.windEastMS, s, cells, 0.0f);
                dynamics.y = interpolate(layer.windNorthMS, s, cells, 0.0f);
                dynamics.z = interpolate(layer.precipitationMmH, s, cells, 0.0f);
                dynamics.w = capeJKg;
            }
            for (size_t k = layerCount; k < size_t(MAX_CLOUD_LAYERS); ++k)
                out.texels[out.index(uint32_t(2 * k + 1), i, j)].w = capeJKg;

            glm::vec4& highShape = out.texels[out.index(WEATHER_WINDOW_HIGH_SLICE, i, j)];
            highShape.x = dataWeight * interpolateCoverage(high.coverage, high.altitudeM, high.altitudeM, s, cells);
            highShape.y = interpolate(high.altitudeM, s, cells, 0.0f);
            highShape.z = nearestType(high.type, s, cells);
            glm::vec4& highDynamics = out.texels[out.index(WEATHER_WINDOW_HIGH_SLICE + 1, i, j)];
            highDynamics.x = interpolate(high.windEastMS, s, cells, 0.0f);
            highDynamics.y = interpolate(high.windNorthMS, s, cells, 0.0f);
            highDynamics.z = interpolate(snapshot.tropopauseAltitudeM, s, cells, kDefaultTropopauseAltitudeM);
        }
    }
}

// Rows per worker below which threads cost more than they save (a row is 256 geodesic problems).
constexpr uint32_t kMinRowsPerWorker = 16;
// More workers than this fight the renderer's own threads for little gain.
constexpr uint32_t kMaxWorkers = 8;

}  // namespace

void resampleWeatherWindow(const WeatherSnapshot& snapshot, double centreLatDeg, double centreLonDeg,
                           double halfExtentM, WeatherWindow& out, uint32_t sizeTexels, double warpRadiusM)
{
    assert(snapshot.grid.nLat >= 1 && snapshot.grid.nLon >= 1 && snapshot.grid.dLonDeg > 0.0);
    assert(halfExtentM > 0.0 && sizeTexels >= 1);

    out.centreLatDeg = centreLatDeg;
    out.centreLonDeg = centreLonDeg;
    out.sizeTexels = sizeTexels;
    out.texelSizeM = 2.0 * halfExtentM / double(sizeTexels);
    out.halfExtentM = halfExtentM;
    out.warpRadiusM = warpRadiusM;
    out.texels.assign(size_t(WEATHER_WINDOW_SLICES) * sizeTexels * sizeTexels, glm::vec4(0.0f));

    const GridSampler sampler(snapshot.grid);
    const ResampleJob job{&snapshot, &sampler, &out, centreLatDeg, centreLonDeg};
    // Every texel is computed independently, so the result does not depend on the number of workers.
    const uint32_t hardware = std::max(1u, std::thread::hardware_concurrency());
    const uint32_t workers = std::clamp(sizeTexels / kMinRowsPerWorker, 1u, std::min(hardware, kMaxWorkers));
    if (workers == 1)
    {
        resampleRows(job, 0, sizeTexels);
        return;
    }
    std::vector<std::thread> threads;
    threads.reserve(workers - 1);
    const uint32_t rowsPerWorker = (sizeTexels + workers - 1) / workers;
    for (uint32_t w = 1; w < workers; ++w)
    {
        const uint32_t first = std::min(w * rowsPerWorker, sizeTexels);
        const uint32_t end = std::min(first + rowsPerWorker, sizeTexels);
        try
        {
            threads.emplace_back(resampleRows, std::cref(job), first, end);
        }
        catch (const std::system_error&)
        {
            resampleRows(job, first, end);  // no thread to be had: do these rows here
        }
    }
    resampleRows(job, 0, std::min(rowsPerWorker, sizeTexels));
    for (std::thread& thread : threads)
        thread.join();
}

glm::dvec2 windowWarpM(const glm::dvec2& pM, double halfExtentM, double warpRadiusM)
{
    if (warpRadiusM <= 0.0)
        return pM;
    return pM * ((halfExtentM + warpRadiusM) / (glm::length(pM) + warpRadiusM));
}

glm::dvec2 windowUnwarpM(const glm::dvec2& qM, double halfExtentM, double warpRadiusM)
{
    if (warpRadiusM <= 0.0)
        return qM;
    // Corners of the square beyond E + r0 have no finite preimage: send them 20 000 km away.
    double denominator = std::max(halfExtentM + warpRadiusM - glm::length(qM), warpRadiusM * 1e-3);
    return qM * (warpRadiusM / denominator);
}

glm::dvec2 WeatherWindow::texelPositionM(uint32_t i, uint32_t j) const
{
    return windowUnwarpM(glm::dvec2(texelEastingM(i), texelNorthingM(j)), halfExtentM, warpRadiusM);
}

}  // namespace sky
