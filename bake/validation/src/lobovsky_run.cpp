#include "swell/bake/validation/lobovsky_run.h"

#include <cmath>
#include <utility>
#include <vector>

#include "swell/bake/error.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/probes.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/buchner2002.h"

namespace swell::bake::validation {

LobovskyRun runLobovsky(const Scene& scene, double tEnd) {
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the Lobovsky check needs a tank");
    const Box tank = *scene.geometry.tank;
    const std::span<const LevelGauge> gauges = lobovskyH300Gauges();
    MpsSolver solver = makeSolver(scene);
    std::vector<double> gaugeX;
    for (const LevelGauge& g : gauges)
        gaugeX.push_back(tank.x0 + g.x); // x from the upstream wall
    // Heights from the tank floor.
    const ProbeParams probe = probeParamsFor(solver, scene, tank.y0, std::move(gaugeX));
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
    // Sensor P1: the first layer of wall particles behind the downstream wall (x1 < x < x1 + l0)
    // whose centres lie in the sensor's band. Wall particles do not move, so the list holds.
    run.sensorHigh = tank.y0 + kBuchnerP1TopOverH * run.H;
    run.sensorLow = run.sensorHigh - kBuchnerP1HeightOverH * run.H;
    const double l0 = scene.geometry.particleSpacing;
    std::vector<std::size_t> sensor;
    {
        const Particles& p = solver.particles();
        for (std::size_t i = 0; i < p.size(); ++i)
            if (p.kind[i] == ParticleKind::Wall && p.x[i] > tank.x1 && p.x[i] < tank.x1 + l0 &&
                p.y[i] >= run.sensorLow && p.y[i] <= run.sensorHigh)
                sensor.push_back(i);
    }
    run.sensorParticles = sensor.size();
    const auto sampleSensor = [&] {
        double sum = 0.0;
        for (std::size_t i : sensor)
            sum += solver.particles().p[i];
        run.farWallPressure.push_back(
            {solver.time(), sensor.empty() ? 0.0 : sum / static_cast<double>(sensor.size())});
    };
    sample();
    sampleSensor();
    run.outcome = runSteps(solver, run.totals, untilTime(tEnd), [&](const StepStats&) {
        sample();
        sampleSensor();
    });
    return run;
}

} // namespace swell::bake::validation
