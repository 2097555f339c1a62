#pragma once
// A solitary wave along a flat bed against theory (docs/validation.md, Solitary wave). A piston's
// single stroke (Goring 1978, piston.kind "solitary") makes a wave of height H in still water of
// depth h that, in theory, travels without changing: its celerity c = sqrt(g (h + A)) for a crest A
// above still water (Rayleigh 1876; Laitone's second order differs by 0.13 % at A / h = 0.2), its
// shape eta = A sech^2(k (x - c t)), k = sqrt(3 A / (4 h^3)) (Boussinesq 1872), and its height kept
// but for the laminar friction of the bed (Keulegan 1948: of the order of 1 % over 20 h at
// laboratory scale). Gauges along the tank record it; each record's incident crest says how fast
// the wave runs, how much height it loses and whether it keeps its width: a nonlinear wave, not
// periodic, that no setting of the solver was chosen on. runSolitaryWave is the run swell-validate
// solitary-wave reports and the CI-resolution test bounds. No I/O.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "swell/bake/piston_motion.h"
#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"

namespace swell::bake::validation {

/// One gauge's incident crest.
struct SolitaryCrest {
    double x = 0.0;          ///< the gauge (m)
    double stillLevel = 0.0; ///< the record's mean over its still window (m)
    double time = 0.0;       ///< when the crest passes (s): the parabola's vertex
    /// A, the crest's height above the still level (m): the top of a least-squares parabola
    /// through the samples within an eighth of the crest's theoretical width of the highest.
    double amplitude = 0.0;
    /// The time the record stays above A / 2 (s), against Boussinesq's shape for a crest of
    /// that A: 2 acosh(sqrt 2) / (k(A) c(A)); ratio - 1.
    double widthError = 0.0;
};

/// What the gauges' records say about the wave.
struct SolitaryWaveCheck {
    std::vector<SolitaryCrest> crests; ///< per gauge, in order of x
    /// Least-squares slope of the gauges' x against their crest times (m/s).
    double celerity = 0.0;
    /// celerity / sqrt(g (h + mean A)) - 1: the wave that exists against its theory.
    double celerityError = 0.0;
    /// The first gauge's A / H: how much of the stroke's wave the run made.
    double firstAmplitudeOverHeight = 0.0;
    /// 1 - A(last gauge) / A(first gauge): the height lost between them.
    double decayTotal = 0.0;
    double meanWidthError = 0.0; ///< mean of the crests' width errors
};

/// Where one gauge's record is read (s), from theory's crest path x = x0 + c t - 4 / k
/// (piston_motion.h) and its front 3 / (k c) ahead of the crest (eta / A = sech^2(3) = 1 %).
struct CrestWindow {
    /// The record's still level is its mean over [stillFrom, stillTo]: before the front
    /// arrives, after the first half of that time, when the settling of the first steps is
    /// over. The lattice's top sits a fraction of a spacing off the nominal level, and the
    /// crest is measured from the level the gauge reads.
    double stillFrom = 0.0, stillTo = 0.0;
    /// The crest is read before this time: the front of the wave reflected at the far wall x1
    /// (which its crest reaches at (x1 - x0 + 4 / k) / c) returning to the gauge.
    double until = 0.0;
};

/// Windows for gauges at `gauges` (m) of a solitary piston whose rest face is at x0 (m) in a
/// tank whose far wall is at x1 (m). Throws std::invalid_argument for a gauge outside
/// (x0, x1), or one so near the paddle that its still window is empty.
std::vector<CrestWindow> solitaryCrestWindows(const PistonParams& piston, double x0, double x1,
                                              std::span<const double> gauges);

/// Reads the incident crest of each gauge's record eta(t) (m from the still-water level; t
/// increasing) inside its window. Throws std::invalid_argument for mismatched sizes, fewer than
/// two gauges, a dry sample (NaN), a record whose highest point in its window is at either
/// end of it (no crest passed), or that never falls below half its crest on one side.
SolitaryWaveCheck analyseSolitaryWave(const PistonParams& piston, std::span<const double> gauges,
                                      std::span<const double> times,
                                      const std::vector<std::vector<double>>& elevations,
                                      std::span<const CrestWindow> windows);

/// One run of a solitary-wave scene: the records (outcome, times, elevations at the gauges,
/// steps, PPE iterations, solver time) and their analysis.
struct SolitaryWaveReport : GaugeRecords {
    SolitaryWaveShape theory;         ///< of the stroke's height H
    double height = 0.0;              ///< H (m)
    double depth = 0.0;               ///< h (m)
    double stroke = 0.0;              ///< the piston's full travel (m)
    std::vector<double> gauges;       ///< output.gauges (m)
    std::vector<CrestWindow> windows; ///< per gauge (solitaryCrestWindows)
    SolitaryWaveCheck check;          ///< when stable
};

/// Runs `scene` (a tank whose back wall is a solitary piston, two or more output.gauges) to
/// run.end_time. Throws SceneError naming the key for a scene without a solitary piston or
/// with fewer than two gauges, std::runtime_error for a record its analysis cannot read; a
/// diverging run returns its outcome.
SolitaryWaveReport runSolitaryWave(const Scene& scene);

} // namespace swell::bake::validation
