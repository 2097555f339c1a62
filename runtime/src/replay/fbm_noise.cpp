#include "swell/runtime/replay/fbm_noise.h"

#include "swell/split_mix64.h"

#include <fftw3.h>

#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

namespace swell::runtime {

void NoiseParams::validate() const {
    if (timeSamples < 2 || timeSamples > 4096) {
        throw std::invalid_argument(
            fmt::format("noise.time_samples must be in [2, 4096], got {}", timeSamples));
    }
    if (!std::isfinite(beta) || beta < 0.0 || beta > 8.0) {
        throw std::invalid_argument(fmt::format("noise.beta must be in [0, 8], got {}", beta));
    }
    if (!std::isfinite(cutoff) || cutoff < 0.0) {
        throw std::invalid_argument(fmt::format("noise.cutoff must be >= 0, got {}", cutoff));
    }
}

FbmNoise::FbmNoise(const NoiseParams& params, int slices, std::uint64_t seed)
    : m_T(params.timeSamples), m_K(slices) {
    params.validate();
    if (slices < 2 || slices > 65536) {
        throw std::invalid_argument(fmt::format("slices must be in [2, 65536], got {}", slices));
    }
    const int T = m_T;
    const int K = m_K;
    const int Kh = K / 2 + 1; // half spectrum of the real transform along k
    auto* spectrum = static_cast<fftw_complex*>(
        fftw_malloc(sizeof(fftw_complex) * static_cast<std::size_t>(T * Kh)));
    auto* field =
        static_cast<double*>(fftw_malloc(sizeof(double) * static_cast<std::size_t>(T * K)));
    std::unique_ptr<fftw_complex, decltype(&fftw_free)> spectrumOwner(spectrum, fftw_free);
    std::unique_ptr<double, decltype(&fftw_free)> fieldOwner(field, fftw_free);
    if (spectrum == nullptr || field == nullptr)
        throw std::bad_alloc();

    // Seeded complex white noise shaped by |f|^(-beta/2) (power ~ |f|^-beta), then the
    // filter. Both random numbers are drawn for every coefficient, kept or not, so the
    // filter never changes the coefficients it keeps.
    SplitMix64 rng(seed);
    bool anyKept = false;
    for (int i = 0; i < T; ++i) {
        const int ft = i <= T / 2 ? i : i - T;
        for (int v = 0; v < Kh; ++v) {
            const double re = rng.gaussian();
            const double im = rng.gaussian();
            const double f = std::sqrt(static_cast<double>(ft * ft + v * v));
            bool keep = f > 0.0; // no DC: the noise has zero mean
            if (params.filter == NoiseFilter::LowPass)
                keep = keep && f <= params.cutoff;
            if (params.filter == NoiseFilter::HighPass)
                keep = keep && f >= params.cutoff;
            const double amplitude = keep ? std::pow(f, -0.5 * params.beta) : 0.0;
            anyKept = anyKept || keep;
            spectrum[i * Kh + v][0] = amplitude * re;
            spectrum[i * Kh + v][1] = amplitude * im;
        }
    }
    if (!anyKept) {
        throw std::invalid_argument(
            fmt::format("noise.cutoff {} removes every frequency of a {} x {} noise grid",
                        params.cutoff, T, K));
    }
    // Hermitian symmetry where the half spectrum holds both f and -f (fk = 0 and, for even K,
    // fk = K/2), so the inverse transform is exactly real.
    for (int v : {0, K % 2 == 0 ? K / 2 : -1}) {
        if (v < 0)
            continue;
        for (int i = 0; i < T; ++i) {
            const int mirror = (T - i) % T;
            if (mirror == i) {
                spectrum[i * Kh + v][1] = 0.0;
            } else if (i > mirror) {
                spectrum[i * Kh + v][0] = spectrum[mirror * Kh + v][0];
                spectrum[i * Kh + v][1] = -spectrum[mirror * Kh + v][1];
            }
        }
    }
    // FFTW_ESTIMATE: the plan (and so the result) does not depend on timing measurements.
    fftw_plan plan = fftw_plan_dft_c2r_2d(T, K, spectrum, field, FFTW_ESTIMATE);
    if (plan == nullptr)
        throw std::logic_error("FFTW could not plan the noise transform");
    fftw_execute(plan);
    fftw_destroy_plan(plan);

    m_values.assign(field, field + static_cast<std::size_t>(T * K));
    double peak = 0.0;
    for (double v : m_values)
        peak = std::max(peak, std::abs(v));
    if (!(peak > 0.0)) {
        throw std::invalid_argument(fmt::format(
            "noise.cutoff {} leaves no signal on a {} x {} noise grid", params.cutoff, T, K));
    }
    for (double& v : m_values)
        v /= peak; // max |N| = 1, so eq. (6) reads F <= 1
}

} // namespace swell::runtime
