#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "swell/bake/kernel.h"

using namespace swell::bake;

TEST(Kernel, WeightIsReOverRMinusOneInsideAndZeroOutside) {
    EXPECT_DOUBLE_EQ(mpsWeight(1.0, 2.1), 1.1);
    EXPECT_DOUBLE_EQ(mpsWeight(0.5, 2.0), 3.0);
    EXPECT_DOUBLE_EQ(mpsWeight(2.1, 2.1), 0.0); // r = re is outside
    EXPECT_DOUBLE_EQ(mpsWeight(5.0, 2.1), 0.0);
    EXPECT_DOUBLE_EQ(mpsWeight(0.0, 2.1), 0.0); // coincident: no direction, weight 0
    EXPECT_GT(mpsWeight(2.0999, 2.1), 0.0);
}

// Closed forms: on a square lattice the neighbours of re = 2.1 l0 sit at distances
// 1 (4 sites), sqrt 2 (4), 2 (4); re = 3.1 l0 adds sqrt 5 (8), sqrt 8 (4), 3 (4).
// n0 = sum count * (re/r - 1); lambda = sum count * r^2 w / n0 (K&O 1996 Laplacian model).
TEST(Kernel, LatticeConstantsMatchClosedFormFor21) {
    const double l0 = 0.01;
    const double re = 2.1;
    const double w1 = re / 1.0 - 1.0, w2 = re / std::sqrt(2.0) - 1.0, w4 = re / 2.0 - 1.0;
    const double n0 = 4 * w1 + 4 * w2 + 4 * w4;
    const double lambda = (4 * 1.0 * w1 + 4 * 2.0 * w2 + 4 * 4.0 * w4) / n0 * l0 * l0;
    const LatticeConstants c = latticeConstants(l0, re * l0);
    EXPECT_NEAR(c.n0, n0, 1e-12);
    EXPECT_NEAR(c.lambda, lambda, 1e-16);
    EXPECT_NEAR(c.n0, 6.539696961, 1e-8); // the number itself, so a shared mistake shows
}

TEST(Kernel, LatticeConstantsMatchClosedFormFor31) {
    const double l0 = 0.025;
    const double re = 3.1;
    struct Shell {
        double r2;
        int count;
    };
    const Shell shells[] = {{1, 4}, {2, 4}, {4, 4}, {5, 8}, {8, 4}, {9, 4}};
    double n0 = 0.0, r2w = 0.0;
    for (const Shell& s : shells) {
        const double w = re / std::sqrt(s.r2) - 1.0;
        n0 += s.count * w;
        r2w += s.count * s.r2 * w;
    }
    const LatticeConstants c = latticeConstants(l0, re * l0);
    EXPECT_NEAR(c.n0, n0, 1e-12);
    EXPECT_NEAR(c.lambda, r2w / n0 * l0 * l0, 1e-16);
}

TEST(Kernel, LatticeConstantsScaleWithSpacing) {
    const LatticeConstants a = latticeConstants(1.0, 3.1);
    const LatticeConstants b = latticeConstants(0.002, 3.1 * 0.002);
    EXPECT_NEAR(a.n0, b.n0, 1e-9);                          // dimensionless
    EXPECT_NEAR(a.lambda * 0.002 * 0.002, b.lambda, 1e-15); // scales as l0^2
}

TEST(Kernel, LatticeConstantsRejectBadInput) {
    EXPECT_THROW(latticeConstants(0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(latticeConstants(1.0, -1.0), std::invalid_argument);
}

// The flat-surface asymmetry for re = 2.1 l0: the lower half lattice's sum of y w is
// -(w(1) + 2 w(sqrt 2)) l0 - 2 w(2) l0 (w(sqrt 5) = 0), over n0 l0.
TEST(Kernel, FlatSurfaceAsymmetryMatchesTheHalfLatticeSum) {
    const double w1 = 2.1 - 1.0, w2 = 2.1 / std::sqrt(2.0) - 1.0, w4 = 2.1 / 2.0 - 1.0;
    const double n0 = 4.0 * (w1 + w2 + w4);
    const LatticeConstants c = latticeConstants(0.01, 0.021);
    EXPECT_NEAR(c.flatSurfaceAsymmetry, (w1 + 2.0 * w2 + 2.0 * w4) / n0, 1e-12);
    EXPECT_NEAR(latticeConstants(0.5, 1.05).flatSurfaceAsymmetry, c.flatSurfaceAsymmetry, 1e-12);
}
