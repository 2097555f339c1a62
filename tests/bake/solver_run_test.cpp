// The step loop of the checks and the probes' settings (swell/bake/solver_run.h), on a small
// dam break: when the loop stops, what it counts, and what a stopped run reports.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "small_scenes.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/probes.h"
#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"

using namespace swell::bake;

using swell::test::smallDamBreak;

TEST(SolverRun, StepsUntilDoneAndCallsAfterEveryStep) {
    MpsSolver solver = makeSolver(smallDamBreak());
    StepTotals totals;
    std::vector<long> seen;
    const std::string outcome = runSteps(solver, totals, untilTime(0.005),
                                         [&](const StepStats& s) { seen.push_back(s.step); });
    EXPECT_EQ(outcome, kStable);
    EXPECT_EQ(totals.steps, 5); // 1 ms steps: the first time at or past 5 ms, not one more
    EXPECT_EQ(seen, (std::vector<long>{1, 2, 3, 4, 5}));
    EXPECT_NEAR(solver.time(), 0.005, 1e-12);
    EXPECT_GT(totals.ppeIterationsMean(), 0.0);
    // Done before the first step: no step at all.
    EXPECT_EQ(runSteps(solver, totals, untilTime(0.005)), kStable);
    EXPECT_EQ(totals.steps, 5);
    // Any predicate: a step count.
    StepTotals counted;
    EXPECT_EQ(runSteps(solver, counted, [&](const MpsSolver&) { return counted.steps >= 3; }),
              kStable);
    EXPECT_EQ(counted.steps, 3);
    EXPECT_NEAR(solver.time(), 0.008, 1e-12);
}

TEST(SolverRun, ADivergingRunEndsTheLoopWithTheDetectorsMessage) {
    Scene scene = smallDamBreak();
    scene.solver.pressure.maxIterations = 1; // the pressure solve cannot converge
    MpsSolver solver = makeSolver(scene);
    StepTotals totals;
    int calls = 0;
    const std::string outcome =
        runSteps(solver, totals, untilTime(0.01), [&](const StepStats&) { ++calls; });
    ASSERT_EQ(outcome.rfind("stopped: ", 0), 0u) << outcome;
    EXPECT_NE(outcome.find("at step 1 ("), std::string::npos) << outcome;
    EXPECT_NE(outcome.find("did not converge"), std::string::npos) << outcome;
    EXPECT_EQ(totals.steps, 0); // the stopped step is not counted, nor reported to afterStep
    EXPECT_EQ(calls, 0);
}

TEST(SolverRun, ProbeParamsComeFromTheSolverAndTheScene) {
    Scene scene = smallDamBreak();
    scene.output.splashRatio = 0.4;
    const MpsSolver solver = makeSolver(scene);
    const ProbeParams p = probeParamsFor(solver, scene, 0.2, {0.05, 0.3});
    EXPECT_EQ(p.n0, solver.densityConstants().n0);
    EXPECT_GT(p.n0, 0.0);
    EXPECT_EQ(p.splashRatio, 0.4);
    EXPECT_EQ(p.spacing, 0.01);
    EXPECT_EQ(p.stillWaterLevel, 0.2);
    EXPECT_EQ(p.gauges, (std::vector<double>{0.05, 0.3}));
}

TEST(SolverRun, RecordGaugesSamplesBeforeTheFirstStepAndAfterEveryStep) {
    const Scene scene = smallDamBreak();
    MpsSolver solver = makeSolver(scene);
    const ProbeParams probe = probeParamsFor(solver, scene, 0.0, {0.02, 0.05});
    const ProbeSample start = sampleProbes(solver.particles(), 0.0, probe);
    const GaugeRecords r = recordGauges(solver, probe, 0.005);
    EXPECT_EQ(r.outcome, kStable);
    EXPECT_EQ(r.steps, 5);
    ASSERT_EQ(r.times.size(), 6u); // t = 0 and after each of the five steps
    EXPECT_EQ(r.times.front(), 0.0);
    EXPECT_NEAR(r.times.back(), 0.005, 1e-12);
    ASSERT_EQ(r.elevations.size(), 2u);
    for (std::size_t g = 0; g < 2; ++g) {
        ASSERT_EQ(r.elevations[g].size(), 6u);
        EXPECT_EQ(r.elevations[g].front(), start.elevations[g]) << g;
        // The same as sampling the solver's state after the run.
        EXPECT_EQ(r.elevations[g].back(),
                  sampleProbes(solver.particles(), solver.time(), probe).elevations[g]);
    }
}
