// MpsSolver::exportState / importState: a solver that imports a state continues bit for bit
// as the solver that exported it (piston wall, a particle moved between steps, water removed),
// and a state of other particles is refused. MpsSolver::removeWater: the water left continues
// as if the removed water had never been there, and the piston keeps moving.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "expect_same_particles.h"
#include "swell/bake/geometry.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/scene.h"

using namespace swell::bake;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

Scene sceneFile(const char* name) {
    return loadScene(kScenes / name);
}

/// Takes `steps` steps with each of two solvers.
void stepBoth(MpsSolver& a, MpsSolver& b, int steps) {
    for (int k = 0; k < steps; ++k) {
        a.step();
        b.step();
    }
}

} // namespace

TEST(MpsState, ImportedStateContinuesBitForBitWithAPistonWall) {
    const Scene scene = sceneFile("surging_small.json");
    MpsSolver a = makeSolver(scene);
    for (int k = 0; k < 120; ++k)
        a.step(); // the piston has started moving (ramp)
    const MpsState s = a.exportState();
    EXPECT_EQ(s.step, 120);
    EXPECT_FALSE(s.wallRestX.empty());
    MpsSolver b = makeSolver(scene);
    b.importState(s);
    EXPECT_EQ(b.stepCount(), 120);
    EXPECT_EQ(b.time(), a.time());
    expectSameParticles(a.particles(), b.particles());
    for (int k = 0; k < 150; ++k) {
        const StepStats& sa = a.step();
        const int itA = sa.ppeIterations;
        const StepStats& sb = b.step();
        ASSERT_EQ(itA, sb.ppeIterations) << "step " << a.stepCount();
    }
    EXPECT_EQ(a.time(), b.time());
    expectSameParticles(a.particles(), b.particles());
}

TEST(MpsState, ParticleMovedBetweenStepsIsCarriedOver) {
    // relocateWater marks the neighbour lists stale (NaN reference); the importing solver
    // must rebuild at the same step as the exporting one.
    const Scene scene = sceneFile("ripple_small.json");
    MpsSolver a = makeSolver(scene);
    for (int k = 0; k < 40; ++k)
        a.step();
    const Particles& P = a.particles();
    a.relocateWater(5, P.x[5], P.y[5], P.vx[5] * 0.5, P.vy[5]);
    const MpsState s = a.exportState();
    MpsSolver b = makeSolver(scene);
    b.importState(s);
    stepBoth(a, b, 60);
    expectSameParticles(a.particles(), b.particles());
}

