#pragma once
// A dam that breaks onto a wet bed, against Stoker's solution of the shallow-water equations
// (docs/validation.md, Dam break onto a wet bed). Still water of depth h0 behind a gate at x0 and a
// thin layer of depth h1 in front of it: when the gate goes, a rarefaction runs back into the
// reservoir and a bore runs forward over the layer. Stoker (1957, "Water Waves", Sec. 10.8) solves
// the shallow-water equations for this: the depth is self-similar in (x - x0) / t, the bore's speed
// and the depth behind it follow from mass and momentum across it (Rankine-Hugoniot) and the
// Riemann invariant through the fan. No solver setting was chosen on this flow: a held-out case for
// the whole water column in motion, where the dry dam break tests a thin front. The theory is the
// long-wave limit, so records are compared once the flow is long against its depth
// (kStokerFromTimes). runWetDamBreak is the run swell-validate wet-dam-break reports and the
// CI-resolution test bounds. No I/O.

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"

namespace swell::bake::validation {

/// The records are compared from t >= kStokerFromTimes sqrt(h0 / g): before that the water's
/// vertical acceleration, which the shallow-water equations leave out, is of the order of g
/// (the gate's first instants; Stansby, Chegini & Barnes 1998 show the early jet that pushes
/// over the layer), and by then the fan is 5 depths long. The constant was fixed before any run
/// of this check, not fitted to a result. The same time after theory's bore passes a gauge
/// lets its breaking front go by before the depth behind it is read.
inline constexpr double kStokerFromTimes = 5.0;

/// Stoker's wet-bed dam break: still water h0 for x < x0 and h1 for x > x0 at t = 0, flat
/// frictionless bed, gravity g. Regions along xi = (x - x0) / t: the reservoir at rest
/// (xi <= -c0), the fan h = (2 c0 - xi)^2 / (9 g) (-c0 < xi <= u2 - c2), the state (h2, u2)
/// (u2 - c2 < xi <= S), the layer at rest (xi > S).
struct StokerDamBreak {
    double h0 = 0.0, h1 = 0.0, gravity = 0.0; ///< (m, m, m/s^2)
    double c0 = 0.0;        ///< sqrt(g h0) (m/s): the speed the fan's head runs back at
    double boreSpeed = 0.0; ///< S (m/s)
    double h2 = 0.0;        ///< depth between the fan and the bore (m)
    double u2 = 0.0;        ///< velocity there (m/s)
    double c2 = 0.0;        ///< sqrt(g h2) (m/s)

    /// Depth (m) at x - x0 = dx (m) and time t (s); at t <= 0 the initial step.
    double depth(double dx, double t) const;
    /// True where the solution at (dx, t > 0) is the state (h2, u2).
    bool behindBore(double dx, double t) const;
    /// kStokerFromTimes sqrt(h0 / g) (s): when the records start to be compared, and how long
    /// after theory's bore a gauge's depth behind it is read.
    double comparedFrom() const;
};

/// Solves for the bore (bisection on the Riemann invariant u2 + 2 c2 = 2 c0, to round-off).
/// Throws std::invalid_argument unless 0 < h1 < h0 and g > 0, all finite.
StokerDamBreak stokerDamBreak(double h0, double h1, double gravity);

/// One gauge's record against the theory.
struct WetDamBreakGauge {
    double x = 0.0;    ///< (m)
    double from = 0.0; ///< the compared window [from, until] (s)
    double until = 0.0;
    double meanAbsErrorOverH0 = 0.0;    ///< mean |h - h_Stoker| / h0 over the window
    double meanSignedErrorOverH0 = 0.0; ///< mean (h - h_Stoker) / h0 over the window
    /// When the depth first rises through (h1 + h2) / 2, interpolated (s); NaN at or upstream
    /// of the gate, or where it does not rise before `until`.
    double boreArrival = 0.0;
    double boreArrivalTheory = 0.0; ///< (x - x0) / S (s); NaN upstream of the gate
    /// The mean depth over h2 where theory is at (h2, u2) and its bore passed at least
    /// kStokerFromTimes sqrt(h0 / g) before; NaN without such a sample.
    double plateauDepthOverTheory = 0.0;
};

/// What the gauges say about the flow.
struct WetDamBreakCheck {
    std::vector<WetDamBreakGauge> gauges; ///< in the order given
    /// Least-squares slope of x against boreArrival over the gauges whose theoretical arrival
    /// is inside their window (m/s), and its ratio to S, minus 1.
    double boreSpeed = 0.0;
    double boreSpeedError = 0.0;
    std::size_t boreGauges = 0; ///< how many gauges the speed was fitted over
    /// Mean of the gauges' plateauDepthOverTheory that exist, minus 1; NaN if none.
    double plateauDepthError = 0.0;
    double meanAbsErrorOverH0Worst = 0.0; ///< the largest meanAbsErrorOverH0
};

/// Where each gauge's record is compared: from kStokerFromTimes sqrt(h0 / g) until `tEnd` or
/// the first time theory allows a wave reflected at the back wall xb (the fan's head reaching
/// it at (x0 - xb) / c0, then coming back no faster than max(c0, u2 + c2)) or at the far wall
/// x1 (the bore reaching it at (x1 - x0) / S and coming back as the bore that brings (h2, u2) to
/// rest) to reach it. Throws std::invalid_argument for a gauge outside (xb, x1), or one whose
/// window would close before it opens.
std::vector<std::pair<double, double>> stokerWindows(const StokerDamBreak& theory, double xb,
                                                     double x0, double x1, double tEnd,
                                                     std::span<const double> gauges);

/// Compares the depth records (m, at `times`, increasing) of gauges at `gauges` (m) with
/// `theory` for a gate at x0 (m) inside `windows` (stokerWindows). Throws
/// std::invalid_argument for mismatched sizes, a window with no sample, a dry sample (NaN)
/// inside a window, or fewer than two gauges that see the bore inside their window.
WetDamBreakCheck analyseWetDamBreak(const StokerDamBreak& theory, double x0,
                                    std::span<const double> gauges, std::span<const double> times,
                                    const std::vector<std::vector<double>>& depths,
                                    std::span<const std::pair<double, double>> windows);

/// One run of a wet-bed dam-break scene: the records (depths at the gauges, from the bed) and
/// their analysis.
struct WetDamBreakReport : GaugeRecords {
    StokerDamBreak theory;
    double gate = 0.0;          ///< x0 (m)
    std::vector<double> gauges; ///< output.gauges (m)
    std::vector<std::pair<double, double>> windows;
    WetDamBreakCheck check; ///< when stable
};

/// Runs `scene` to run.end_time: a tank whose water is two rectangles on its bed, the
/// reservoir from the back wall to the gate and a lower layer from the gate to the front wall,
/// no piston and no recycling, two or more output.gauges. Throws SceneError naming the key for
/// any other scene, std::runtime_error for records its analysis cannot read; a diverging run
/// returns its outcome.
WetDamBreakReport runWetDamBreak(const Scene& scene);

} // namespace swell::bake::validation
