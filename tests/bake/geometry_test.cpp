#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "swell/bake/error.h"
#include "swell/bake/geometry.h"

using namespace swell::bake;

namespace {

GeometryParams tankWithColumn() {
    GeometryParams g;
    g.particleSpacing = 0.01;
    g.tank = Box{0.0, 0.0, 0.5, 0.3};
    g.water = {Box{0.0, 0.0, 0.1, 0.2}};
    return g;
}

template <typename F> std::string sceneErrorKey(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.key();
    }
    return "<no SceneError>";
}

} // namespace

TEST(Geometry, TankAndColumnParticleCounts) {
    const GeneratedGeometry g = generateGeometry(tankWithColumn());
    const Particles& P = g.particles;
    EXPECT_EQ(P.count(ParticleKind::Water), 10u * 20u);
    // Bed: 4 layers x (50 + 2 * 4) sites; side walls: 2 x 4 layers x 30 sites.
    const std::size_t fixed = 4 * 58 + 2 * 4 * 30;
    EXPECT_EQ(P.count(ParticleKind::Wall) + P.count(ParticleKind::Dummy), fixed);
    // Innermost two layers are wall: bed 2 x 54 (corners beyond the 2nd layer are dummy), sides 2 x
    // 2 x 30.
    EXPECT_EQ(P.count(ParticleKind::Wall), 2u * 54u + 2u * 2u * 30u);
    // Water first, then wall, then dummy.
    for (std::size_t i = 1; i < P.size(); ++i)
        EXPECT_LE(P.kind[i - 1], P.kind[i]);
}

TEST(Geometry, WaterSitsOnTheLatticeOneSpacingFromTheWalls) {
    const GeneratedGeometry g = generateGeometry(tankWithColumn());
    const Particles& P = g.particles;
    double minX = 1.0, minY = 1.0;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        minX = std::min(minX, P.x[i]);
        minY = std::min(minY, P.y[i]);
        const double fx = P.x[i] / 0.01 - 0.5, fy = P.y[i] / 0.01 - 0.5;
        EXPECT_NEAR(fx, std::round(fx), 1e-9);
        EXPECT_NEAR(fy, std::round(fy), 1e-9);
    }
    EXPECT_NEAR(minX, 0.005, 1e-12); // back wall's first layer is at x = -0.005
    EXPECT_NEAR(minY, 0.005, 1e-12);
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] == ParticleKind::Wall && std::abs(P.x[i] - 0.205) < 1e-9) {
            EXPECT_TRUE(std::abs(P.y[i] + 0.005) < 1e-9 || std::abs(P.y[i] + 0.015) < 1e-9);
        }
    }
}

TEST(Geometry, DefaultDomainContainsEveryParticleWithRoomAbove) {
    const GeneratedGeometry g = generateGeometry(tankWithColumn());
    for (std::size_t i = 0; i < g.particles.size(); ++i) {
        EXPECT_TRUE(g.domain.contains(g.particles.x[i], g.particles.y[i]));
    }
    EXPECT_GT(g.domain.y1, 0.3 + 0.2);
}

TEST(Geometry, SolidBlockHasWallSkinAndDummyCore) {
    GeometryParams g;
    g.particleSpacing = 0.01;
    g.water = {Box{0.0, 0.0, 0.05, 0.05}};
    g.solids = {Box{0.1, 0.0, 0.2, 0.1}}; // 10 x 10 sites
    const GeneratedGeometry out = generateGeometry(g);
    EXPECT_EQ(out.particles.count(ParticleKind::Wall), 100u - 36u); // layers 0-1
    EXPECT_EQ(out.particles.count(ParticleKind::Dummy),
              36u - 4u); // layers 2-3; the 2x2 core is left out
}

TEST(Geometry, BadRectanglesNameTheirKey) {
    GeometryParams g = tankWithColumn();
    g.water.push_back(Box{0.2, 0.0, 0.2 + 0.004, 0.1}); // thinner than one spacing
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[1]");

    g = tankWithColumn();
    g.water = {Box{-0.05, 0.0, 0.05, 0.1}}; // reaches into the back wall
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[0]");

    g = tankWithColumn();
    g.water.push_back(Box{0.05, 0.1, 0.15, 0.15}); // overlaps water[0]
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[1]");

    g = tankWithColumn();
    g.tank = Box{0.0, 0.0, 0.505, 0.3}; // not a whole number of spacings
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.tank");

    g = tankWithColumn();
    g.particleSpacing = -0.01;
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.particle_spacing");

    g = tankWithColumn();
    g.water.clear();
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water");

    g = tankWithColumn();
    g.domain = Box{0.0, 0.0, 0.2, 0.2}; // cuts through the tank
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.domain");
}

