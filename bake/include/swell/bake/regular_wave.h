#pragma once
// Regular-wave validation (docs/validation.md): the gauge records of a bake whose piston moves
// sinusoidally, against linear wavemaker theory (Biesel transfer function, dispersion).
// Pure functions on probe samples; readProbeCsv reads what swell-bake --probes wrote.

#include <filesystem>
#include <span>
#include <vector>

#include "swell/bake/probes.h"
#include "swell/bake/scene.h"
#include "swell/bake/wave_theory.h"

namespace swell::bake {

/// Time window of a regular-wave record that linear theory describes: it opens one period
/// after the ramp has ended and the fully grown wave, moving at the group velocity, has
/// passed the farthest gauge; it closes when the reflection from the far wall can reach the
/// nearest gauge (or at the end of the run).
struct WaveWindow {
    double start = 0.0; ///< (s)
    double end = 0.0;   ///< (s)
};
/// Throws SceneError when the scene has no sinusoidal piston, no tank or fewer than two gauges.
WaveWindow regularWaveWindow(const Scene& scene);

/// Wave height and length measured at the gauges against linear theory.
struct RegularWaveCheck {
    LinearPistonWave theory;     ///< Biesel height, dispersion wavelength
    double depth = 0.0;          ///< still-water depth h (m)
    WaveWindow window;           ///< samples used
    std::size_t samples = 0;     ///< samples inside the window
    std::vector<double> gauges;  ///< gauge x (m)
    std::vector<double> heights; ///< H = 2 x amplitude of the harmonic fit at each gauge (m)
    double wavelength = 0.0;     ///< 2 pi dx / (phase lag) between the first two gauges (m)
    /// Relative errors against theory: measured / theory - 1.
    double heightError(std::size_t gauge) const { return heights.at(gauge) / theory.height - 1.0; }
    double wavelengthError() const { return wavelength / theory.wavelength - 1.0; }
};

/// Fits each gauge's record inside `window` with a cos wt + b sin wt + c at the piston's
/// frequency. Throws SceneError for a scene without a sinusoidal piston or two gauges, and
/// std::invalid_argument for too few samples or a dry gauge (NaN) inside the window.
RegularWaveCheck checkRegularWave(const Scene& scene, std::span<const ProbeSample> samples,
                                  const WaveWindow& window);

/// Reads a probes CSV written by swell-bake --probes (header time,front_x,gauge_<x>...).
/// Throws std::runtime_error naming the file and line for a malformed file.
std::vector<ProbeSample> readProbeCsv(const std::filesystem::path& path);

} // namespace swell::bake
