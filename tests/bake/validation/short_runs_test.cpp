// The short runs that stand in ctest for the long validation runs tools/validate runs
// (long_runs.txt): each long case's own scene, at its own resolution, for its first steps. They
// catch a case that no longer loads, diverges, loses water or runs away; the figures of the long
// runs are guarded bit for bit by the numerics digest (numerics_version_test.cpp), whose change
// asks for tools/validate.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/mps_solver.h"
#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/step_stats.h"

using namespace swell::bake;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

struct ShortRun {
    const char* scene;
    std::vector<std::string> overrides;
    long steps;
};

void PrintTo(const ShortRun& r, std::ostream* os) {
    *os << r.scene;
}

class ShortValidationRun : public testing::TestWithParam<ShortRun> {};

} // namespace

// `steps` steps of the case: the detector never stops it, no water particle is lost or passes the
// front wall or the bed, and no particle moves faster than the scene's expected speed (the Courant
// check's speed: twice the Ritter front speed of its deepest water, or the speed the scene names).
TEST_P(ShortValidationRun, StaysStableKeepsItsWaterAndItsSpeedBounded) {
    const ShortRun& run = GetParam();
    const Scene scene = loadScene(kScenes / run.scene, run.overrides);
    MpsSolver solver = makeSolver(scene);
    const std::size_t water = solver.particles().count(ParticleKind::Water);
    ASSERT_GT(water, 0u);
    StepTotals totals;
    const std::string outcome =
        runSteps(solver, totals, [&](const MpsSolver& s) { return s.stepCount() >= run.steps; });
    ASSERT_EQ(outcome, kStable);
    EXPECT_EQ(totals.steps, run.steps);
    const Particles& p = solver.particles();
    EXPECT_EQ(p.count(ParticleKind::Water), water);
    const Box& tank = *scene.geometry.tank;
    const double bound = 2.0 * expectedSpeed(scene);
    double fastest = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.kind[i] != ParticleKind::Water)
            continue;
        // The back wall may be a piston; the front wall and the bed stand.
        ASSERT_TRUE(p.x[i] < tank.x1 && p.y[i] > tank.y0)
            << "water particle " << i << " at (" << p.x[i] << ", " << p.y[i] << ")";
        fastest = std::max(fastest, std::hypot(p.vx[i], p.vy[i]));
    }
    RecordProperty("fastest_m_per_s", std::to_string(fastest));
    EXPECT_LT(fastest, bound);
}

INSTANTIATE_TEST_SUITE_P(LongCases, ShortValidationRun,
                         testing::Values(ShortRun{"progressive_wave.json", {}, 100},
                                         ShortRun{"shoaling_small.json", {}, 100},
                                         ShortRun{"wet_dam_break_small.json", {}, 150},
                                         ShortRun{"solitary_wave_small.json", {}, 200},
                                         ShortRun{
                                             "still_tank_small.json", {"solver.dt=0.0005"}, 2000}),
                         [](const testing::TestParamInfo<ShortRun>& info) {
                             std::string name = info.param.scene;
                             name = name.substr(0, name.find('.'));
                             name.erase(std::remove(name.begin(), name.end(), '_'), name.end());
                             return name;
                         });
