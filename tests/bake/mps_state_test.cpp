// MpsSolver::exportState / importState: a solver that imports a state continues bit for bit
// as the solver that exported it (piston wall, a particle moved between steps), and a
// state of other particles is refused.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "expect_same_particles.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/scene.h"

using namespace swell::bake;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

Scene sceneFile(const char* name) {
    return loadScene(kScenes / name);
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
    for (int k = 0; k < 60; ++k) {
        a.step();
        b.step();
    }
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
