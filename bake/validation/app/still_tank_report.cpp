// swell-validate still-tank: the run's hydrostatics and the water's speeds at rest.
#include "case_reports.h"

#include <cmath>
#include <cstdio>

#include "swell/bake/validation/still_tank.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

json stillTank(const Scene& scene, double settle, long steps, long trace) {
    StillTankStep onStep;
    if (trace > 0) {
        // Called only once runStillTank has checked that the scene has a tank.
        onStep = [trace, &scene](const MpsSolver& solver, const StepStats& s) {
            if (s.step % trace != 0)
                return;
            const FastestParticle f =
                fastestWaterParticle(solver, *scene.geometry.tank, scene.geometry.particleSpacing);
            std::fprintf(
                stderr,
                "step %ld t %.3f max|u| %.4f (particle %zu at %.4f, %.4f n/n0 %.3f; before the "
                "shift %.4f) ppe %d surface %zu collisions %zu\n",
                s.step, s.time, std::hypot(f.u, f.v), f.index, f.x, f.y,
                solver.particles().n[f.index] / solver.densityConstants().n0, s.maxSpeed,
                s.ppeIterations, s.surfaceParticles, s.collisions);
        };
    }
    const StillTankReport r = runStillTank(scene, settle, steps, onStep);
    json out{{"scene", scene.name},
             {"H", scene.geometry.water.at(0).height()},
             {"l0", scene.geometry.particleSpacing},
             {"particles", r.particles},
             {"water", r.water},
             {"gauge_particles", r.gaugeParticles},
             {"outcome", r.outcome},
             {"steps", r.steps},
             {"time", r.time},
             {"bottom_pressure_mean", r.bottomPressureMean},
             {"rho_g_H", r.rhoGH},
             {"bottom_pressure_ratio", r.bottomPressureRatio},
             {"max_speed_after_settle", r.maxSpeed},
             {"max_speed_over_sqrt_gH", r.maxSpeedOverSqrtGH},
             {"max_speed_before_shift_over_sqrt_gH", r.maxSpeedBeforeShiftOverSqrtGH},
             {"mean_speed_over_sqrt_gH", r.meanSpeedOverSqrtGH},
             {"max_excursion_over_l0", r.maxExcursionOverL0},
             {"max_drift_speed_over_sqrt_gH", r.maxDriftSpeedOverSqrtGH},
             {"escaped", r.escaped},
             {"ppe_iterations_mean", r.ppeIterationsMean},
             {"solver_seconds", r.solverSeconds}};
    if (r.maxSpeed > 0.0) {
        const FastestParticle& f = r.fastest;
        out["fastest_after_settle"] = {{"particle", f.index},
                                       {"time", f.time},
                                       {"x", f.x},
                                       {"y", f.y},
                                       {"u", f.u},
                                       {"v", f.v},
                                       {"free_surface", f.freeSurface},
                                       {"depth_below_top_over_l0", f.depthOverL0},
                                       {"wall_distance_over_l0", f.wallDistanceOverL0}};
    }
    return out;
}

} // namespace swell::bake
