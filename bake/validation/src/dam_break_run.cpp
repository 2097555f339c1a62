#include "swell/bake/validation/dam_break_run.h"

#include <cmath>

#include "swell/bake/error.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/solver_run.h"

namespace swell::bake::validation {

DamBreakRun runDamBreak(const Scene& scene, double tEnd) {
    if (scene.geometry.water.empty())
        throw SceneError("geometry.water", "the dam-break check needs a water column");
    const Box column = scene.geometry.water.front();
    DamBreakRun run;
    run.a = column.width();
    const double tScale = std::sqrt(2.0 * scene.physics.gravity / run.a); // T = t sqrt(2 g / a)
    MpsSolver solver = makeSolver(scene);
    run.particles = solver.particles().size();
    run.water = solver.particles().count(ParticleKind::Water);
    const double n0 = solver.densityConstants().n0;
    const auto sample = [&] {
        run.series.push_back(
            {solver.time() * tScale,
             surgeFront(solver.particles(), n0, scene.output.splashRatio, column.x0) / run.a});
    };
    sample();
    run.outcome = runSteps(
        solver, run.totals, [&](const MpsSolver& s) { return s.time() * tScale >= tEnd; },
        [&](const StepStats&) { sample(); });
    return run;
}

} // namespace swell::bake::validation
