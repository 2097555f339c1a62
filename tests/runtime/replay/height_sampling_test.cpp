// Point queries on a height field: exact for fields linear in x and z, clamped at the edges,
// NaN outside the mesh.
#include "swell/runtime/replay/height_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace swell::runtime {
namespace {

Grid grid(int N, int M) {
    Grid g;
    g.cellsX = N;
    g.cellsZ = M;
    g.slices = 4;
    g.x0 = -1.0;
    g.dx = 0.25;
    g.dz = 0.5;
    g.extentZ = M * g.dz;
    return g;
}

/// h = a + b x + c z at the cell centres.
HeightField plane(const Grid& g, double a, double b, double c) {
    HeightField f{g.cellsX, g.cellsZ, {}};
    for (int m = 0; m < g.cellsZ; ++m)
        for (int n = 0; n < g.cellsX; ++n)
            f.heights.push_back(a + b * (g.x0 + (n + 0.5) * g.dx) + c * (m + 0.5) * g.dz);
    return f;
}

TEST(HeightSampling, BilinearIsExactOnAPlane) {
    const Grid g = grid(12, 7);
    const HeightField f = plane(g, 0.5, 0.3, -0.2);
    for (double x = g.x0 + 0.5 * g.dx; x <= g.x0 + 11.5 * g.dx; x += 0.0371)
        for (double z = 0.5 * g.dz; z <= 6.5 * g.dz; z += 0.113)
            EXPECT_NEAR(sampleHeight(f, g, x, z), 0.5 + 0.3 * x - 0.2 * z, 1e-12);
}

TEST(HeightSampling, EdgesClampAndOutsideIsNaN) {
    const Grid g = grid(4, 3);
    const HeightField f = plane(g, 0.0, 1.0, 0.0);
    // Within half a cell of the first edge: the first centre's value.
    EXPECT_DOUBLE_EQ(sampleHeight(f, g, g.x0, 0.7), f.at(0, 0));
    EXPECT_DOUBLE_EQ(sampleHeight(f, g, g.x0 + 4 * g.dx, 0.7), f.at(3, 0));
    EXPECT_TRUE(std::isnan(sampleHeight(f, g, g.x0 - 1e-9, 0.7)));
    EXPECT_TRUE(std::isnan(sampleHeight(f, g, 0.0, g.extentZ + 1e-9)));
    EXPECT_TRUE(std::isnan(sampleHeight(f, g, 0.0, -0.1)));
    EXPECT_TRUE(std::isnan(sampleHeight(f, g, std::numeric_limits<double>::quiet_NaN(), 0.5)));
}

TEST(HeightSampling, OneCellWideAndSizeErrors) {
    const Grid g = grid(1, 1);
    const HeightField f{1, 1, {0.42}};
    EXPECT_DOUBLE_EQ(sampleHeight(f, g, g.x0 + 0.1, 0.3), 0.42);
    const HeightField wrong{2, 1, {0.1, 0.2}};
    EXPECT_THROW(sampleHeight(wrong, g, 0.0, 0.0), std::invalid_argument);
    const std::vector<double> x{0.0, 0.1}, z{0.0};
    std::vector<double> out(2);
    EXPECT_THROW(sampleHeights(f, g, x, z, out), std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
