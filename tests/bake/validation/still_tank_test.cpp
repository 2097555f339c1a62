// The still-tank run (swell/bake/still_tank.h) that swell-validate still-tank reports and the
// CI-resolution hydrostatics tests (validation_test.cpp) bound: what it measures and where,
// on short runs. The long runs are validation_test's.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/bake/validation/still_tank.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

Scene smallTank(std::vector<std::string> overrides = {}) {
    return loadScene(kScenes / "still_tank_small.json", overrides);
}

} // namespace

TEST(StillTank, MeasuresAfterSettlingAndNamesTheFastestWaterParticle) {
    const Scene scene = smallTank();
    long calls = 0;
    const StillTankReport r =
        runStillTank(scene, 0.2, 400, [&](const MpsSolver&, const StepStats&) { ++calls; });
    EXPECT_EQ(r.outcome, "stable");
    EXPECT_EQ(r.steps, 400);
    EXPECT_EQ(calls, 400);
    EXPECT_NEAR(r.time, 0.4, 1e-9);
    const MpsSolver fresh = makeSolver(scene);
    EXPECT_EQ(r.particles, fresh.particles().size());
    EXPECT_EQ(r.water, fresh.particles().count(ParticleKind::Water));
    // The middle half of the 0.2 m bed at l0 = 0.01 m: the 10 wall particles under x in (0.05,
    // 0.15).
    EXPECT_EQ(r.gaugeParticles, 10u);
    EXPECT_NEAR(r.rhoGH, 1000.0 * 9.81 * 0.1, 1e-9);
    EXPECT_NEAR(r.bottomPressureRatio, 1.0, 0.1); // the water has barely started to settle
    EXPECT_EQ(r.escaped, 0u);
    EXPECT_GT(r.ppeIterationsMean, 0.0);
    EXPECT_GT(r.solverSeconds, 0.0);

    ASSERT_GT(r.maxSpeed, 0.0);
    EXPECT_NEAR(r.maxSpeedOverSqrtGH, r.maxSpeed / std::sqrt(9.81 * 0.1), 1e-12);
    EXPECT_LE(r.meanSpeedOverSqrtGH, r.maxSpeedOverSqrtGH);
    EXPECT_GE(r.maxDriftSpeedOverSqrtGH, 0.0);
    const FastestParticle& f = r.fastest;
    EXPECT_EQ(fresh.particles().kind.at(f.index), ParticleKind::Water);
    EXPECT_GE(f.time, 0.2);
    EXPECT_LE(f.time, 0.4 + 1e-9);
    // The maximum is that particle's velocity at the end of the step that set it; the step's
    // statistics, taken before the shift's damping, never read less.
    EXPECT_DOUBLE_EQ(std::hypot(f.u, f.v), r.maxSpeed);
    EXPECT_GE(r.maxSpeedBeforeShift, r.maxSpeed * (1.0 - 1e-12)); // sqrt and hypot round apart
    EXPECT_NEAR(r.maxSpeedBeforeShiftOverSqrtGH, r.maxSpeedBeforeShift / std::sqrt(9.81 * 0.1),
                1e-12);
    EXPECT_GE(f.depthOverL0, 0.0);
    EXPECT_LT(f.depthOverL0, 10.5); // 10 rows of water
    EXPECT_GE(f.wallDistanceOverL0, 0.0);
    EXPECT_LE(f.wallDistanceOverL0, 10.0); // half the 0.2 m tank
    EXPECT_NEAR(f.wallDistanceOverL0 * 0.01, std::min(f.x, 0.2 - f.x), 1e-12);
}

TEST(StillTank, TheMaximumSpeedIsTheStateAtTheEndOfAStep) {
    // The damping against the shift (solver.shift_damping) takes part of a surface particle's
    // velocity after the pressure correction, where the step's statistics read it. The report's
    // maximum is what the particles carry at the end of the step: with the damping it reads less
    // than the statistics in this run, without it the same.
    const StillTankReport damped = runStillTank(smallTank(), 1.0, 3000);
    EXPECT_EQ(damped.outcome, "stable");
    EXPECT_GT(damped.maxSpeed, 0.0);
    EXPECT_LT(damped.maxSpeed, damped.maxSpeedBeforeShift);
    const StillTankReport undamped =
        runStillTank(smallTank({"solver.shift_damping=false"}), 1.0, 3000);
    EXPECT_EQ(undamped.outcome, "stable");
    EXPECT_GT(undamped.maxSpeed, 0.0);
    EXPECT_NEAR(undamped.maxSpeed, undamped.maxSpeedBeforeShift, 1e-12 * undamped.maxSpeed);
    EXPECT_DOUBLE_EQ(std::hypot(undamped.fastest.u, undamped.fastest.v), undamped.maxSpeed);
}

TEST(StillTank, NothingMeasuredBeforeTheSettlingTime) {
    const StillTankReport r = runStillTank(smallTank(), 1.0, 50);
    EXPECT_EQ(r.outcome, "stable");
    EXPECT_EQ(r.steps, 50);
    EXPECT_EQ(r.maxSpeed, 0.0);
    EXPECT_EQ(r.bottomPressureMean, 0.0);
    EXPECT_EQ(r.maxExcursionOverL0, 0.0);
}

TEST(StillTank, AStoppedRunReportsTheDetectorsMessage) {
    // A Courant limit far below what gravity gives the water in its first steps.
    const StillTankReport r = runStillTank(
        smallTank({"solver.courant_limit=0.0002", "solver.expected_speed=0.001"}), 0.0, 200);
    EXPECT_EQ(r.outcome.rfind("stopped: ", 0), 0u) << r.outcome;
    EXPECT_NE(r.outcome.find("courant_limit"), std::string::npos) << r.outcome;
    EXPECT_LT(r.steps, 200);
}

TEST(StillTank, RefusesASceneWithoutATank) {
    Scene scene = smallTank();
    scene.geometry.tank.reset();
    try {
        runStillTank(scene, 0.0, 1);
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("geometry.tank"), std::string::npos) << e.what();
    }
}
