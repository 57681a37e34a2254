// SPDX-License-Identifier: MIT
// The reference path tracer's sampling (shaders/lib/phase_sampling.glsl) compiled as C++: each phase
// function is drawn in proportion to itself (the histogram of sampled cosines against the phase function
// integrated over each bin), the directions have the cosine asked for, cosine-weighted directions are.
#include "shaders/shared/prelude.h"
#include "shaders/shared/reference_params.h"

#include <gtest/gtest.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
namespace glsl
{
using namespace glm;
#include "shaders/lib/phase.glsl"
#include "shaders/lib/phase_sampling.glsl"
}  // namespace glsl
#pragma GCC diagnostic pop

#include <cmath>
#include <vector>

namespace
{

constexpr double kPi = 3.14159265358979323846;

// The phase function's probability of nu in [a, b] (2 pi times its integral over nu), by Simpson's rule on
// a fine grid: the forward peaks need it.
double binProbability(int model, glm::vec3 twoLobe, float dropletUm, double a, double b)
{
    const int steps = 2000;
    const double h = (b - a) / steps;
    double sum = 0.0;
    for (int i = 0; i <= steps; ++i)
    {
        const double w = (i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * double(glsl::referencePhase(model, twoLobe, dropletUm, float(a + i * h)));
    }
    return 2.0 * kPi * sum * h / 3.0;
}

// Bins of the scattering-angle cosine, finer toward the forward peak (the 20 um HG lobe has g = 0.995).
const std::vector<double> kEdges = {-1.0, -0.8, -0.5, -0.2, 0.1, 0.4, 0.6, 0.75, 0.85, 0.92, 0.96, 0.98,
                                    0.99, 0.995, 0.998, 0.9995, 1.0};

// Draws n cosines and compares their histogram with the phase function; returns the largest difference
// in probability per bin, relative to its standard error.
double worstBinZ(int model, glm::vec3 twoLobe, float dropletUm, int n)
{
    const std::vector<double>& edges = kEdges;
    std::vector<int> counts(edges.size() - 1, 0);
    uint32_t rng = 12345u;
    for (int i = 0; i < n; ++i)
    {
        const double nu = double(glsl::sampleReferencePhaseCos(model, twoLobe, dropletUm, rng));
        for (size_t b = 0; b + 1 < edges.size(); ++b)
            if (nu >= edges[b] && (nu < edges[b + 1] || b + 2 == edges.size()))
            {
                ++counts[b];
                break;
            }
    }
    double worst = 0.0;
    for (size_t b = 0; b + 1 < edges.size(); ++b)
    {
        const double p = binProbability(model, twoLobe, dropletUm, edges[b], edges[b + 1]);
        const double sigma = std::sqrt(std::max(p * (1.0 - p) / n, 1e-12));
        worst = std::max(worst, std::abs(double(counts[b]) / n - p) / sigma);
    }
    return worst;
}

TEST(ReferenceSampling, PhaseFunctionsIntegrateToOneOverTheSphere)
{
    const glm::vec3 model(0.8f, -0.3f, 0.7f);
    for (int m : {REFERENCE_PHASE_MODEL, REFERENCE_PHASE_HG_DRAINE, REFERENCE_PHASE_ISOTROPIC})
    {
        double total = 0.0;
        for (size_t b = 0; b + 1 < kEdges.size(); ++b)
            total += binProbability(m, model, 20.0f, kEdges[b], kEdges[b + 1]);
        EXPECT_NEAR(total, 1.0, 2e-3) << "model " << m;
    }
}

TEST(ReferenceSampling, EachPhaseFunctionIsDrawnInProportionToItself)
{
    // 200 000 draws: a bin off by 5 standard errors is a wrong sampler, not chance (p ~ 1e-6 per bin).
    const glm::vec3 model(0.8f, -0.3f, 0.7f);
    EXPECT_LT(worstBinZ(REFERENCE_PHASE_MODEL, model, 20.0f, 200000), 5.0);
    EXPECT_LT(worstBinZ(REFERENCE_PHASE_ISOTROPIC, model, 20.0f, 200000), 5.0);
    for (float dUm : {2.0f, 10.0f, 20.0f, 40.0f})
        EXPECT_LT(worstBinZ(REFERENCE_PHASE_HG_DRAINE, model, dUm, 200000), 5.0) << dUm << " um";
}

TEST(ReferenceSampling, TwoLobeMeanCosineIsTheWeightedMeanOfTheLobes)
{
    uint32_t rng = 7u;
    double sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i)
        sum += double(glsl::sampleReferencePhaseCos(REFERENCE_PHASE_MODEL, glm::vec3(0.8f, -0.3f, 0.7f), 20.0f, rng));
    EXPECT_NEAR(sum / n, 0.7 * 0.8 + 0.3 * -0.3, 0.005);
}

TEST(ReferenceSampling, DirectionsAroundAnAxisHaveTheCosineAskedFor)
{
    const glm::vec3 axes[] = {glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)), glm::vec3(0.0f, 0.0f, -1.0f),
                              glm::vec3(1.0f, 0.0f, 0.0f)};
    for (const glm::vec3& axis : axes)
        for (float c : {-0.9f, 0.0f, 0.5f, 0.99f})
            for (float phi : {0.0f, 1.0f, 4.0f})
            {
                const glm::vec3 d = glsl::directionAround(axis, c, phi);
                EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
                EXPECT_NEAR(glm::dot(d, axis), c, 1e-5f);
            }
}

TEST(ReferenceSampling, CosineDirectionsHaveMeanCosineTwoThirds)
{
    uint32_t rng = 99u;
    double sum = 0.0;
    double sumSq = 0.0;
    const int n = 200000;
    const glm::vec3 up(0.0f, 0.0f, 1.0f);
    for (int i = 0; i < n; ++i)
    {
        const float u1 = glsl::randomFloat(rng);
        const float u2 = glsl::randomFloat(rng);
        const double c = glm::dot(glsl::sampleCosineDirection(up, u1, u2), up);
        ASSERT_GE(c, 0.0);
        sum += c;
        sumSq += c * c;
    }
    // pdf cos/pi: E[cos] = 2/3, E[cos^2] = 1/2.
    EXPECT_NEAR(sum / n, 2.0 / 3.0, 0.003);
    EXPECT_NEAR(sumSq / n, 0.5, 0.003);
}

}  // namespace