TEST(MpsState, StateOfOtherParticlesIsRefused) {
    const Scene surging = sceneFile("surging_small.json");
    const Scene ripple = sceneFile("ripple_small.json");
    MpsSolver a = makeSolver(surging);
    MpsSolver r = makeSolver(ripple);
    const auto message = [](MpsSolver& solver, const MpsState& s) -> std::string {
        try {
            solver.importState(s);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(message(r, a.exportState()).find("particles"), std::string::npos);

    MpsState kind = a.exportState();
    const std::size_t wall = kind.particles.size() - 1;
    kind.particles.kind[wall] = ParticleKind::Water;
    EXPECT_NE(message(a, kind).find(std::to_string(wall)), std::string::npos);

    MpsState noWall = a.exportState();
    noWall.wallRestX.clear();
    EXPECT_NE(message(a, noWall).find("moving wall"), std::string::npos);

    MpsState outside = a.exportState();
    outside.particles.x[0] = 1e9;
    EXPECT_NE(message(a, outside).find("outside the domain"), std::string::npos);
    // A refused import leaves the solver as it was.
    EXPECT_EQ(a.stepCount(), 0);
    EXPECT_NO_THROW(a.step());
}

TEST(MpsState, RemovedWaterLeavesTheRestAsIfItHadNeverBeenThere) {
    // A droplet high above the dam-break tank, beyond every kernel's reach, taken out after
    // the first step: from then on the tank's water is bit for bit that of a run without it.
    const Scene scene = sceneFile("dam_break_small.json");
    const GeneratedGeometry g = generateGeometry(scene.geometry);
    const std::size_t water = g.particles.count(ParticleKind::Water);
    Particles with;
    for (std::size_t i = 0; i < g.particles.size(); ++i) {
        if (i == water)
            with.add(0.25, 0.6, ParticleKind::Water); // the last water particle
        with.add(g.particles.x[i], g.particles.y[i], g.particles.kind[i]);
    }
    const double l0 = scene.geometry.particleSpacing;
    MpsSolver a(scene.physics, scene.solver, with, l0, g.domain);
    MpsSolver b(scene.physics, scene.solver, g.particles, l0, g.domain);
    a.step();
    b.step();
    EXPECT_LT(a.particles().vy[water], 0.0) << "the droplet falls freely";
    const std::vector<std::size_t> droplet{water};
    a.removeWater(droplet);
    EXPECT_EQ(a.removedWater(), std::vector<std::uint32_t>{static_cast<std::uint32_t>(water)});
    EXPECT_EQ(a.particles().count(ParticleKind::Water), water);
    expectSameParticles(a.particles(), b.particles());
    EXPECT_EQ(a.surfaceFlags(), b.surfaceFlags());
    stepBoth(a, b, 200);
    expectSameParticles(a.particles(), b.particles());
}

TEST(MpsState, RemovingWaterKeepsThePistonMoving) {
    const Scene scene = sceneFile("surging_small.json");
    MpsSolver a = makeSolver(scene);
    MpsSolver b = makeSolver(scene);
    stepBoth(a, b, 100);
    const std::vector<std::size_t> gone{0, 7};
    a.removeWater(gone);
    stepBoth(a, b, 100);
    // The fixed particles (after the water) are where the same piston puts them in both runs.
    const Particles& A = a.particles();
    const Particles& B = b.particles();
    ASSERT_EQ(A.size() + 2, B.size());
    const std::size_t water = A.count(ParticleKind::Water);
    ASSERT_EQ(water + 2, B.count(ParticleKind::Water));
    bool moved = false;
    for (std::size_t i = water; i < A.size(); ++i) {
        ASSERT_EQ(A.kind[i], B.kind[i + 2]);
        ASSERT_EQ(A.x[i], B.x[i + 2]) << "fixed particle " << i;
        ASSERT_EQ(A.y[i], B.y[i + 2]);
        moved = moved || A.vx[i] != 0.0;
    }
    EXPECT_TRUE(moved) << "the piston is moving";
    EXPECT_EQ(a.exportState().wallRestX.size(), A.size());
}

TEST(MpsState, StateWithRemovedWaterIsImportedBitForBit) {
    const Scene scene = sceneFile("surging_small.json");
    MpsSolver a = makeSolver(scene);
    for (int k = 0; k < 60; ++k)
        a.step();
    a.removeWater(std::vector<std::size_t>{3});
    for (int k = 0; k < 30; ++k)
        a.step();
    a.removeWater(std::vector<std::size_t>{9}); // initially particle 10: 3 went before it
    EXPECT_EQ(a.removedWater(), (std::vector<std::uint32_t>{3, 10}));
    for (int k = 0; k < 30; ++k)
        a.step();
    const MpsState s = a.exportState();
    EXPECT_EQ(s.removedWater, (std::vector<std::uint32_t>{3, 10}));
    MpsSolver b = makeSolver(scene);
    b.importState(s);
    EXPECT_EQ(b.removedWater(), s.removedWater);
    expectSameParticles(a.particles(), b.particles());
    stepBoth(a, b, 60);
    expectSameParticles(a.particles(), b.particles());

    // A solver that removed other water does not take the state.
    MpsSolver c = makeSolver(scene);
    c.removeWater(std::vector<std::size_t>{4});
    try {
        c.importState(s);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("removed different water"), std::string::npos)
            << e.what();
    }
}

TEST(MpsState, RemoveWaterRefusesFixedRepeatedOrAllTheWater) {
    const Scene scene = sceneFile("surging_small.json");
    MpsSolver a = makeSolver(scene);
    const std::size_t water = a.particles().count(ParticleKind::Water);
    const auto message = [&](std::vector<std::size_t> gone) -> std::string {
        try {
            a.removeWater(gone);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(message({water}).find("is not water"), std::string::npos);
    EXPECT_NE(message({a.particles().size()}).find("is not water"), std::string::npos);
    EXPECT_NE(message({2, 2}).find("twice"), std::string::npos);
    std::vector<std::size_t> all(water);
    for (std::size_t i = 0; i < water; ++i)
        all[i] = i;
    EXPECT_NE(message(all).find("no water would remain"), std::string::npos);
    EXPECT_EQ(a.particles().count(ParticleKind::Water), water)
        << "a refused removal changes nothing";
    EXPECT_TRUE(a.removedWater().empty());
    EXPECT_NO_THROW(a.step());
}
