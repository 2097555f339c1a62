#pragma once
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "swell/bake/particles.h"
#include "swell/bake/validation/lobovsky2014.h"
#include "swell/bake/validation/martin_moyce1952.h"

namespace swell::bake::validation {

/// Both Martin & Moyce series as CSV text, "series,T,Z" then one row per point, series
/// "a2.25in" (martinMoyceA225) before "a1.125in" (martinMoyceA1125): the records the dam-break
/// check compares with, for plots (swell-validate dam-break --records).
std::string martinMoyceRecordsCsv();

/// Surge front: the largest x of a water particle that is not splash (n >= d1 n0,
/// paper eq. (4)), minus `x0` (the column's back face). Returns 0 if none qualifies.
double surgeFront(const Particles& particles, double n0, double splashRatio, double x0 = 0.0);

/// Mean and max of |Z_sim(T) - Z_exp(T)| over the experimental points with T in [tLo, tHi];
/// Z_sim is linearly interpolated in a simulated series sorted by T.
struct FrontError {
    double mean = 0.0;
    double max = 0.0;
    double meanSigned = 0.0; ///< mean of Z_sim - Z_exp (positive: simulation ahead)
    int points = 0;
};
FrontError compareFront(std::span<const FrontPoint> simulated,
                        std::span<const FrontPoint> experiment, double tLo, double tHi);
/// Two comparisons pooled (the two Martin & Moyce series): mean and signed mean weighted by
/// their point counts, the larger max, the points added; zero when neither has points.
FrontError pooled(const FrontError& a, const FrontError& b);

/// Front comparison on a time origin tied to the front position. Martin & Moyce's t = 0 (when
/// the gate release counts as complete) could not be found in any source we can read, so the
/// simulated series is shifted in T by a fixed a-priori rule, never fitted: the simulated front
/// must reach the experiment's FIRST recorded position Z_1 exactly at that point's T_1. The
/// crossing time is the first one in the simulated series (linear interpolation between the
/// two samples around it); shift = T_1 - T_cross is added to every simulated T (positive: the
/// simulation was ahead). The shifted series is then compared like compareFront over the
/// experimental points with T in [tLo, tHi], the alignment point itself excluded (it agrees by
/// construction).
struct AlignedFront {
    double shift = 0.0; ///< added to the simulated T
    FrontError error;   ///< shifted series against the experiment without its first point
};
/// Throws std::invalid_argument for fewer than two simulated or two experimental points, a
/// simulated series that starts beyond Z_1 or never reaches it, or a shifted series that does
/// not cover the compared experimental times.
AlignedFront alignedFront(std::span<const FrontPoint> simulated,
                          std::span<const FrontPoint> experiment, double tLo = 0.8,
                          double tHi = 3.0);

/// How far Martin & Moyce's two series are from each other under the same rule: the
/// a = 2.25 in record, treated as a simulated series, aligned on the a = 1.125 in record's
/// first point and compared with its other points in [tLo, tHi] (alignedFront). The
/// experiment's own repeatability: a front error below it cannot be told from scatter.
/// (The other direction is not defined: the a = 1.125 in record starts beyond the a = 2.25 in
/// record's first position.)
AlignedFront martinMoyceScatter(double tLo = 0.8, double tHi = 3.0);

/// Water-level gauge against an experimental record (Lobovsky et al. 2014 dam break): the
/// simulated series (sorted by t, sampled more densely than the record) is linearly
/// interpolated at each record time in [tLo, tHi], so that every compared value is a measured
/// one and the record is not interpolated between its points (it is thinned to 26.7 ms,
/// lobovsky2014.cpp). Errors in metres (h_sim - h_record).
struct LevelError {
    double mean = 0.0;       ///< mean |h_sim - h_record| (m)
    double max = 0.0;        ///< max |h_sim - h_record| (m)
    double meanSigned = 0.0; ///< mean of h_sim - h_record (m): positive where the sim is higher
    int points = 0;          ///< record points compared
};
/// Throws std::invalid_argument for fewer than two simulated points or a simulated series that
/// does not cover the record's times in [tLo, tHi].
LevelError compareLevel(std::span<const LevelPoint> simulated, std::span<const LevelPoint> record,
                        double tLo, double tHi);

/// How far the experiment is from itself at one gauge: the gauge's other series (`repeat`,
/// lobovsky2014.h) compared with its record as compareLevel compares a simulated series, over
/// [tLo, tHi]. A gauge error below it cannot be told from the experiment's scatter. Empty for
/// a gauge without a second series (H1).
std::optional<LevelError> lobovskyScatter(const LevelGauge& gauge, double tLo, double tHi);

/// The time a level series (sorted by t) first stands above `level` (m): its first sample
/// above it; nothing if none is.
std::optional<double> firstTimeAbove(std::span<const LevelPoint> series, double level);

/// The gauge nearest the far wall (the largest x). Throws std::invalid_argument for no gauges.
std::size_t lobovskyFarGauge(std::span<const LevelGauge> gauges);

/// Where "the first impact and run-up", a window for the Lobovsky levels, ends: the water the far
/// wall throws back lands on the gauge nearest that wall, read as the first record sample there
/// above half the column's height H (H4 at 1.093 s in the H = 300 mm records; docs/validation.md,
/// Lobovsky et al. (2014) dam break). Until then the gauges see the collapse, the surge, the impact
/// and the run-up only. Throws std::invalid_argument for no gauges or a far record that never rises
/// above H / 2.
double lobovskyRunUpEnd(std::span<const LevelGauge> gauges, double H);

/// The Lobovsky et al. (2014) gauge records as CSV text, "gauge,series,x,t,h" (x, t, h in m
/// and s as in lobovskyH300Gauges) then one row per point, gauges in the order H1..H4, each
/// gauge's record (series "record": what the lobovsky check compares with) then its other
/// series' points (series "repeat", where it has one), for plots (swell-validate lobovsky
/// --records).
std::string lobovskyRecordsCsv();

/// Least-squares fit v(t) ~ a cos(omega t) + b sin(omega t) + c of a gauge record at a
/// known angular frequency (regular-wave validation): amplitude sqrt(a^2 + b^2) and phase
/// atan2(b, a), so v ~ amplitude cos(omega t - phase) + mean. Throws std::invalid_argument
/// for fewer than 3 samples, different lengths or a singular fit.
struct HarmonicFit {
    double amplitude = 0.0; ///< (units of v)
    double phase = 0.0;     ///< (rad), in (-pi, pi]
    double mean = 0.0;      ///< (units of v)
};
HarmonicFit fitHarmonic(std::span<const double> t, std::span<const double> v, double omega);

/// The standard error of fitHarmonic's amplitude, from the record's own fluctuations about the wave
/// (docs/validation.md, Progressive waves). The record v(t), sampled at an even step dt, is fitted
/// with the mean and the first kStandardErrorHarmonics harmonics of omega, the mean and the first
/// harmonic's amplitude each drifting linearly across the record (a growing wave front is the
/// wave's, not a fluctuation). The residual's autocovariance C_k over lags up to one period, under
/// a triangular lag window, gives its spectral density at omega,
/// S = C_0 + 2 sum_k (1 - k / (K + 1)) C_k cos(omega k dt) (the Bartlett estimate, never
/// negative). The fit took the band around omega out of the residual, so S is divided by what
/// the same estimate reads, per unit of density, from the residual of white noise (exact, from
/// the fit's projection). Each of fitHarmonic's two coefficients then has the variance 2 S / N
/// (N samples), which is also the amplitude's where the amplitude is well above it. A flow whose
/// surface fluctuates between the wave's crests (its particles) makes a fit over a finite window
/// read a height that differs from one record to the next by about this much. Throws
/// std::invalid_argument for fewer than kStandardErrorMinSamples samples, t and v of different
/// lengths, samples not evenly spaced (within 1 % of their mean step), or a fit that does not
/// resolve the harmonics or leaves nothing to estimate the noise from.
inline constexpr int kStandardErrorHarmonics = 3;
/// The fewest samples harmonicAmplitudeStandardError takes: twice its fit's columns.
inline constexpr std::size_t kStandardErrorMinSamples = 2 * (4 + 2 * kStandardErrorHarmonics);
double harmonicAmplitudeStandardError(std::span<const double> t, std::span<const double> v,
                                      double omega);

/// Slope of the least-squares line through (x, y) (a wave's decay or phase along its gauges,
/// a standing wave's ln amplitude over its periods). Throws std::invalid_argument(what) when
/// the x are all equal.
double lineSlope(std::span<const double> x, std::span<const double> y, const char* what);

/// Where a record y(t) crosses `level` on either side of its crest at `crestTime`: searched
/// outward from the crest over the samples with t in [lo, hi], the first sample below `level`
/// on each side, the crossing interpolated linearly between it and its neighbour towards the
/// crest. Returns (front, back) times; NaN for a side whose crossing that span does not hold.
/// The solitary wave's width and the shoaling wave's rise and fall are read with it.
std::pair<double, double> crossingsAround(std::span<const double> t, std::span<const double> y,
                                          double lo, double hi, double crestTime, double level);

/// The top of a record's crest: the least-squares parabola y = a + b s + c s^2 (s = t - t[peak])
/// through the samples [lo, hi], as (t of its vertex, y there). Falls back to (t[peak],
/// y[peak]) where fewer than three samples, a singular fit, a fit that is not a maximum, or a
/// vertex farther from t[peak] than the samples span.
std::pair<double, double> parabolaTop(std::span<const double> t, std::span<const double> y,
                                      std::size_t lo, std::size_t hi, std::size_t peak);

/// One figure over an ensemble of runs (swell-validate --ensemble): members that differ only
/// by a jitter of the water far below the resolution, so their spread is how far one record
/// of a flow that amplifies small differences can be trusted.
struct Spread {
    double mean = 0.0;
    double sd = 0.0; ///< sample standard deviation (n - 1); 0 for one member
    double min = 0.0;
    double max = 0.0;
    std::size_t count = 0;
};
/// Throws std::invalid_argument for no values or a value that is not finite.
Spread spreadOf(std::span<const double> values);

} // namespace swell::bake::validation
