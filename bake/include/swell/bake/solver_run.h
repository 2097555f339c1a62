#pragma once
// A solver run as every check steps it (still tank, standing wave, dam breaks): the
// step loop that turns the divergence detector's stop into the run's outcome, and the probes'
// settings read from the solver's own constants. No I/O.

#include <functional>
#include <string>
#include <vector>

#include "swell/bake/mps_solver.h"
#include "swell/bake/probes.h"
#include "swell/bake/scene.h"
#include "swell/bake/step_stats.h"

namespace swell::bake {

/// What a check's run reports as its outcome when it reached its end.
inline constexpr const char* kStable = "stable";

/// Steps `solver` until `done(solver)` holds (it is asked before every step, the first
/// included), adds every step to `totals` and calls `afterStep` after it. A DivergenceError
/// ends the loop, not the caller: returns "stable", or "stopped: " and the detector's message,
/// which names the step, the time and the particle.
std::string runSteps(MpsSolver& solver, StepTotals& totals,
                     const std::function<bool(const MpsSolver&)>& done,
                     const std::function<void(const StepStats&)>& afterStep = {});

/// `done` for runSteps: the solver's time has reached tEnd (s), to 1e-9 s.
std::function<bool(const MpsSolver&)> untilTime(double tEnd);

/// The probes of a run of `scene` by `solver`: the solver's n0, the scene's splash ratio and
/// particle spacing, elevations from stillWaterLevel (m), gauges at the x given (m).
ProbeParams probeParamsFor(const MpsSolver& solver, const Scene& scene, double stillWaterLevel,
                           std::vector<double> gauges);

/// The surface at a run's gauges, as the wave checks (standing, solitary) read it; their
/// reports extend it.
struct GaugeRecords {
    /// "stable", or "stopped: " and the divergence detector's message (runSteps).
    std::string outcome;
    std::vector<double> times;                   ///< sample times (s), 0 first
    std::vector<std::vector<double>> elevations; ///< per gauge of `probe`, at `times` (m)
    long steps = 0;
    double ppeIterationsMean = 0.0;
    double solverSeconds = 0.0;
    std::size_t particles = 0, water = 0; ///< the run's particles, and of them water
};

/// Samples `probe` (sampleProbes) before the first step and after every step while runSteps
/// takes `solver` to tEnd (s).
GaugeRecords recordGauges(MpsSolver& solver, const ProbeParams& probe, double tEnd);

/// A run of `scene` to its run.end_time (makeSolver) that records its surface at `gauges` (m),
/// elevations from stillWaterLevel (m): the wave checks' run.
GaugeRecords recordGauges(const Scene& scene, double stillWaterLevel, std::vector<double> gauges);

} // namespace swell::bake
