#pragma once
// A standing wave in a closed tank against linear theory (docs/validation.md, Standing wave). Water
// at rest whose surface is one cosine, y = h + A cos(k (x - x0)), k = pi / length for the tank's
// first mode, sloshes at the linear frequency omega^2 = g k tanh(k h) (Lamb 1932, Hydrodynamics,
// 6th ed., arts. 227-228) and, with water's viscosity, keeps its amplitude: the viscous decay rate
// of a free-surface wave, 2 nu k^2 (Lamb art. 348), and the wall and bed boundary layers take well
// under 1 % per period at laboratory scale. So the record of the surface at a wall measures a
// scheme's dispersion (the period) and its numerical damping (the decay per period) on a flow no
// setting of the solver was tuned on. runStandingWave is the run swell-validate standing-wave
// reports and the CI-resolution test bounds. No I/O.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"

namespace swell::bake::validation {

/// Linear theory of a standing wave of wavelength `wavelength` in water of depth `depth`.
struct StandingWaveTheory {
    double wavenumber = 0.0; ///< k = 2 pi / wavelength (1/m)
    double kh = 0.0;         ///< relative depth (-)
    double omega = 0.0;      ///< sqrt(g k tanh(k h)) (rad/s)
    double period = 0.0;     ///< 2 pi / omega (s)
};

/// Throws std::invalid_argument for a non-positive wavelength, depth or gravity.
StandingWaveTheory standingWaveTheory(double wavelength, double depth, double gravity);

/// What one gauge's elevation record says about the oscillation it saw.
struct SloshRecord {
    std::vector<double> crossings;  ///< upward crossings of the record's mean (s), interpolated
    std::vector<double> amplitudes; ///< half the range of each period between two crossings (m)
    double period = 0.0;            ///< (last - first crossing) / (crossings - 1) (s)
    /// 1 - exp(b), b the least-squares slope of ln(amplitude) per period: the part of its
    /// amplitude the wave loses each period (negative: it grows).
    double decayPerPeriod = 0.0;
};

/// Reads an elevation record eta(t) (t increasing). Throws std::invalid_argument for records
/// of different sizes, or with fewer than three upward crossings (two whole periods).
SloshRecord analyseSlosh(std::span<const double> t, std::span<const double> eta);

/// One run of a standing-wave scene and what its two gauges read: the records (outcome, times,
/// elevations at the gauges, steps, PPE iterations, solver time) and their analysis.
struct StandingWaveReport : GaugeRecords {
    StandingWaveTheory theory;
    /// Gauge x (m): one spacing in from each side wall, where the first mode's elevation is
    /// largest; the elevation is the top of the highest non-splash water particle within l0,
    /// from the water's mean level y1 (sampleProbes), after every step.
    std::vector<double> gauges;
    std::vector<SloshRecord> records; ///< per gauge, when stable
    double period = 0.0;              ///< mean of the gauges' periods (s)
    double periodError = 0.0;         ///< period / theory.period - 1
    double decayPerPeriod = 0.0;      ///< mean of the gauges'
    /// The first period's amplitude over the cosine's A |cos k (x - x0)| at the gauge, mean of
    /// the gauges: about 1 for a clean first mode.
    double firstAmplitudeOverTheory = 0.0;
};

/// Runs `scene` (a tank, geometry.water[0] with a cosine top) to run.end_time. Throws
/// SceneError naming the key for a scene without a tank or a cosine top, std::runtime_error
/// for a gauge that runs dry or a record too short to read (analyseSlosh); a diverging run
/// returns its outcome.
StandingWaveReport runStandingWave(const Scene& scene);

} // namespace swell::bake::validation
