// Water outside an open tank (spill.h): the outline is the one generateGeometry lays out, and
// water beyond it is sorted into spray over a wall (spilled) and water through a solid (leaked).
#include <algorithm>

#include <gtest/gtest.h>

#include "swell/bake/geometry.h"
#include "swell/bake/spill.h"

using namespace swell::bake;

namespace {

GeometryParams tankGeometry(double bedBehind) {
    GeometryParams g;
    g.particleSpacing = 0.01;
    g.tank = Box{0.0, 0.0, 1.0, 0.5};
    g.water = {Box{0.0, 0.0, 0.3, 0.2}};
    g.bedExtensionBack = bedBehind;
    return g;
}

/// The route of one water particle at (x, y), or nothing when it is not outside the tank.
std::vector<EscapedWater> escapesOf(double x, double y, const TankOutline& tank) {
    Particles p;
    p.add(0.5, 0.1, ParticleKind::Water); // in the tank
    p.add(x, y, ParticleKind::Water);
    p.add(x, y, ParticleKind::Wall); // fixed particles are never water that escaped
    return findEscapedWater(p, tank);
}

Escape routeOf(double x, double y, const TankOutline& tank) {
    const std::vector<EscapedWater> e = escapesOf(x, y, tank);
    EXPECT_EQ(e.size(), 1u) << "(" << x << ", " << y << ")";
    return e.empty() ? Escape::OverFrontWall : e.front().route;
}

} // namespace

TEST(Spill, OutlineIsTheOuterFaceOfTheGeneratedWallsAndBed) {
    for (double behind : {0.0, 0.103}) {
        const GeometryParams g = tankGeometry(behind);
        const TankOutline t = tankOutline(g);
        const Particles p = generateGeometry(g).particles;
        const double l0 = g.particleSpacing;
        const Box o = t.outer();
        EXPECT_NEAR(*std::max_element(p.x.begin(), p.x.end()) + 0.5 * l0, o.x1, 1e-12);
        EXPECT_NEAR(*std::min_element(p.x.begin(), p.x.end()) - 0.5 * l0, o.x0, 1e-12);
        EXPECT_NEAR(*std::min_element(p.y.begin(), p.y.end()) - 0.5 * l0, o.y0, 1e-12);
        EXPECT_EQ(o.y1, t.inner.y1);                                // the walls' top
        EXPECT_NEAR(t.bedBehind, behind > 0.0 ? 0.11 : 0.0, 1e-12); // whole spacings
    }
}

TEST(Spill, WaterIsOverAWallAtItsTopAndThroughItBelow) {
    const TankOutline t = tankOutline(tankGeometry(0.0)); // outer faces at -0.04 and 1.04
    EXPECT_TRUE(escapesOf(0.5, 0.45, t).empty());
    EXPECT_TRUE(escapesOf(1.03, 0.7, t).empty()) << "above the wall, not yet beyond it";
    EXPECT_TRUE(escapesOf(0.5, 3.0, t).empty()) << "spray high above the tank";
    EXPECT_EQ(routeOf(1.05, 0.52, t), Escape::OverFrontWall);
    EXPECT_EQ(routeOf(1.05, 0.495, t), Escape::OverFrontWall) << "within a spacing of the top";
    EXPECT_EQ(routeOf(1.05, 0.485, t), Escape::ThroughFrontWall);
    EXPECT_EQ(routeOf(-0.05, 0.6, t), Escape::OverBackWall);
    EXPECT_EQ(routeOf(-0.05, 0.2, t), Escape::ThroughBackWall);
    EXPECT_EQ(routeOf(0.5, -0.05, t), Escape::ThroughBed);
    EXPECT_TRUE(spilled(Escape::OverFrontWall));
    EXPECT_TRUE(spilled(Escape::OverBackWall));
    EXPECT_FALSE(spilled(Escape::ThroughFrontWall));
    EXPECT_FALSE(spilled(Escape::ThroughBackWall));
    EXPECT_FALSE(spilled(Escape::ThroughBed));
    EXPECT_EQ(toString(Escape::ThroughBed), "through the bed");
}

TEST(Spill, BehindAPistonOnlyTheEndOfTheBedIsOutside) {
    const TankOutline t = tankOutline(tankGeometry(0.1)); // bed's end at -0.14
    EXPECT_TRUE(escapesOf(-0.1, 0.02, t).empty()) << "on the bed behind the piston";
    EXPECT_EQ(routeOf(-0.15, 0.02, t), Escape::OffBedBehind);
    EXPECT_TRUE(spilled(Escape::OffBedBehind));
    EXPECT_EQ(routeOf(-0.15, 0.6, t), Escape::OverBackWall);
}

TEST(Spill, EveryEscapedParticleIsFoundInIndexOrder) {
    const TankOutline t = tankOutline(tankGeometry(0.0));
    Particles p;
    p.add(1.1, 0.6, ParticleKind::Water);
    p.add(0.5, 0.1, ParticleKind::Water);
    p.add(-0.1, 0.7, ParticleKind::Water);
    const std::vector<EscapedWater> e = findEscapedWater(p, t);
    ASSERT_EQ(e.size(), 2u);
    EXPECT_EQ(e[0].particle, 0u);
    EXPECT_EQ(e[1].particle, 2u);
    EXPECT_EQ(e[1].route, Escape::OverBackWall);
}
