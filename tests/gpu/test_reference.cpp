// SPDX-License-Identifier: MIT
// The reference path tracer (skyservice/render/reference_renderer.h) on lavapipe with validation on:
// a homogeneous plane-parallel slab against the published transfer of a conservative isotropic layer,
// energy conservation with albedo 1, and the built-in clouds drawn where the real-time march draws them.
#include "skyservice/render/reference_renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>

#include <cmath>

namespace sky::testscenes
{
namespace
{

class Reference : public GpuFixture
{
protected:
    static inline ReferenceRenderer* ref = nullptr;

    static void SetUpTestSuite()
    {
        GpuFixture::SetUpTestSuite();
        ref = new ReferenceRenderer;
        SkyStatus s = createReferenceRenderer(*renderer, *ref);
        ASSERT_TRUE(s.ok()) << s.message;
    }
    static void TearDownTestSuite()
    {
        destroyReferenceRenderer(*renderer, *ref);
        delete ref;
        ref = nullptr;
        GpuFixture::TearDownTestSuite();
    }

    static RenderResult referenceOk(const ViewRequest& view, const QualitySettings& quality,
                                    const ReferenceSettings& settings)
    {
        RenderResult result;
        SkyStatus s = renderReference(*renderer, *ref, view, quality, settings, result);
        EXPECT_TRUE(s.ok()) << s.message;
        EXPECT_EQ(ref->last.majorantExceeded, 0u);
        EXPECT_EQ(ref->last.pathsTruncated, 0u);
        return result;
    }

    /// The flux through a horizontal plane at the eye, per unit incident flux, of the slab lit by a unit
    /// light from the zenith: the mean of pi L over the eye's cosine-distributed hemisphere rays (all
    /// pixels, all samples), upward (hemisphere +1: what the slab transmits diffusely) or downward (-1:
    /// what it reflects).
    static inline double standardError = 0.0;  ///< of the last slabFlux

    static double slabFlux(double altitudeM, int hemisphere, double opticalDepth, ReferencePhase phase)
    {
        setWeather(*renderer, clearSky());
        ViewRequest view = lookUp(44.3, 7.5, altitudeM, 30.0, "2026-06-21T12:00:00Z");
        view.width = 32;
        view.height = 32;
        view.readback = kReadCloud;
        ReferenceSettings s;
        s.samplesPerPixel = 64;
        s.phase = phase;
        s.slab.enabled = true;
        s.slab.baseM = 2000.0;
        s.slab.topM = 3000.0;
        s.slab.extinctionPerM = opticalDepth / 1000.0;
        s.slab.albedo = 1.0;
        s.unitLight = true;
        s.hemisphere = hemisphere;
        QualitySettings q = testQuality();
        q.highCloud = false;
        const RenderResult r = referenceOk(view, q, s);
        double sum = 0.0;
        double sumSq = 0.0;
        const size_t pixels = size_t(view.width) * view.height;
        EXPECT_EQ(r.cloudRgbaHalf.size(), pixels * 4);
        for (size_t i = 0; i < pixels; ++i)
        {
            const double v = 3.14159265358979 * double(glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + 1]));
            sum += v;
            sumSq += v * v;
        }
        const double mean = sum / double(pixels);
        // The standard error of the mean over the pixels (each the mean of its samples), for the message.
        standardError = std::sqrt(std::max(sumSq / double(pixels) - mean * mean, 0.0) / double(pixels));
        return mean;
    }
};

// Diffuse transmission of a conservative, isotropically scattering plane-parallel layer of optical depth
// tau lit at normal incidence, from the thick-layer asymptotic formula (van de Hulst 1980, "Multiple Light
// Scattering", vol. 2, ch. 14; Chandrasekhar 1950, "Radiative Transfer"): T = 4 K(mu0) / (3 (tau + 2 q0)),
// with the escape function K(mu) = (sqrt 3 / 4) H(mu) (normalised 2 int K mu dmu = 1), H(1) = 2.90781 the
// conservative isotropic H-function (Chandrasekhar's table), and q0 = 0.710446 the Milne extrapolation
// length (Hopf's constant). Its error falls off exponentially with tau; at tau = 8 it is below 0.5 %, and
// Eddington's approximation (2 + 3 mu0 - e^-tau) / (4 + 3 tau) gives 0.1786 against its 0.1782.
double thickLayerTransmission(double tau)
{
    const double k1 = std::sqrt(3.0) / 4.0 * 2.90781;
    return 4.0 * k1 / (3.0 * (tau + 2.0 * 0.710446));
}