TEST(Geometry, CosineTopHoldsTheSitesBelowTheCurve) {
    GeometryParams g = tankWithColumn();
    g.water = {Box{0.0, 0.0, 0.5, 0.2}};
    g.waterTops = {CosineTop{0.03, 1.0}}; // top 0.2 + 0.03 cos(2 pi x): 0.23 at x = 0, 0.17 at 0.5
    const GeneratedGeometry out = generateGeometry(g);
    const Particles& p = out.particles;
    int water = 0;
    double topLeft = -1.0, topRight = -1.0; // the highest site in the first and last columns
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.kind[i] != ParticleKind::Water)
            continue;
        ++water;
        const double x = p.x[i], y = p.y[i];
        EXPECT_LT(y, 0.2 + 0.03 * std::cos(2.0 * 3.141592653589793 * x)) << x;
        if (x < 0.01)
            topLeft = std::max(topLeft, y);
        if (x > 0.49)
            topRight = std::max(topRight, y);
    }
    EXPECT_NEAR(topLeft, 0.225, 1e-9);  // sites at (j + 1/2) l0 below 0.22999
    EXPECT_NEAR(topRight, 0.165, 1e-9); // below 0.17001
    // The cosine's mean over its whole wavelength is y1: as many sites as the flat rectangle,
    // give or take the rows the lattice rounds at each column.
    EXPECT_NEAR(water, 50 * 20, 50);

    g.waterTops = {CosineTop{0.2, 1.0}}; // as deep as the water: the trough would reach the bed
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[0].surface.amplitude");
    g.waterTops = {CosineTop{0.01, 0.0}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[0].surface.wavelength");
    g.waterTops = {CosineTop{0.0, 0.0}}; // flat: the wavelength is not read
    EXPECT_EQ(generateGeometry(g).particles.count(ParticleKind::Water), 50u * 20u);
}

TEST(Geometry, MoreThanTheParticleLimitIsRefusedBeforeAnyIsMade) {
    GeometryParams g = tankWithColumn();
    g.particleSpacing = 1e-5; // 1e4 x 2e4 = 2e8 water particles in the 0.1 m x 0.2 m column
    g.tank.reset();
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.particle_spacing");
    g.particleSpacing = 0.01;
    g.water = {Box{-1e300, 0.0, 1e300, 0.1}}; // counts beyond any integer type
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.particle_spacing");
    g.water = {Box{0.0, 0.0, 0.1, 0.1}};
    g.solids = {Box{1.0, 0.0, 1e12, 1e12}}; // hollow, but its ring alone is too many
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.particle_spacing");
}

