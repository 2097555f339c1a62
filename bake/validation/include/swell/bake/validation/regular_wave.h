#pragma once
// Regular-wave validation (docs/validation.md): the gauge records of a bake whose piston moves
// sinusoidally, against linear wavemaker theory (Biesel transfer function, dispersion).
// Pure functions on probe samples; readProbeCsv reads what swell-bake --probes wrote.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "swell/bake/piston_motion.h"
#include "swell/bake/probes.h"
#include "swell/bake/scene.h"
#include "swell/bake/wave_theory.h"

namespace swell::bake::validation {

/// Time window of a regular-wave record that linear theory describes, for gauges anywhere
/// between the paddle and the far wall. Wave energy travels at the group velocity c_g of
/// linear theory (the piston's frequency, still-water depth).
/// - Opens one period after the fully grown wave has passed the FARTHEST gauge: the piston
///   reaches full stroke at the end of its ramp, and that part of the wave train reaches gauge x
///   at ramp_time + (x - x_paddle) / c_g; the farthest gauge is the last to be reached.
/// - Closes when the reflection from the far wall x_1 reaches the FARTHEST gauge (the one
///   nearest to that wall, hence the first to see it): the first motion of the piston (t = 0)
///   arrives there at (2 (x_1 - x_paddle) - (x - x_paddle)) / c_g; or at the end of the run if
///   that is earlier. Because the piston's stroke is ramped from zero, the reflected wave is
///   still small at that moment. The dispersive precursor that runs ahead of the group (up to
///   sqrt(g h)) is neglected; with a ramp of two periods it is a few per cent of the height.
/// A scene for far gauges needs a tank long enough that the window is at least two periods
/// (scenes/progressive_wave.json).
struct WaveWindow {
    double start = 0.0; ///< (s)
    double end = 0.0;   ///< (s)
};
/// Throws SceneError when the scene has no sinusoidal piston, no tank or fewer than two gauges.
WaveWindow regularWaveWindow(const Scene& scene);

/// Each gauge's own window (docs/validation.md, Progressive waves), in the order of
/// scene.output.gauges: the rule of WaveWindow applied to that gauge alone. It opens one period
/// after the fully grown wave passed that gauge and closes when the far wall's reflection reaches
/// it, or at the end of the run. A gauge nearer the piston is reached earlier and reflected later,
/// so its window holds more periods; the farthest gauge's own window is regularWaveWindow's. Throws
/// like regularWaveWindow.
std::vector<WaveWindow> regularWaveGaugeWindows(const Scene& scene);

/// Wave height and length measured at the gauges against linear theory.
struct RegularWaveCheck {
    LinearPistonWave theory;    ///< Biesel height, dispersion wavelength
    double depth = 0.0;         ///< still-water depth h (m)
    WaveWindow window;          ///< the common window: the phases (wavelengths) are fitted in it
    std::size_t samples = 0;    ///< samples inside the common window
    std::vector<double> gauges; ///< gauge x (m)
    std::vector<WaveWindow> gaugeWindows;  ///< each gauge's own window: its height is fitted in it
    std::vector<std::size_t> gaugeSamples; ///< samples inside each gauge's own window
    std::vector<double> heights; ///< H = 2 x harmonic amplitude, each in its own window (m)
    std::vector<double> heightsCommonWindow; ///< the same fit in the common window (m)
    double wavelength = 0.0; ///< 2 pi dx / (phase lag) between the first two gauges (m)
    /// Wavelength from the phase slope over ALL gauges (m): 2 pi / (least-squares slope of
    /// the unwrapped phase against x). The gauges are taken in order of x and each phase lag
    /// between neighbours in [0, 2 pi) (a wave travelling towards +x; neighbouring gauges must be
    /// less than a wavelength apart). Equals `wavelength` for two gauges.
    double wavelengthFit = 0.0;
    /// Height decay along the tank, from a least-squares fit ln H = a + b x over all gauges
    /// (`heights`, each gauge's own window):
    /// fractional loss per (theoretical) wavelength, 1 - exp(b L); positive when the wave decays.
    double decayPerWavelength = 0.0;
    /// Height lost between the first and the last gauge along the same least-squares line:
    /// 1 - exp(b (x_last - x_first)), over 3 L in the shipped wave scenes. It reads every gauge,
    /// so one gauge's short window moves it less than the two-gauge ratio below; the "lost
    /// over 3 L" of docs/validation.md, Progressive waves.
    double decayOverSpan = 0.0;
    /// 1 - H(last gauge) / H(first gauge), gauges in order of x.
    double decayTotal = 0.0;
    /// Each height's standard error from its record's own fluctuations in its own window, 2 x
    /// harmonicAmplitudeStandardError (m), in the order of `heights`; NaN for a window it cannot
    /// read (fewer than kStandardErrorMinSamples or unevenly spaced samples). One record's figure
    /// differs from another record's of the same wave by about this much.
    std::vector<double> heightStandardErrors;
    /// The standard error of decayOverSpan, with the gauges' errors taken as independent: the
    /// line's slope b has the variance sum (x - mean x)^2 (se_H / H)^2 / (sum (x - mean x)^2)^2,
    /// and 1 - exp(b span) the standard error exp(b span) span se_b.
    double decayOverSpanStandardError = 0.0;
    /// Relative errors against theory: measured / theory - 1.
    double heightError(std::size_t gauge) const { return heights.at(gauge) / theory.height - 1.0; }
    double wavelengthError() const { return wavelength / theory.wavelength - 1.0; }
    double wavelengthFitError() const { return wavelengthFit / theory.wavelength - 1.0; }
};

/// Fits each gauge's record with a cos wt + b sin wt + c at the piston's frequency: inside
/// its own window in `gaugeWindows` (one per gauge, in the order of scene.output.gauges) for
/// its height, and inside the common `window` for its phase, since a phase lag compares the
/// gauges at the same times. Empty `gaugeWindows`: every gauge's height in `window` too.
/// Throws SceneError for a scene without a sinusoidal piston or two gauges, and
/// std::invalid_argument for a gaugeWindows of the wrong size, too few samples or a dry gauge
/// (NaN) inside a window it is fitted in.
RegularWaveCheck checkRegularWave(const Scene& scene, std::span<const ProbeSample> samples,
                                  const WaveWindow& window,
                                  std::span<const WaveWindow> gaugeWindows = {});

/// Whether linear theory's tank ends in a reflecting wall at x_1 or opens into a channel.
enum class FarWall { Open, Reflects };

/// What linear theory records at the scene's gauges at `times` (s): the propagating wave of
/// the piston's actual motion, ramp included, as a superposition of Biesel waves. The piston
/// velocity V(t) (PistonMotion, zero after the last time) is Fourier transformed, and each
/// frequency travels as its own Biesel wave: eta(x, w) = B(kh) V(w) / w e^{-i k x}, with
/// B = H / S of pistonHeightOverStroke and k from dispersionWavenumber, x from the paddle's
/// rest position (for V = V0 cos wt this is the regular wave H / 2 cos(wt - kx),
/// H = B S). The evanescent modes near the paddle are left out. Run through
/// checkRegularWave with the record's windows, it shows what the measurement itself makes of
/// an undamped wave train: the growth of the dispersive wave front, which the window's
/// group-velocity rule neglects. With FarWall::Reflects (the default: the tank as the solver
/// sees it) the far wall reflects the train: each gauge also records the same wave from the
/// mirror distance 2 (x_1 - x_paddle) - (x - x_paddle); the reflection's return from the
/// paddle is left out (it reaches the gauges later still). FarWall::Open leaves the channel
/// open. Throws like checkRegularWave for an unsuitable scene.
std::vector<ProbeSample> linearTheoryRecord(const Scene& scene, std::span<const double> times,
                                            FarWall farWall = FarWall::Reflects);

/// Throws std::invalid_argument, naming `what`, when the record `samples` ends more than
/// `tolerance` (s) before the last of `windows` closes: a record cut short (a bake that stopped)
/// would be fitted over less than its windows.
void requireRecordCoversWindows(std::span<const ProbeSample> samples,
                                std::span<const WaveWindow> windows, double tolerance,
                                const std::string& what);

/// Reads a probes CSV written by swell-bake --probes (header time,front_x,gauge_<x>...).
/// With `gauges`, the header must be the one a bake with those gauges writes (probeCsvHeader):
/// a record of another scene is refused, not fitted. Throws std::runtime_error naming the
/// file and line for a malformed file or another scene's header.
std::vector<ProbeSample> readProbeCsv(const std::filesystem::path& path,
                                      std::span<const double> gauges = {});

} // namespace swell::bake::validation
