// SPDX-License-Identifier: MIT
// The weather window's lattice of centres and the eye's place on a window (skyservice/earth/
// window_lattice.h), against GeographicLib's geodesics.
#include "skyservice/weather/window_lattice.h"

#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace sky;

TEST(WindowLattice, EveryEyeIsNearItsNodeAndTheNodeDependsOnlyOnTheEye)
{
    const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-540.0, 540.0);
    double worstM = 0;
    for (int i = 0; i < 20000; ++i)
    {
        double la = i < 4 ? (i % 2 ? 90.0 : -90.0) : lat(rng);
        double lo = i < 4 ? (i < 2 ? 0.0 : 179.999) : lon(rng);
        WindowCentre c = windowCentreForEye(la, lo);
        double s12 = 0;
        g.Inverse(la, lo, c.latDeg, c.lonDeg, s12);
        worstM = std::max(worstM, s12);
        ASSERT_GE(c.lonDeg, -180.0);
        ASSERT_LT(c.lonDeg, 180.0);
        // Another longitude convention for the same point gives the same node.
        WindowCentre same = windowCentreForEye(la, lo + 360.0);
        ASSERT_TRUE(same == c) << la << " " << lo;
    }
    std::printf("farthest eye from its node: %.0f m\n", worstM);
    EXPECT_LT(worstM, 1700.0);
    EXPECT_GT(worstM, 1000.0);  // the lattice is as coarse as documented (~2.2 km), not finer
}

TEST(WindowLattice, NeighbouringEyesAcrossACellEdgeGetNeighbouringNodes)
{
    // 45.01 deg is halfway between rows 2250 and 2251.
    WindowCentre a = windowCentreForEye(45.0099, 7.0);
    WindowCentre b = windowCentreForEye(45.0101, 7.0);
    EXPECT_EQ(a.row + 1, b.row);
    EXPECT_NEAR(b.latDeg - a.latDeg, kWindowLatticeDeg, 1e-12);
}

TEST(WindowLattice, EyeOnWindowMatchesTheGeodesicFromTheCentre)
{
    const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
    for (double la : {0.0, 45.0, -63.0, 78.0, 89.99})
        for (double lo : {7.0, 179.995, -179.995})
        {
            WindowCentre c = windowCentreForEye(la, lo);
            EyeOnWindow e = placeEyeOnWindow(c.latDeg, c.lonDeg, la, lo);
            double s12 = 0, azi1 = 0, azi2 = 0;
            g.Inverse(c.latDeg, c.lonDeg, la, lo, s12, azi1, azi2);
            // Azimuthal equidistant: the distance from the centre is kept, the direction is the azimuth.
            EXPECT_NEAR(glm::length(e.offsetM), s12, 1e-3) << la << " " << lo;
            if (s12 > 1.0)
            {
                EXPECT_NEAR(e.offsetM.x, s12 * std::sin(azi1 * M_PI / 180.0), 1e-3);
                EXPECT_NEAR(e.offsetM.y, s12 * std::cos(azi1 * M_PI / 180.0), 1e-3);
            }
            // Within ~2 km of the centre the map from the eye's east/north to the plane is a rotation by
            // the meridian convergence (tiny except near the pole) with a scale of 1.
            EXPECT_NEAR(glm::length(e.eastAxis), 1.0, 1e-4);
            EXPECT_NEAR(glm::length(e.northAxis), 1.0, 1e-4);
            EXPECT_NEAR(glm::dot(e.eastAxis, e.northAxis), 0.0, 1e-4);
            EXPECT_GT(e.eastAxis.x * e.northAxis.y - e.eastAxis.y * e.northAxis.x, 0.99);  // not mirrored
        }
}

TEST(WindowLattice, EyeAtTheCentreIsAtTheOrigin)
{
    EyeOnWindow e = placeEyeOnWindow(45.0, 7.0, 45.0, 7.0);
    EXPECT_NEAR(e.offsetM.x, 0.0, 1e-6);
    EXPECT_NEAR(e.offsetM.y, 0.0, 1e-6);
    EXPECT_NEAR(e.eastAxis.x, 1.0, 1e-6);
    EXPECT_NEAR(e.northAxis.y, 1.0, 1e-6);
}
