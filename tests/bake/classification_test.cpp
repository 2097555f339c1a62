#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

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

namespace {

/// Adds a water particle with number density n and velocity (vx, vy).
void addWater(Particles& P, double x, double y, double n, double vx = 0.0, double vy = 0.0) {
    P.add(x, y, ParticleKind::Water);
    P.n.back() = n;
    P.vx.back() = vx;
    P.vy.back() = vy;
}

} // namespace

// eq. (4) over a hand-made set: n0 = 10, d1 = 0.49, d2 = 0.96.
TEST(Classification, KeepsSurfaceSortedByXAndSplashWithVelocity) {
    Particles P;
    addWater(P, 0.30, 0.10, 9.0);            // surface
    addWater(P, 0.10, 0.20, 4.9);            // surface (n = d1 n0)
    addWater(P, 0.20, 0.05, 9.7);            // deep
    addWater(P, 0.50, 0.40, 1.0, 1.5, -2.0); // splash
    addWater(P, 0.05, 0.00, 12.0);           // deep
    addWater(P, 0.10, 0.15, 9.6);            // surface (n = d2 n0), same x as the second: y orders
    P.add(0.0, 0.0, ParticleKind::Wall);     // walls are never classified, whatever n
    P.n.back() = 2.0;
    P.add(0.0, -0.01, ParticleKind::Dummy);
    const ClassifiedFrame c = classifyParticles(P, 10.0, 0.49, 0.96);
    EXPECT_EQ(c.deep, 2u);
    ASSERT_EQ(c.surface(), 3u);
    ASSERT_EQ(c.splash(), 1u);
    const std::vector<float> surface{0.10f, 0.15f, 0.10f, 0.20f, 0.30f, 0.10f};
    EXPECT_EQ(c.frame.surface, surface);
    const std::vector<float> splash{0.50f, 0.40f, 1.5f, -2.0f};
    EXPECT_EQ(c.frame.splash, splash);
}

TEST(Classification, NoSplashGivesNoSplashRecords) {
    Particles P;
    for (int i = 0; i < 5; ++i)
        addWater(P, 0.01 * i, 0.0, 8.0);
    const ClassifiedFrame c = classifyParticles(P, 10.0, 0.49, 0.96);
    EXPECT_TRUE(c.frame.splash.empty());
    EXPECT_EQ(c.surface(), 5u);
}

// The solver's surface layer (distribution test) promotes a crest particle compressed above
// d2 n0 to surface; splash and eq. (4)'s own surface stay as they are, walls are never kept.
TEST(Classification, SurfaceLayerFlagsKeepCompressedCrestParticles) {
    Particles P;
    addWater(P, 0.10, 0.10, 9.9); // deep by n, on the layer: surface
    addWater(P, 0.20, 0.10, 9.9); // deep by n, off the layer: deep
    addWater(P, 0.30, 0.40, 1.0); // splash, on the layer: still splash
    addWater(P, 0.40, 0.10, 9.0); // surface by n, off the layer: still surface
    P.add(0.0, 0.0, ParticleKind::Wall);
    P.n.back() = 9.9;
    const std::vector<std::uint8_t> layer{1, 0, 1, 0, 1};
    const ClassifiedFrame c = classifyParticles(P, 10.0, 0.49, 0.96, layer);
    EXPECT_EQ(c.surface(), 2u);
    EXPECT_EQ(c.splash(), 1u);
    EXPECT_EQ(c.deep, 1u);
    const std::vector<float> surface{0.10f, 0.10f, 0.40f, 0.10f};
    EXPECT_EQ(c.frame.surface, surface);
    const ClassifiedFrame plain = classifyParticles(P, 10.0, 0.49, 0.96);
    EXPECT_EQ(plain.surface(), 1u);
    EXPECT_EQ(plain.deep, 2u);
}