TEST(Geometry, OverlappingOrTooManySolidBlocksAreRefusedAtOnce) {
    GeometryParams g = tankWithColumn();
    g.tank.reset();
    // Touching blocks are one step of two; overlapping ones would stack their wall particles.
    g.solids = {Box{1.0, 0.0, 1.2, 0.2}, Box{1.2, 0.0, 1.4, 0.1}};
    EXPECT_NO_THROW((void)generateGeometry(g));
    g.solids.push_back(Box{1.1, 0.05, 1.3, 0.15});
    try {
        (void)generateGeometry(g);
        ADD_FAILURE() << "overlapping solids accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "geometry.solids[2]");
        EXPECT_NE(std::string(e.what()).find("overlaps geometry.solids[0]"), std::string::npos)
            << e.what();
    }
    // 50,000 copies of one block: refused by their number before any pair is compared.
    g.solids.assign(50'000, Box{1.0, 0.0, 1.2, 0.2});
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.solids");
    g.solids.resize(kMaxSolids); // at the limit: the first pair that overlaps
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.solids[1]");
}

TEST(Geometry, HollowSolidHoldsOnlyItsWallAndDummyRing) {
    GeometryParams g = tankWithColumn();
    g.tank.reset();
    g.solids = {Box{1.0, 0.0, 3.0, 1.0}}; // 200 x 100 sites, 4 layers: the core stays empty
    const GeneratedGeometry geo = generateGeometry(g);
    const std::size_t ring = 200 * 100 - (200 - 8) * (100 - 8);
    EXPECT_EQ(geo.particles.size() - geo.particles.count(ParticleKind::Water), ring);
    EXPECT_EQ(geo.particles.count(ParticleKind::Wall), 200 * 100 - (200 - 4) * (100 - 4));
}

TEST(Geometry, DomainBeyondTheNeighbourGridIsRefusedNamingIt) {
    GeometryParams g = tankWithColumn();
    g.domain = Box{-1e4, -1e4, 1e4, 1e4}; // 2e6 x 2e6 spacings
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry.domain");
    g.domain.reset();
    g.tank.reset();
    g.water = {Box{0.0, 0.0, 0.01, 0.01}, Box{1e5, 0.0, 1e5 + 0.01, 0.01}}; // two far apart
    EXPECT_EQ(sceneErrorKey([&] { (void)generateGeometry(g); }), "geometry");
}

// jitterWater (geometry.jitter): every water particle moves by at most the amplitude along x
// and y, no fixed particle moves, the offsets are a fixed function of the seed (the same twice,
// others for another seed) and spread over the whole range (not, e.g., all zero).
TEST(Geometry, JitterMovesOnlyWaterWithinItsAmplitudeAndFollowsTheSeed) {
    const GeneratedGeometry base = generateGeometry(tankWithColumn());
    const double a = 1e-3;
    const auto jittered = [&](std::uint64_t seed) {
        Particles p = base.particles;
        jitterWater(p, a, seed);
        return p;
    };
    const Particles one = jittered(7), again = jittered(7), other = jittered(8);
    const Particles& P = base.particles;
    double largest = 0.0;
    std::size_t moved = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
        const double dx = one.x[i] - P.x[i], dy = one.y[i] - P.y[i];
        if (P.kind[i] != ParticleKind::Water) {
            EXPECT_EQ(dx, 0.0);
            EXPECT_EQ(dy, 0.0);
            continue;
        }
        EXPECT_LE(std::abs(dx), a);
        EXPECT_LE(std::abs(dy), a);
        largest = std::max({largest, std::abs(dx), std::abs(dy)});
        moved += dx != 0.0 && dy != 0.0;
        EXPECT_EQ(one.x[i], again.x[i]);
        EXPECT_EQ(one.y[i], again.y[i]);
        EXPECT_NE(one.x[i], other.x[i]);
    }
    EXPECT_EQ(moved, P.count(ParticleKind::Water));
    EXPECT_GT(largest, 0.9 * a); // 400 draws: the largest is within 10 % of the bound
}

namespace {

/// A 0.5 m tank with a beach: flat to x = 0.2 m, then rising 1:5 to 0.06 m at the front wall.
GeometryParams tankWithBeach() {
    GeometryParams g = tankWithColumn();
    g.water = {Box{0.0, 0.0, 0.5, 0.1}};
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.5, 0.06}};
    return g;
}

} // namespace

TEST(Geometry, BedHeightFollowsTheProfileAndIsFlatBeyondItsEnds) {
    const GeometryParams g = tankWithBeach();
    EXPECT_DOUBLE_EQ(bedHeight(g, 0.1), 0.0);
    EXPECT_DOUBLE_EQ(bedHeight(g, 0.2), 0.0);
    EXPECT_NEAR(bedHeight(g, 0.35), 0.03, 1e-15);
    EXPECT_DOUBLE_EQ(bedHeight(g, 0.5), 0.06);
    EXPECT_DOUBLE_EQ(bedHeight(g, 0.7), 0.06);
    EXPECT_DOUBLE_EQ(bedHeight(tankWithColumn(), 0.3), 0.0); // no profile: the tank's y0
}

TEST(Geometry, WithoutABedProfileTheTankIsLaidOutAsBefore) {
    // The profile's code path with a flat profile at y0 gives the same sites, kinds and order.
    GeometryParams flat = tankWithColumn();
    flat.bed = {BedPoint{0.0, 0.0}, BedPoint{0.5, 0.0}};
    const GeneratedGeometry a = generateGeometry(tankWithColumn());
    const GeneratedGeometry b = generateGeometry(flat);
    ASSERT_EQ(a.particles.size(), b.particles.size());
    for (std::size_t i = 0; i < a.particles.size(); ++i) {
        EXPECT_EQ(a.particles.x[i], b.particles.x[i]);
        EXPECT_EQ(a.particles.y[i], b.particles.y[i]);
        EXPECT_EQ(a.particles.kind[i], b.particles.kind[i]);
    }
    EXPECT_EQ(a.backWall, b.backWall);
}

