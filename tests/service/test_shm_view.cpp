// SPDX-License-Identifier: MIT
// The view a published frame carries (skyservice/service/shm_view.h): longitude wrapped, and an
// asymmetric frustum's half-angles with the flag, fov_deg then the vertical angle it covers.
#include "skyservice/service/shm_view.h"

#include <gtest/gtest.h>

using namespace sky;

TEST(ServiceShmView, SymmetricAndAsymmetricViews)
{
    ViewRequest r;
    r.pose = EyePose{47.5, 190.0, 1200.0, 90.0, 5.0, -3.0};
    r.fovYDeg = 55.0;
    r.width = 96;
    r.height = 48;
    SkyShmView v = shmViewOf(r);
    EXPECT_EQ(v.lon_deg, -170.0);
    EXPECT_EQ(v.fov_deg, 55.0);
    EXPECT_EQ(v.asymmetric, 0u);
    EXPECT_EQ(v.left_deg, 0.0);
    EXPECT_EQ(v.width, 96u);
    EXPECT_EQ(v.roll_deg, -3.0);

    r.frustum = Frustum{true, 40.0, -10.0, 12.0, 18.0};
    v = shmViewOf(r);
    EXPECT_EQ(v.asymmetric, 1u);
    EXPECT_EQ(v.left_deg, 40.0);
    EXPECT_EQ(v.right_deg, -10.0);
    EXPECT_EQ(v.up_deg, 12.0);
    EXPECT_EQ(v.down_deg, 18.0);
    EXPECT_EQ(v.fov_deg, 30.0);
    EXPECT_EQ(v.reserved, 0u);
}
