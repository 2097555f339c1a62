#include "swell/bake/lobovsky_run.h"

#include <cmath>

#include "swell/bake/error.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/probes.h"

namespace swell::bake {

LobovskyRun runLobovsky(const Scene& scene, double tEnd) {
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the Lobovsky check needs a tank");
    const Box tank = *scene.geometry.tank;
    const std::span<const LevelGauge> gauges = lobovskyH300Gauges();
    MpsSolver solver = makeSolver(scene);
    ProbeParams probe;
    probe.n0 = solver.densityConstants().n0;
    probe.splashRatio = scene.output.splashRatio;
    probe.spacing = scene.geometry.particleSpacing;
    probe.stillWaterLevel = tank.y0; // heights from the tank floor
    for (const LevelGauge& g : gauges)
        probe.gauges.push_back(tank.x0 + g.x); // x from the upstream wall
    LobovskyRun run;
    run.H = scene.geometry.water.at(0).height();
    run.particles = solver.particles().size();
    run.water = solver.particles().count(ParticleKind::Water);
    run.top.resize(gauges.size());
    const auto sample = [&] {
        const ProbeSample s = sampleProbes(solver.particles(), solver.time(), probe);
        for (std::size_t g = 0; g < gauges.size(); ++g) {
            const double h = s.elevations[g];
            run.top[g].push_back({s.time, std::isnan(h) ? 0.0 : h}); // NaN: dry gauge
        }
    };
    sample();
    try {
        while (solver.time() < tEnd - 1e-9) {
            run.totals.add(solver.step());
            sample();
        }
        run.outcome = "stable";
    } catch (const DivergenceError& e) {
        run.outcome = std::string("stopped: ") + e.what();
    }
    return run;
}

} // namespace swell::bake
