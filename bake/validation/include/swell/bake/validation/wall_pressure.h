#pragma once
// A wall-pressure series against the far-wall records of the dam break (buchner2002.h,
// docs/validation.md, Far-wall pressure), in t sqrt(g / H) and p / (rho g H): the impact, the
// second peak that the run-up's collapse makes, and the mean error. MPS pressures are noisy from
// step to step, so every series, simulated or recorded, goes through the same moving average first.
// Pure functions.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "swell/bake/validation/buchner2002.h"

namespace swell::bake::validation {

/// One sample of a dimensionless pressure series.
struct PressurePoint {
    double t = 0.0; ///< t sqrt(g / H)
    double p = 0.0; ///< p / (rho g H)
};

/// Half width of the moving average, in t sqrt(g / H) (8.7 ms at Lobovsky's H = 0.3 m).
inline constexpr double kPressureSmoothing = 0.05;
/// The impact's time: the first smoothed sample above this p / (rho g H), half the level the
/// records settle at after the impact (0.55-0.69).
inline constexpr double kImpactLevel = 0.3;
/// Where the second peak is looked for, t sqrt(g / H): the span in which the records place the
/// run-up's collapse onto the wall's foot (the experiment's at 5.83, delta-SPH's at 6.31-6.42),
/// after the impact's plateau.
inline constexpr double kSecondPeakFrom = 5.0;
inline constexpr double kSecondPeakTo = 7.0;

/// The mean of the samples within halfWidth of each sample's t (series sorted by t).
std::vector<PressurePoint> movingAverage(std::span<const PressurePoint> series, double halfWidth);

/// What a series says, read after the moving average (kPressureSmoothing).
struct PressureFigures {
    std::optional<double> impactTime; ///< first t above kImpactLevel; none if never
    std::optional<double> peakTime; ///< t of the largest value in [kSecondPeakFrom, kSecondPeakTo]
    double peak = 0.0;              ///< that value (0 when the window holds no sample)
};
PressureFigures pressureFigures(std::span<const PressurePoint> series);

/// Mean |p_sim - p_ref| over the simulated samples in the reference's span, both smoothed and the
/// reference interpolated linearly at the simulated times; none if no simulated sample lies in
/// it.
std::optional<double> meanAbsPressureError(std::span<const PressurePoint> simulated,
                                           std::span<const PressurePoint> reference);

/// A column of the P1 records and its name.
struct PressureRecordColumn {
    const char* name = "";                           ///< experiment, delta_sph_40, ...
    double FarWallPressureSample::*column = nullptr; ///< e.g. &FarWallPressureSample::deltaSph320
};
/// The records' columns in order: experiment, delta_sph_40, delta_sph_80, delta_sph_320.
std::span<const PressureRecordColumn> buchnerP1Columns();

/// One column of the P1 records as a series, e.g. &FarWallPressureSample::deltaSph320.
std::vector<PressurePoint> buchnerP1Series(double FarWallPressureSample::*column);

/// The P1 records as CSV text, "series,t,p" (t sqrt(g / H), p / (rho g H)), series experiment,
/// delta_sph_40, delta_sph_80, delta_sph_320, for plots (swell-validate lobovsky
/// --pressure-records).
std::string buchnerP1RecordsCsv();

} // namespace swell::bake::validation
