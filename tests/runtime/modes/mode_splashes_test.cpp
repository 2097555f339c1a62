// Splash sprites follow the ripple's rotated slice sets and the whirlpool's spirals.
#include "swell/runtime/modes/mode_splashes.h"

#include "swell/runtime/modes/whirlpool.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swell::runtime {
namespace {

Grid testGrid() {
    Grid g;
    g = test::sized(64, 64, 32, g); // J = 63
    g.x0 = -0.5;
    g.dx = 4.0 / 64;
    g.dz = 4.0 / 64;
    g.extentZ = 4.0;
    return g;
}

// Surging keeps the sprites where they are and drops those outside the tank (the mesh is x in
// [-0.5, 3.5], z in [0, 4]): past the far wall, behind the back wall, beyond the side faces.
TEST(ModeSplashes, SurgingKeepsTheSpritesInTheTankAndDropsTheRest) {
    std::vector<SplashSprite> s{{0.3f, 0.6f, 1.2f, 0.5f},  {9.0f, 0.6f, 1.2f, 1.0f},
                                {-0.6f, 0.6f, 1.2f, 1.0f}, {3.4f, 0.9f, 3.9f, 0.7f},
                                {1.0f, 0.6f, -0.1f, 1.0f}, {1.0f, 0.6f, 4.1f, 1.0f}};
    const std::vector<SplashSprite> before = s;
    placeSplashes(s, testGrid(), ModeParams{}, 0, 3.0);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s[0].x, before[0].x);
    EXPECT_EQ(s[0].z, before[0].z);
    EXPECT_EQ(s[1].x, before[3].x);
    EXPECT_EQ(s[1].z, before[3].z);
}

TEST(ModeSplashes, RippleRotatesAboutTheCentreAndDropsWhatLeavesTheMesh) {
    ModeParams mode;
    mode.mode = ReplayMode::Ripple;
    mode.ripple.anglesDegrees = {0.0, 90.0, 45.0};
    // The mesh is x in [-0.5, 3.5], z in [0, 4], centre (1.5, 2.0): a sprite 1 m along +x from
    // the centre, one at the centre, one near a corner (45 degrees take it past the edge).
    std::vector<SplashSprite> s{
        {2.5f, 0.7f, 2.0f, 0.8f}, {1.5f, 0.4f, 2.0f, 1.0f}, {3.4f, 0.5f, 3.9f, 1.0f}};
    std::vector<SplashSprite> d0 = s;
    placeSplashes(d0, testGrid(), mode, 0, 0.0);
    ASSERT_EQ(d0.size(), 3u); // 0 degrees: unchanged
    EXPECT_FLOAT_EQ(d0[0].x, 2.5f);
    std::vector<SplashSprite> d2 = s;
    placeSplashes(d2, testGrid(), mode, 2, 0.0);
    ASSERT_EQ(d2.size(), 2u); // the corner one went to (1.5, 4.69): dropped
    EXPECT_NEAR(d2[0].x, 1.5 + std::sqrt(0.5), 1e-6);
    placeSplashes(s, testGrid(), mode, 1, 0.0);
    ASSERT_EQ(s.size(), 3u); // a square turned by 90 degrees about its centre stays on it
    // +x turns into +z (a = 90 degrees from +x towards +z); y and opacity stay.
    EXPECT_NEAR(s[0].x, 1.5, 1e-6);
    EXPECT_NEAR(s[0].z, 3.0, 1e-6);
    EXPECT_FLOAT_EQ(s[0].y, 0.7f);
    EXPECT_FLOAT_EQ(s[0].alpha, 0.8f);
    EXPECT_NEAR(s[1].x, 1.5, 1e-6);
    EXPECT_NEAR(s[1].z, 2.0, 1e-6);
    EXPECT_THROW(placeSplashes(s, testGrid(), mode, 3, 0.0), std::invalid_argument);
}

TEST(ModeSplashes, WhirlpoolPutsASliceOnItsSpiral) {
    ModeParams mode;
    mode.mode = ReplayMode::Whirlpool;
    const Grid g = testGrid();
    const SpiralGeometry spiral(g, mode.whirlpool);
    const double J = spiral.sliceCount();
    // Real slice j = 4 at column u = 16 (t = pi / 2), animation time 0 (no spin).
    const double z = g.sliceZCells(4) * g.dz;
    const double x = g.x0 + 16.0 * g.dx;
    std::vector<SplashSprite> s{{static_cast<float>(x), 0.6f, static_cast<float>(z), 1.0f}};
    placeSplashes(s, g, mode, 0, 0.0);
    ASSERT_EQ(s.size(), 1u);
    const double t = std::numbers::pi / 2.0;
    const double r = spiral.innerRadius() * std::exp(mode.whirlpool.growth * t);
    const double angle = 2.0 * std::numbers::pi * 4.0 / J + t;
    EXPECT_NEAR(s[0].x, spiral.centreX() + r * std::cos(angle), 1e-5);
    EXPECT_NEAR(s[0].z, spiral.centreZ() + r * std::sin(angle), 1e-5);
    EXPECT_FLOAT_EQ(s[0].y, 0.6f);
    // The cell there lies on that spiral: SpiralGeometry gives back slice 4 and column 16.
    const int n = static_cast<int>(std::floor((s[0].x - g.x0) / g.dx));
    const int m = static_cast<int>(std::floor(s[0].z / g.dz));
    const SpiralPoint p = spiral.at(n, m);
    EXPECT_NEAR(p.u, 16.0, 1.5);
    EXPECT_NEAR(p.s, 4.0, 1.5);
}

} // namespace
} // namespace swell::runtime
