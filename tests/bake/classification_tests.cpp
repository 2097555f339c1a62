#include <gtest/gtest.h>

#include "swell/bake/classification.h"

using namespace swell::bake;

// Paper eq. (4) with Table 1 thresholds d1 = 0.49, d2 = 0.96.
TEST(Classification, FollowsEquation4Boundaries) {
    const double n0 = 10.0;
    EXPECT_EQ(classifyWater(4.8, n0, 0.49, 0.96), WaterClass::Splash);
    EXPECT_EQ(classifyWater(4.9, n0, 0.49, 0.96), WaterClass::Surface); // n = d1 n0 is surface
    EXPECT_EQ(classifyWater(9.6, n0, 0.49, 0.96), WaterClass::Surface); // n = d2 n0 is surface
    EXPECT_EQ(classifyWater(9.61, n0, 0.49, 0.96), WaterClass::Deep);
    EXPECT_EQ(classifyWater(0.0, n0, 0.49, 0.96), WaterClass::Splash);
}