TEST(Geometry, BedProfileCutsTheWaterAndLaysItsLayersUnderTheSlope) {
    const GeometryParams g = tankWithBeach();
    const GeneratedGeometry out = generateGeometry(g);
    const Particles& P = out.particles;
    const double l0 = g.particleSpacing;
    const int layers = g.wallLayers + g.dummyLayers;
    std::size_t water = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
        const double b = bedHeight(g, std::clamp(P.x[i], 0.0, 0.5));
        if (P.kind[i] == ParticleKind::Water) {
            ++water;
            // At least l0 / 2 above the profile: one spacing above the bed's first layer.
            EXPECT_GE(P.y[i], b + 0.5 * l0 - 1e-9) << "water too near the bed at x = " << P.x[i];
            continue;
        }
        if (P.x[i] < 0.0 || P.x[i] > 0.5 || P.y[i] > b - 1e-9)
            continue; // the side walls above the bed
        // Under the bed the column's layers follow the profile: at b - (k + 1/2) l0, the first
        // two wall, the next two dummy, none deeper (not a staircase of lattice rows).
        const double k = (b - P.y[i]) / l0 - 0.5;
        EXPECT_NEAR(k, std::round(k), 1e-9) << P.x[i] << ", " << P.y[i];
        EXPECT_LT(k, layers) << P.x[i] << ", " << P.y[i];
        EXPECT_EQ(P.kind[i], k < g.wallLayers ? ParticleKind::Wall : ParticleKind::Dummy)
            << P.x[i] << ", " << P.y[i];
    }
    // Each column between the walls: its water sites are the lattice rows from l0 / 2 above the
    // bed to 0.1 m.
    std::size_t expected = 0;
    for (int i = 0; i < 50; ++i) {
        const double x = (i + 0.5) * l0;
        for (int j = 0; j < 10; ++j)
            expected += (j + 0.5) * l0 >= bedHeight(g, x) + 0.5 * l0 - 1e-9 ? 1 : 0;
    }
    EXPECT_EQ(water, expected);
    EXPECT_LT(water, 500u); // the beach took some
    // Every column has exactly `layers` fixed sites under the bed: no hole, no orphan.
    for (int i = 0; i < 50; ++i) {
        const double x = (i + 0.5) * l0;
        int under = 0;
        for (std::size_t p = 0; p < P.size(); ++p)
            under += P.kind[p] != ParticleKind::Water && std::abs(P.x[p] - x) < 1e-9 &&
                     P.y[p] < bedHeight(g, x) - 1e-9;
        EXPECT_EQ(under, layers) << "column at x = " << x;
    }
    // The front wall stands on the beach's top, 0.06 m: its sites start l0 / 2 above it, and
    // under it are that column's bed layers, the deeper two dummy.
    for (std::size_t p = 0; p < P.size(); ++p) {
        if (P.x[p] > 0.5 && P.y[p] > 0.0 && P.y[p] < 0.06 - 2.0 * l0) {
            EXPECT_EQ(P.kind[p], ParticleKind::Dummy) << P.x[p] << ", " << P.y[p];
        }
        if (P.x[p] > 0.5 && P.y[p] > 0.06) {
            const double j = (P.y[p] - 0.06) / l0 - 0.5;
            EXPECT_NEAR(j, std::round(j), 1e-9) << P.x[p] << ", " << P.y[p];
        }
    }
}

TEST(Geometry, BadBedProfilesNameTheirPoint) {
    GeometryParams g = tankWithBeach();
    g.bed = {BedPoint{0.2, 0.0}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed");
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.2, 0.01}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[1]");
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.6, 0.01}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[1]");
    g.bed = {BedPoint{0.2, -0.01}, BedPoint{0.4, 0.01}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[0]");
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.3, 0.3}}; // to the top of the walls
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[1]");
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.25, 0.06}}; // slope 1.2
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[1]");
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.25, 0.05}}; // slope 1: allowed
    EXPECT_NO_THROW(generateGeometry(g));
    g.bed = {BedPoint{0.2, 0.0}, BedPoint{0.3, std::nan("")}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.bed[1]");
    // Water wholly under the bed holds nothing.
    g.bed = {BedPoint{0.0, 0.05}, BedPoint{0.5, 0.05}};
    g.water = {Box{0.0, 0.0, 0.5, 0.1}, Box{0.0, 0.0, 0.5, 0.04}};
    g.water[0].y0 = 0.05;
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(g); }), "geometry.water[1]");
    // A profile needs a tank.
    GeometryParams open;
    open.water = {Box{0.0, 0.0, 0.1, 0.1}};
    open.bed = {BedPoint{0.0, 0.0}, BedPoint{0.1, 0.0}};
    EXPECT_EQ(sceneErrorKey([&] { generateGeometry(open); }), "geometry.bed");
}
