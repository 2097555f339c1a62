#pragma once
// The noise N(i, k) of eq. (5): 2D fBm (1/f^beta) noise on a T x K grid (time x slice), made
// by FFT spectral synthesis (FFTW, paper ref. [33]). Periodic in both axes, normalised to
// max |N| = 1.

#include <cstdint>
#include <vector>

namespace swell::runtime {

/// Which band of the fBm spectrum is kept (Sec. 4.3: low-pass for smooth wave fronts).
enum class NoiseFilter {
    None,     ///< keep every frequency
    LowPass,  ///< keep |f| <= cutoff
    HighPass, ///< keep |f| >= cutoff
};

/// Noise shape. Frequencies are integer wavenumbers (cycles per period) per axis,
/// |f| = sqrt(ft^2 + fk^2), ft in (-T/2, T/2], fk in [0, K/2].
struct NoiseParams {
    int timeSamples = 16;  ///< T: noise samples along animation time (paper: 16)
    double beta = 2.0;     ///< power spectrum ~ |f|^-beta (paper Table 4: 2.0 surging)
    double cutoff = 128.0; ///< c, in wavenumbers (paper Table 4: 128)
    NoiseFilter filter = NoiseFilter::LowPass; ///< band kept (paper: low-pass)

    /// Throws std::invalid_argument naming the key ("noise.beta", ...).
    void validate() const;
};

class FbmNoise {
public:
    /// Synthesises a T x K field (T = params.timeSamples): complex white noise from
    /// SplitMix64(seed), amplitude |f|^(-beta/2), filter, inverse real FFT, scaled to
    /// max |N| = 1. Throws std::invalid_argument on bad parameters or a filter that removes
    /// every frequency. Plans an FFTW transform: FFTW's planner is not thread-safe, so do not
    /// construct two FbmNoise at once on different threads.
    FbmNoise(const NoiseParams& params, int slices, std::uint64_t seed);

    int timeSamples() const { return m_T; }
    int slices() const { return m_K; }
    /// N(i, k), i in [0, T), k in [0, K).
    double at(int i, int k) const { return m_values[static_cast<std::size_t>(i * m_K + k)]; }
    /// Row-major values, N(i, k) at [i * K + k].
    const std::vector<double>& values() const { return m_values; }

private:
    int m_T;
    int m_K;
    std::vector<double> m_values;
};

} // namespace swell::runtime
