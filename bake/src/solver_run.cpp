#include "swell/bake/solver_run.h"

#include <utility>

#include "swell/bake/error.h"

namespace swell::bake {

std::string runSteps(MpsSolver& solver, StepTotals& totals,
                     const std::function<bool(const MpsSolver&)>& done,
                     const std::function<void(const StepStats&)>& afterStep) {
    try {
        while (!done(solver)) {
            const StepStats& s = solver.step();
            totals.add(s);
            if (afterStep)
                afterStep(s);
        }
    } catch (const DivergenceError& e) {
        return std::string("stopped: ") + e.what();
    }
    return kStable;
}

std::function<bool(const MpsSolver&)> untilTime(double tEnd) {
    return [tEnd](const MpsSolver& solver) { return solver.time() >= tEnd - 1e-9; };
}

GaugeRecords recordGauges(MpsSolver& solver, const ProbeParams& probe, double tEnd) {
    GaugeRecords r;
    r.elevations.resize(probe.gauges.size());
    const auto sample = [&] {
        const ProbeSample s = sampleProbes(solver.particles(), solver.time(), probe);
        r.times.push_back(s.time);
        for (std::size_t g = 0; g < r.elevations.size(); ++g)
            r.elevations[g].push_back(s.elevations[g]);
    };
    sample();
    StepTotals totals;
    r.outcome = runSteps(solver, totals, untilTime(tEnd), [&](const StepStats&) { sample(); });
    r.steps = totals.steps;
    r.ppeIterationsMean = totals.ppeIterationsMean();
    r.solverSeconds = totals.seconds;
    return r;
}

GaugeRecords recordGauges(const Scene& scene, double stillWaterLevel, std::vector<double> gauges) {
    MpsSolver solver = makeSolver(scene);
    const std::size_t particles = solver.particles().size();
    const std::size_t water = solver.particles().count(ParticleKind::Water);
    const ProbeParams probe = probeParamsFor(solver, scene, stillWaterLevel, std::move(gauges));
    GaugeRecords r = recordGauges(solver, probe, scene.run.endTime);
    r.particles = particles;
    r.water = water;
    return r;
}

ProbeParams probeParamsFor(const MpsSolver& solver, const Scene& scene, double stillWaterLevel,
                           std::vector<double> gauges) {
    ProbeParams p;
    p.n0 = solver.densityConstants().n0;
    p.splashRatio = scene.output.splashRatio;
    p.spacing = scene.geometry.particleSpacing;
    p.stillWaterLevel = stillWaterLevel;
    p.gauges = std::move(gauges);
    return p;
}

} // namespace swell::bake
