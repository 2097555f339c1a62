// The picture measures on fields and points with known answers.
#include "swell/runtime/replay/picture_measures.h"

#include "swell/split_mix64.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace swell::runtime {
namespace {

HeightField fieldOf(int N, int M, const std::function<double(int, int)>& f) {
    HeightField h;
    h.cellsX = N;
    h.cellsZ = M;
    for (int m = 0; m < M; ++m)
        for (int n = 0; n < N; ++n)
            h.heights.push_back(f(n, m));
    return h;
}

} // namespace

TEST(PictureMeasures, SlopeRatiosOfAPlane) {
    const SlopeRatios r = slopeRatios(fieldOf(40, 30, [](int n, int m) { return 2.0 * n + m; }));
    EXPECT_DOUBLE_EQ(r.mean, 0.5);
    EXPECT_DOUBLE_EQ(r.p99, 0.5);
    // Long crests: a wave along x only has no slope along z.
    EXPECT_DOUBLE_EQ(
        slopeRatios(fieldOf(40, 30, [](int n, int) { return std::sin(0.3 * n); })).mean, 0.0);
    EXPECT_THROW(slopeRatios(fieldOf(40, 30, [](int, int m) { return m; })), std::invalid_argument);
    EXPECT_THROW(slopeRatios(fieldOf(1, 30, [](int n, int) { return n; })), std::invalid_argument);
}

TEST(PictureMeasures, NeedlesAreCellsAboveOrBelowAllFourNeighbours) {
    HeightField h = fieldOf(12, 12, [](int n, int) { return 0.001 * n; });
    EXPECT_EQ(needleShare(h, 0.01), 0.0);
    h.heights[5 * 12 + 5] += 0.05; // a spike
    h.heights[8 * 12 + 2] -= 0.05; // a pit
    h.heights[0] += 1.0;           // a corner cell has no four neighbours: not counted
    EXPECT_DOUBLE_EQ(needleShare(h, 0.01), 2.0 / 100.0);
    EXPECT_EQ(needleShare(h, 0.06), 0.0);
    // A ridge one cell wide along a diagonal is higher than all four axis neighbours.
    const HeightField ridge = fieldOf(12, 12, [](int n, int m) { return n == m ? 0.05 : 0.0; });
    EXPECT_DOUBLE_EQ(needleShare(ridge, 0.01), 10.0 / 100.0);
}

TEST(PictureMeasures, DifferencesAndDiscMean) {
    const HeightField a = fieldOf(10, 10, [](int n, int) { return n; });
    const HeightField b = fieldOf(10, 10, [](int n, int m) { return m < 3 ? n + 1.0 : n; });
    EXPECT_DOUBLE_EQ(shareDiffering(a, b, 0.5), 0.3);
    EXPECT_DOUBLE_EQ(meanChange(a, b), 0.3);
    EXPECT_THROW(meanChange(a, fieldOf(9, 10, [](int, int) { return 0.0; })),
                 std::invalid_argument);
    // Cell centres n + 1/2 within 2 cells of (5, 5): symmetric about n = 4.5.
    EXPECT_DOUBLE_EQ(discMean(a, 5.0, 5.0, 2.0), 4.5);
    EXPECT_THROW(discMean(a, 50.0, 50.0, 1.0), std::invalid_argument);
}

TEST(PictureMeasures, ACreaseAlongALineAndNoneOnASmoothField) {
    // A V along the diagonal n = m: the slope breaks there.
    const HeightField v = fieldOf(40, 40, [](int n, int m) {
        return 0.01 * std::abs(n - m) + 0.001 * std::sin(0.4 * n) * std::cos(0.3 * m);
    });
    EXPECT_GT(creaseRatio(v, 0.5, 0.5, 1.0, 1.0), 5.0);
    const HeightField smooth =
        fieldOf(40, 40, [](int n, int m) { return std::sin(0.2 * n) * std::cos(0.25 * m); });
    const double r = creaseRatio(smooth, 0.5, 0.5, 1.0, 1.0);
    EXPECT_GT(r, 0.5);
    EXPECT_LT(r, 1.5);
    EXPECT_THROW(creaseRatio(smooth, 0.5, 0.5, 0.0, 0.0), std::invalid_argument);
}

TEST(PictureMeasures, ARowOfPointsCoversALineAndScatteredClustersDoNot) {
    // A row along a 30-degree line across a 10 m mesh.
    std::vector<double> xs, zs;
    SplitMix64 rng(3);
    for (int i = 0; i < 400; ++i) {
        const double t = 10.0 * rng.uniform();
        xs.push_back(t * std::cos(std::numbers::pi / 6.0));
        zs.push_back(t * std::sin(std::numbers::pi / 6.0));
    }
    EXPECT_GT(lineCoverage(xs, zs, 0.05, 10.0), 0.9);
    // Twenty clusters of twenty points, 4 cm across, scattered over the mesh.
    std::vector<double> sx, sz;
    for (int c = 0; c < 20; ++c) {
        const double cx = 10.0 * rng.uniform(), cz = 10.0 * rng.uniform();
        for (int i = 0; i < 20; ++i) {
            sx.push_back(cx + 0.04 * (rng.uniform() - 0.5));
            sz.push_back(cz + 0.04 * (rng.uniform() - 0.5));
        }
    }
    EXPECT_LT(lineCoverage(sx, sz, 0.05, 10.0), 0.1);
    EXPECT_EQ(lineCoverage({}, {}, 0.05, 10.0), 0.0);
    EXPECT_THROW(lineCoverage(sx, sz, 0.0, 10.0), std::invalid_argument);
}

} // namespace swell::runtime
