#pragma once
// The Martin & Moyce (1952) dam break as a run (docs/validation.md, Dam break): the scene's first
// water rectangle, a column of width a, collapses, and after every step the surge front is read.
// One run, as swell-validate dam-break reports it and as the CI-resolution tests
// (tests/bake/validation/validation_test.cpp) bound it. No I/O.

#include <cstddef>
#include <string>
#include <vector>

#include "swell/bake/scene.h"
#include "swell/bake/step_stats.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {

struct DamBreakRun {
    /// "stable", or "stopped: " and the divergence detector's message.
    std::string outcome;
    double a = 0.0; ///< the column's width (m): the scene's first water rectangle
    std::size_t particles = 0;
    std::size_t water = 0;
    StepTotals totals;
    /// At T = 0 and after every step: T = t sqrt(2 g / a) and Z = the surge front (surgeFront,
    /// from the column's back face) / a, what the check compares with the records.
    std::vector<FrontPoint> series;
};

/// Runs `scene` until T = t sqrt(2 g / a) reaches tEnd, or until the divergence detector stops
/// it. Throws SceneError for a scene without water.
DamBreakRun runDamBreak(const Scene& scene, double tEnd);

} // namespace swell::bake::validation