TEST_F(Reference, ConservativeIsotropicSlabMatchesThePlaneParallelTables)
{
    const double tau = 8.0;
    const double expectedT = thickLayerTransmission(tau);  // 0.1782 (+ e^-8 = 3e-4 direct, not in the flux)
    const double transmitted = slabFlux(1000.0, +1, tau, ReferencePhase::Isotropic);
    const double errorT = standardError;
    const double reflected = slabFlux(4000.0, -1, tau, ReferencePhase::Isotropic);
    // 65 536 paths each: standard errors near 1.2 % of T and 0.4 % of R (at 128 samples: T 0.1794 +- 0.0015,
    // R 0.8193 +- 0.0022; an analog Monte Carlo of the same slab with 800 000 photons: 0.1775 and 0.8222).
    // 4 % and 1.5 % leave the formula's accuracy and more than 3 standard errors.
    EXPECT_NEAR(transmitted, expectedT, 0.04 * expectedT) << "standard error " << errorT;
    EXPECT_NEAR(reflected, 1.0 - expectedT - std::exp(-tau), 0.015 * (1.0 - expectedT))
        << "standard error " << standardError;
}

TEST_F(Reference, ConservesEnergyWithAlbedoOne)
{
    // The model's two-lobe phase function (mean cosine 0.47): what is not reflected is transmitted, as
    // the diffuse flux below plus the direct beam e^-tau; the ground is black, nothing else absorbs.
    const double tau = 5.0;
    const double transmitted = slabFlux(1000.0, +1, tau, ReferencePhase::Model) + std::exp(-tau);
    const double errorT = standardError;
    const double reflected = slabFlux(4000.0, -1, tau, ReferencePhase::Model);
    // Standard errors near 0.004 each (at 128 samples: 0.3989 + 0.0067 and 0.5915, sum 0.9971).
    EXPECT_NEAR(reflected + transmitted, 1.0, 0.025) << "standard errors " << errorT << ", " << standardError;
    // With a forward-peaked phase function more gets through than with isotropic scattering.
    EXPECT_GT(transmitted, thickLayerTransmission(tau));
}

TEST_F(Reference, DrawsTheBuiltinCloudsWhereTheMarchDrawsThem)
{
    setWeather(*renderer, makeBuiltinWeather(0));
    ViewRequest view = lookUp(44.3, 7.5, 500.0, 10.0, "2026-06-21T12:00:00Z");
    view.width = 40;
    view.height = 24;
    QualitySettings q = testQuality();
    const RenderResult realTime = renderOk(view, q);
    ReferenceSettings s;
    s.samplesPerPixel = 4;
    const RenderResult reference = referenceOk(view, q, s);
    ASSERT_EQ(reference.cloudRgbaHalf.size(), realTime.cloudRgbaHalf.size());
    ASSERT_EQ(reference.displayRgba8.size(), size_t(view.width) * view.height * 4);
    const ImageStats a = cloudStats(realTime);
    const ImageStats b = cloudStats(reference);
    EXPECT_TRUE(b.allFinite);
    ASSERT_GT(a.cloudPixels, 20u) << "the view should look at the built-in cumulus";
    // The same density: the alpha of each pixel (1 - the eye ray's transmittance) agrees within the noise
    // of 4 samples and the march's step.
    double diff = 0.0;
    const size_t pixels = size_t(view.width) * view.height;
    for (size_t i = 0; i < pixels; ++i)
        diff += std::abs(double(glm::unpackHalf1x16(reference.cloudRgbaHalf[i * 4 + 3])) -
                         double(glm::unpackHalf1x16(realTime.cloudRgbaHalf[i * 4 + 3])));
    EXPECT_LT(diff / double(pixels), 0.12);
    EXPECT_GT(b.meanCloudLuminance, 0.0);
}

}  // namespace
}  // namespace sky::testscenes
