// Splash sprites under the opaque water surface are dropped before drawing, in order.
#include "swell/runtime/render/splash_culling.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace swell::runtime {
namespace {

Grid testGrid() {
    Grid g;
    g = test::sized(10, 8, 4, g);
    g.x0 = 0.0;
    g.dx = 0.1;
    g.dz = 0.1;
    g.extentZ = 0.8;
    return g;
}

// Flat water at 0.5 m except one bump at vertex (5, 4); vertex (n, m) at x = (n + 0.5) 0.1,
// z = (m + 0.5) 0.1.
std::vector<float> testHeights() {
    std::vector<float> h(10 * 8, 0.5f);
    h[4 * 10 + 5] = 0.7f;
    return h;
}

// Far above: the footprint stays the radius (0.71 px at 3 m is 0.002 m at 1000 px per metre).
const SpriteFootprint kFootprint{0.01, {0.5, 3.0, 0.4}, 1000.0};

TEST(SplashCulling, DropsOnlySpritesWhollyUnderTheSurfaceAndKeepsTheOrder) {
    const std::vector<SplashSprite> sprites{
        {0.42, 0.60, 0.31, 1.0f},  // above the water: kept
        {0.42, 0.40, 0.31, 0.5f},  // 0.1 m under: dropped
        {0.42, 0.495, 0.31, 0.7f}, // its disc reaches above 0.5: kept
        {0.03, 0.10, 0.31, 1.0f},  // under, but in the edge cell: kept
        {0.42, 0.40, 0.75, 1.0f},  // under, but outside the mesh's inner cells: kept
        {0.57, 0.30, 0.45, 0.2f},  // under (the bump is higher): dropped
        {-1.0, -5.0, 0.40, 1.0f},  // outside the mesh: kept
    };
    std::vector<SplashSprite> out;
    const std::size_t dropped =
        cullSubmergedSplashes(sprites, testHeights(), testGrid(), kFootprint, out);
    EXPECT_EQ(dropped, 2u);
    ASSERT_EQ(out.size(), 5u);
    const std::vector<std::size_t> kept{0, 2, 3, 4, 6};
    for (std::size_t k = 0; k < kept.size(); ++k) {
        EXPECT_EQ(out[k].y, sprites[kept[k]].y) << k;
        EXPECT_EQ(out[k].alpha, sprites[kept[k]].alpha) << k;
    }
}

TEST(SplashCulling, ManySpritesAreCulledInParallelAsOneAtATimeAndAppended) {
    // Enough sprites to be split over threads: the result is the sprites kept one at a time,
    // in order, appended after what `out` held.
    std::vector<SplashSprite> sprites;
    for (int k = 0; k < 40000; ++k) {
        const float x = 0.15f + 0.7f * static_cast<float>((k * 37) % 101) / 100.0f;
        const float z = 0.15f + 0.5f * static_cast<float>((k * 53) % 89) / 88.0f;
        const float y = 0.3f + 0.4f * static_cast<float>((k * 29) % 97) / 96.0f;
        sprites.push_back({x, y, z, static_cast<float>(k)});
    }
    std::vector<SplashSprite> expected{{9.0f, 9.0f, 9.0f, -1.0f}};
    std::size_t expectedDropped = 0;
    for (const SplashSprite& s : sprites)
        expectedDropped += cullSubmergedSplashes(std::span(&s, 1), testHeights(), testGrid(),
                                                 kFootprint, expected);
    std::vector<SplashSprite> out{{9.0f, 9.0f, 9.0f, -1.0f}};
    const std::size_t dropped =
        cullSubmergedSplashes(sprites, testHeights(), testGrid(), kFootprint, out);
    EXPECT_EQ(dropped, expectedDropped);
    EXPECT_GT(dropped, 5000u);
    EXPECT_LT(dropped, 35000u);
    ASSERT_EQ(out.size(), expected.size());
    for (std::size_t k = 0; k < out.size(); ++k)
        ASSERT_EQ(out[k].alpha, expected[k].alpha) << k;
}

TEST(SplashCulling, TheLowestVertexAroundDecides) {
    // Under the flat 0.5 m but above a dip at a neighbouring vertex: kept.
    std::vector<float> h = testHeights();
    const std::vector<SplashSprite> sprites{{0.42, 0.45, 0.31, 1.0f}};
    std::vector<SplashSprite> out;
    EXPECT_EQ(cullSubmergedSplashes(sprites, h, testGrid(), kFootprint, out), 1u);
    h[2 * 10 + 3] = 0.40f; // vertex (3, 2), one cell away from the sprite's cell (4, 2)
    out.clear();
    EXPECT_EQ(cullSubmergedSplashes(sprites, h, testGrid(), kFootprint, out), 0u);
    EXPECT_EQ(out.size(), 1u);
}

TEST(SplashCulling, DiscsAsBigAsACellOrAPixelFarAwayAreKept) {
    const std::vector<SplashSprite> sprites{{0.42, 0.40, 0.31, 1.0f}};
    std::vector<SplashSprite> out;
    // Radius of a whole cell: it could reach past the vertices looked at.
    EXPECT_EQ(cullSubmergedSplashes(sprites, testHeights(), testGrid(),
                                    {0.1, kFootprint.eye, 1000.0}, out),
              0u);
    // A tiny sprite drawn as one pixel, seen from so far that the pixel spans a cell.
    out.clear();
    EXPECT_EQ(cullSubmergedSplashes(sprites, testHeights(), testGrid(),
                                    {0.001, {0.4, 100.0, 0.3}, 500.0}, out),
              0u);
}

TEST(SplashCulling, HeightsOfTheWrongSizeThrow) {
    std::vector<SplashSprite> out;
    const std::vector<float> wrong(12, 0.0f);
    EXPECT_THROW(cullSubmergedSplashes({}, wrong, testGrid(), kFootprint, out),
                 std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
