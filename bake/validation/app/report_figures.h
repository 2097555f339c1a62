#pragma once
// swell-validate's reports: how a figure and a run's cost go into a check's JSON report.

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"

namespace swell::bake {

/// A figure as JSON: null where the run could not measure it (NaN).
nlohmann::json finiteOrNull(double v);

/// Solver time per step and particle (µs), 0 for a run that took no step.
double usPerParticleStep(double seconds, long steps, std::size_t particles);

/// A wave check's cost in its report: steps, PPE iterations, solver time, and that time per
/// step and particle.
void addRunCost(nlohmann::json& out, const GaugeRecords& r, std::size_t particles);

/// What every wave check's report says of its run: the gauges' x (m), the particles, the water
/// particles and the outcome.
void addGaugeRun(nlohmann::json& out, const GaugeRecords& r, const std::vector<double>& gauges);

/// The head of a wave's report: the scene, l0, the still depth, the wave height and their ratio.
nlohmann::json waveReportHead(const Scene& scene, double depth, double height);

} // namespace swell::bake
