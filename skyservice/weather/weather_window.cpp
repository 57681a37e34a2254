// SPDX-License-Identifier: MIT
#include "skyservice/weather/weather_window.h"

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

float nearestType(const std::vector<uint8_t>& type, const GridPoint& s, size_t cellCount)
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
    const LatLonGrid* grid;
    WeatherWindow* out;
    double centreLatDeg;
    double centreLonDeg;
};

void resampleRows(const ResampleJob& job, uint32_t firstRow, uint32_t endRow)
{
    const WeatherSnapshot& snapshot = *job.snapshot;
    const LatLonGrid& grid = *job.grid;
    WeatherWindow& out = *job.out;
    const size_t cells = grid.cellCount();
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
            const GridPoint s = grid.locate(latDeg, lonDeg);
            const float capeJKg = grid.sample(snapshot.capeJKg, s, 0.0f);
            // Outside a regional model's domain there is no data: clear sky, faded in over its soft edge.
            const float dataWeight = std::clamp(grid.sample(snapshot.dataWeight, s, 1.0f), 0.0f, 1.0f);

            for (size_t k = 0; k < layerCount; ++k)
            {
                const CloudLayerFields& layer = snapshot.layers[k];
                glm::vec4& shape = out.texels[out.index(uint32_t(2 * k), i, j)];
                shape.x =
                    dataWeight * sampleCoverage(grid, layer.coverage, layer.baseAltitudeM, layer.topAltitudeM, s);
                shape.y = grid.sample(layer.baseAltitudeM, s, 0.0f);
                shape.z = grid.sample(layer.topAltitudeM, s, 0.0f);
                shape.w = nearestType(layer.type, s, cells);
                glm::vec4& dynamics = out.texels[out.index(uint32_t(2 * k + 1), i, j)];
                dynamics.x = grid.sample(layer.windEastMS, s, 0.0f);
                dynamics.y = grid.sample(layer.windNorthMS, s, 0.0f);
                dynamics.z = grid.sample(layer.precipitationMmH, s, 0.0f);
                dynamics.w = capeJKg;
            }
            for (size_t k = layerCount; k < size_t(MAX_CLOUD_LAYERS); ++k)
                out.texels[out.index(uint32_t(2 * k + 1), i, j)].w = capeJKg;

            glm::vec4& highShape = out.texels[out.index(WEATHER_WINDOW_HIGH_SLICE, i, j)];
            highShape.x = dataWeight * sampleCoverage(grid, high.coverage, high.altitudeM, high.altitudeM, s);
            highShape.y = grid.sample(high.altitudeM, s, 0.0f);
            highShape.z = nearestType(high.type, s, cells);
            glm::vec4& highDynamics = out.texels[out.index(WEATHER_WINDOW_HIGH_SLICE + 1, i, j)];
            highDynamics.x = grid.sample(high.windEastMS, s, 0.0f);
            highDynamics.y = grid.sample(high.windNorthMS, s, 0.0f);
            highDynamics.z = grid.sample(snapshot.tropopauseAltitudeM, s, kDefaultTropopauseAltitudeM);
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

    const ResampleJob job{&snapshot, &snapshot.grid, &out, centreLatDeg, centreLonDeg};
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
