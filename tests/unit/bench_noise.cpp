// SPDX-License-Identifier: MIT
// CPU cost of the noise textures' per-texel recipes (the same code the compute passes run), to estimate
// the start-up cost on lavapipe. Usage: bench_noise [threads]. Prints ms per texture and a checksum.
#include "shaders/shared/noise_params.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace glsl
{
using namespace glm;
#include "shaders/lib/noise.glsl"
}  // namespace glsl

namespace
{

template <typename F>
double timeSlices(uint32_t slices, uint32_t threads, F&& perSlice)
{
    auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> workers;
    for (uint32_t t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (uint32_t z = t; z < slices; z += threads)
                perSlice(z);
        });
    for (std::thread& w : workers)
        w.join();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv)
{
    const uint32_t threads = argc > 1 ? uint32_t(std::atoi(argv[1])) : 1u;
    const uint32_t seed = 1u;
    std::vector<float> sums(BASE_NOISE_SIZE, 0.0f);

    double baseMs = timeSlices(BASE_NOISE_SIZE, threads, [&](uint32_t z) {
        for (uint32_t y = 0; y < BASE_NOISE_SIZE; ++y)
            for (uint32_t x = 0; x < BASE_NOISE_SIZE; ++x)
                sums[z] += glsl::baseNoiseTexel(glm::uvec3(x, y, z), BASE_NOISE_SIZE, seed).x;
    });
    double detailMs = timeSlices(DETAIL_NOISE_SIZE, threads, [&](uint32_t z) {
        for (uint32_t y = 0; y < DETAIL_NOISE_SIZE; ++y)
            for (uint32_t x = 0; x < DETAIL_NOISE_SIZE; ++x)
                sums[z] += glsl::detailNoiseTexel(glm::uvec3(x, y, z), DETAIL_NOISE_SIZE, seed).x;
    });
    double curlMs = timeSlices(CURL_NOISE_SIZE, threads, [&](uint32_t y) {
        for (uint32_t x = 0; x < CURL_NOISE_SIZE; ++x)
            sums[y] += glsl::curlNoiseTexel(glm::uvec2(x, y), CURL_NOISE_SIZE, seed).x;
    });
    double checksum = 0.0;
    for (float s : sums)
        checksum += double(s);
    std::printf("threads %u: base %u^3 %.0f ms (%.1f ns/texel/thread), detail %u^3 %.1f ms, curl %u^2 %.1f ms; checksum %.6g\n",
                threads, BASE_NOISE_SIZE, baseMs, baseMs * 1e6 * threads / (128.0 * 128.0 * 128.0), DETAIL_NOISE_SIZE,
                detailMs, CURL_NOISE_SIZE, curlMs, checksum);
    return 0;
}
