#pragma once
// Still-tank hydrostatics (docs/validation.md, Still tank): a tank of water at rest run for a
// number of steps; after a settling time, the bed pressure against rho g H and how much the water
// still moves. One run, measured as swell-validate still-tank reports it and as the CI-resolution
// tests (tests/bake/validation/validation_test.cpp) bound it. No I/O.

#include <cstddef>
#include <functional>
#include <string>

#include "swell/bake/mps_solver.h"
#include "swell/bake/scene.h"

namespace swell::bake::validation {

/// The water particle that was the fastest when the largest speed after settling was reached:
/// where the remaining motion sits.
struct FastestParticle {
    std::size_t index = 0;
    double time = 0.0;               ///< end of the step (s)
    double x = 0.0, y = 0.0;         ///< (m)
    double u = 0.0, v = 0.0;         ///< velocity (m/s)
    bool freeSurface = false;        ///< on the free surface (p = 0) in that step
    double depthOverL0 = 0.0;        ///< below the highest water particle then (l0)
    double wallDistanceOverL0 = 0.0; ///< to the nearer side wall's inner face (l0)
};

/// The water particle with the largest |u| in the solver's state now, and where it is in the
/// tank (its interior box `tank`; l0 the particle spacing).
FastestParticle fastestWaterParticle(const MpsSolver& solver, const Box& tank, double l0);

struct StillTankReport {
    /// "stable", or "stopped: " and the divergence detector's message.
    std::string outcome;
    std::size_t particles = 0;       ///< all of them: water, wall and dummy
    std::size_t water = 0;           ///< water particles
    long steps = 0;                  ///< steps taken
    double time = 0.0;               ///< simulated time at the end (s)
    std::size_t gaugeParticles = 0;  ///< wall particles averaged for the bed pressure
    double bottomPressureMean = 0.0; ///< their pressure, averaged over them and the steps (Pa)
    double rhoGH = 0.0;              ///< rho g H (Pa)
    double bottomPressureRatio = 0.0;
    /// Largest |u| any water particle carries at the end of a step after settling (m/s): the
    /// velocity the next step starts from and a bake writes.
    double maxSpeed = 0.0;
    double maxSpeedOverSqrtGH = 0.0; ///< the same / sqrt(g H)
    /// Largest |u| after settling right after a step's pressure correction, before the shift
    /// and its damping (StepStats::maxSpeed, the speed the Courant number reads). Never below
    /// maxSpeed with the default scheme.
    double maxSpeedBeforeShift = 0.0;
    double maxSpeedBeforeShiftOverSqrtGH = 0.0; ///< the same / sqrt(g H)
    double meanSpeedOverSqrtGH = 0.0;
    /// Each water particle's displacement over consecutive windows of kDriftWindow, divided by
    /// the window (max over particles and windows) / sqrt(g H): how fast the water moves, to
    /// set beside the largest |u| (a particle the shifting keeps in place has the one but not
    /// the other).
    double maxDriftSpeedOverSqrtGH = 0.0;
    double maxExcursionOverL0 = 0.0; ///< farthest a water particle got from its settled place
    std::size_t escaped = 0;         ///< water particles outside the tank at the end
    double ppeIterationsMean = 0.0;
    double solverSeconds = 0.0;
    FastestParticle fastest; ///< the particle with maxSpeed; valid when maxSpeed > 0
};

/// The drift speed's window (s).
inline constexpr double kDriftWindow = 0.1;

/// Called after every step with the solver and the step's statistics (a trace; may be empty).
using StillTankStep = std::function<void(const MpsSolver&, const StepStats&)>;

/// Runs the scene's tank for `steps` steps and measures after `settle` s: the bed pressure on
/// the wall layer touching the water (y = y0 - l0/2) under the middle half of the bed, and the
/// water's speeds and excursions. A step the divergence detector stops ends the run with
/// outcome "stopped: ..." and what was measured until then. Throws SceneError for a scene
/// without a tank or water.
StillTankReport runStillTank(const Scene& scene, double settle, long steps,
                             const StillTankStep& onStep = {});

} // namespace swell::bake::validation
