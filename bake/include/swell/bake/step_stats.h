#pragma once
#include <array>
#include <cstddef>
#include <string_view>

namespace swell::bake {

/// The named phases of one MPS step, in order (STYLE.md #4).
enum class Phase : int {
    Neighbors,   ///< cell grid counting sort + neighbour lists (only when the skin is used up)
    Explicit,    ///< gravity + viscosity, predict u* and r*, collisions
    Density,     ///< number density n*, free-surface flags, PPE source
    PpeAssembly, ///< sparse PPE matrix
    PpeSolve,    ///< preconditioned conjugate gradient
    Correction,  ///< minimum-pressure gradient, velocity/position correction, checks
};
inline constexpr std::size_t kPhaseCount = 6;
std::string_view toString(Phase phase);

/// What one step did; returned by MpsSolver::step().
struct StepStats {
    long step = 0;            ///< index of the step just taken (1 = first)
    double time = 0.0;        ///< simulated time after the step (s)
    double dt = 0.0;          ///< time step used (s), all its sub-steps together
    int substeps = 1;         ///< sub-steps the step was taken in (TimeStepParams::substepCourant)
    int ppeIterations = 0;    ///< PCG iterations, summed over the sub-steps
    double ppeResidual = 0.0; ///< final relative residual |b - Ax| / |b| (largest sub-step)
    std::size_t ppeUnknowns = 0;
    double maxSpeed = 0.0;            ///< max |u| of water after the pressure correction (m/s)
    double courant = 0.0;             ///< max |u| dt / l0 of the sub-steps, their own dt (-)
    std::size_t outOfBounds = 0;      ///< particles outside the domain (a non-zero count throws)
    std::size_t surfaceParticles = 0; ///< water + wall flagged free surface (p = 0)
    std::size_t collisions = 0;       ///< colliding pairs handled, summed over the sub-steps
    int neighborRebuilds = 0;         ///< times the neighbour lists were rebuilt (0-2 per sub-step)
    std::array<double, kPhaseCount> phaseSeconds{}; ///< wall time per Phase (s)

    double seconds() const {
        double s = 0.0;
        for (double t : phaseSeconds)
            s += t;
        return s;
    }
};

/// Totals over the steps of a run, for the reports of validation runs: steps taken, PCG
/// iterations and the solver's wall time.
struct StepTotals {
    long steps = 0;
    double ppeIterations = 0.0;
    double seconds = 0.0;

    void add(const StepStats& s) {
        ++steps;
        ppeIterations += s.ppeIterations;
        seconds += s.seconds();
    }
    double ppeIterationsMean() const {
        return steps > 0 ? ppeIterations / static_cast<double>(steps) : 0.0;
    }
};

} // namespace swell::bake
