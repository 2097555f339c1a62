#pragma once
// A solitary wave shoaling on a plane beach until it breaks, against the experiment of Grilli
// et al. (1994) (grilli1994.h; docs/validation.md, Shoaling). A piston's solitary stroke (Goring
// 1978) of height H / h0 = 0.2 runs over a flat bed onto a 1:34.7 slope (geometry.bed); six
// gauges at the experiment's places record it: g0 on the flat bed, the incident wave, and
// g1-g9 on the slope, where the wave steepens and grows to 0.34 h0 in 0.25 h0 of water and
// breaks. The comparison follows the experiment's convention: the run's clock is aligned on
// g0's crest, then each slope gauge's record is compared with the run over the record's span.
// Nonlinear shoaling, a bed that is not flat and breaking: a case no solver setting was chosen
// on. runShoaling is the run swell-validate shoaling reports and the CI-resolution test
// bounds. No I/O.

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/grilli1994.h"

namespace swell::bake::validation {

/// A crest is the top of the parabola through the samples within this many sqrt(h0 / g) of a
/// record's highest sample, and at least one more on each side (parabolaTop): about a tenth of
/// the incident crest's half-height duration, and the width of g9's breaking crest in the
/// experiment.
inline constexpr double kShoalingCrestHalfWindow = 0.3;

/// One gauge: the run against the record, in the experiment's units (h0, sqrt(h0 / g)).
struct ShoalingGaugeError {
    std::string name;
    double x = 0.0;               ///< the gauge in the scene (m; runShoaling sets it)
    double crest = 0.0;           ///< the run's crest / h0 (above its still level)
    double crestRecord = 0.0;     ///< the record's crest / h0
    double crestTime = 0.0;       ///< the run's crest, on the experiment's clock
    double crestTimeRecord = 0.0; ///< the record's
    /// The run's crest over its g0 crest, and the record's over the record's g0 crest: how much
    /// the wave grew from the flat bed, whatever height the paddle made.
    double amplification = 0.0;
    double amplificationRecord = 0.0;
    /// Mean |eta - eta_record| / h0 and mean (eta - eta_record) / h0 over the record's span,
    /// each sample weighted by the time it stands for (the digitised samples are uneven).
    double meanAbsError = 0.0;
    double meanSignedError = 0.0;
    double from = 0.0, until = 0.0; ///< the record's span, on the experiment's clock
    /// The wave's shape, in sqrt(h0 / g): from where its front first stands at half the crest
    /// to the crest (rise), and from the crest to where its back falls below half of it
    /// (fall), the run's and the record's, each within the record's span; NaN where the span
    /// does not reach that far (halfHeightTimes).
    double rise = 0.0, riseRecord = 0.0, fall = 0.0, fallRecord = 0.0;
    /// The integral of eta^2 dt over the record's span, the run's over the record's (each
    /// sample weighted as in the mean errors). At one depth the linear long-wave energy flux
    /// through the gauge is rho g sqrt(g h) times that integral, so 1 reads the record's
    /// energy whatever the wave's shape: a run that is low and broad but near 1 has kept the
    /// wave's energy and lost its shape, one well below 1 has lost energy.
    double energyRatio = 0.0;
    double stillLevel = 0.0; ///< the run's level before the wave (m): its still-window mean
};

/// The times (same units as t) from the front's first sample at or above half of `crest`
/// to `crestTime`, and from `crestTime` to the back's first sample below half of it, each
/// crossing interpolated linearly between samples, searched outward from the crest over the
/// samples with t in [lo, hi]; NaN for a side whose crossing that span does not hold.
std::pair<double, double> halfHeightTimes(std::span<const double> t, std::span<const double> y,
                                          double lo, double hi, double crestTime, double crest);

/// What the gauges say.
struct ShoalingCheck {
    /// Added to the run's time / sqrt(h0 / g) to put it on the experiment's clock: the
    /// record's g0 crest time minus the run's.
    double clockOffset = 0.0;
    std::vector<ShoalingGaugeError> gauges; ///< g0 first, then g1..g9
    double incidentCrestError = 0.0;        ///< g0: crest / crestRecord - 1
    /// Over g1..g9: the crest error crest / crestRecord - 1 of largest size (signed), the
    /// amplification error likewise, and the largest mean |eta - eta_record| / h0.
    double crestErrorWorst = 0.0;
    double amplificationErrorWorst = 0.0;
    double meanAbsErrorWorst = 0.0;
    /// The crest's time from g1 to g9 over the record's, minus 1 (independent of the clock's
    /// alignment and of where g0 is): how fast the wave climbs the beach.
    double travelTimeError = 0.0;
};

/// Compares the run's gauge records with `records` (g0 first): `times` (s, increasing),
/// `elevations` per gauge (m above still water), in water of depth `depth` (m) under gravity
/// `gravity`; each record's still level is its mean over [stillFrom, stillTo] (s), before
/// the wave. Throws std::invalid_argument for mismatched sizes, fewer than two gauges, an
/// empty still window, a dry sample inside a compared span, or a run that does not cover a
/// record's span once aligned.
ShoalingCheck analyseShoaling(std::span<const ShoalingGauge> records, double depth, double gravity,
                              std::span<const double> times,
                              const std::vector<std::vector<double>>& elevations, double stillFrom,
                              double stillTo);

/// The records of grilli1994Gauges as CSV text, "gauge,x_over_h0,t,eta" (t sqrt(g / h0),
/// eta / h0) then one row per sample, g0 first, for plots (swell-validate shoaling --records).
std::string grilli1994RecordsCsv();

/// One run of a shoaling scene: the records and their comparison.
struct ShoalingReport : GaugeRecords {
    double depth = 0.0;                    ///< h0 (m): the still water over the tank's bed
    double height = 0.0;                   ///< H (m): the piston's solitary wave
    double toe = 0.0;                      ///< x of the slope's toe (m): geometry.bed's first point
    double slope = 0.0;                    ///< the bed's first segment, dy / dx
    std::vector<double> gauges;            ///< output.gauges (m)
    double stillFrom = 0.0, stillTo = 0.0; ///< (s)
    ShoalingCheck check;                   ///< when stable
};

/// Runs `scene`: a tank whose back wall is a solitary piston of H / h0 within 1 % of
/// kGrilliHeightOverDepth, whose geometry.bed starts at the tank's bed (the toe) and rises at
/// kGrilliSlope within 1 % past the last gauge, with output.gauges the six gauges of
/// grilli1994Gauges (toe + xOverDepth h0, within l0 / 2), run long enough for g9's record.
/// Throws SceneError naming the key where the scene is not that, std::runtime_error for a
/// record the comparison cannot read; a diverging run returns its outcome.
ShoalingReport runShoaling(const Scene& scene);

} // namespace swell::bake::validation
