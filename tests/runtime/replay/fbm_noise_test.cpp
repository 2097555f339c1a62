#include "swell/runtime/replay/fbm_noise.h"
#include "swell/split_mix64.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace swell::runtime {
namespace {

/// |FFT|^2 of a T x K real field, as [i * (K/2 + 1) + v].
std::vector<double> powerSpectrum(const std::vector<double>& field, int T, int K) {
    const int Kh = K / 2 + 1;
    std::vector<double> in(field);
    auto* out = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * T * Kh));
    fftw_plan plan = fftw_plan_dft_r2c_2d(T, K, in.data(), out, FFTW_ESTIMATE);
    fftw_execute(plan);
    std::vector<double> power(static_cast<std::size_t>(T * Kh));
    for (int i = 0; i < T * Kh; ++i)
        power[i] = out[i][0] * out[i][0] + out[i][1] * out[i][1];
    fftw_destroy_plan(plan);
    fftw_free(out);
    return power;
}

double radius(int i, int v, int T) {
    const int ft = i <= T / 2 ? i : i - T;
    return std::sqrt(static_cast<double>(ft * ft + v * v));
}

/// Least-squares slope of log P against log f, P radially averaged over unit-wide rings,
/// averaged over several seeds, fitted over f in [fMin, fMax].
double fittedSlope(double beta, int size, int seeds, double fMin, double fMax) {
    NoiseParams p;
    p.timeSamples = size;
    p.beta = beta;
    p.filter = NoiseFilter::None;
    const int Kh = size / 2 + 1;
    const int rings = static_cast<int>(fMax) + 2;
    std::vector<double> sum(rings, 0.0);
    std::vector<int> count(rings, 0);
    for (int s = 0; s < seeds; ++s) {
        const FbmNoise noise(p, size, 1000 + s);
        const std::vector<double> power = powerSpectrum(noise.values(), size, size);
        for (int i = 0; i < size; ++i) {
            for (int v = 0; v < Kh; ++v) {
                const int r = static_cast<int>(std::lround(radius(i, v, size)));
                if (r < rings) {
                    sum[r] += power[i * Kh + v];
                    ++count[r];
                }
            }
        }
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (int r = static_cast<int>(fMin); r <= static_cast<int>(fMax); ++r) {
        if (count[r] == 0)
            continue;
        const double x = std::log(static_cast<double>(r));
        const double y = std::log(sum[r] / count[r]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        ++n;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace

TEST(SplitMix64, MatchesTheReferenceSequence) {
    // Reference values of SplitMix64 seeded with 0 (Vigna's splitmix64.c).
    SplitMix64 rng(0);
    EXPECT_EQ(rng.next(), 0xe220a8397b1dcdafULL);
    EXPECT_EQ(rng.next(), 0x6e789e6aa1b965f4ULL);
    EXPECT_EQ(rng.next(), 0x06c45d188009454fULL);
}

TEST(SplitMix64, GaussianHasUnitVariance) {
    SplitMix64 rng(42);
    double s = 0, ss = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double g = rng.gaussian();
        s += g;
        ss += g * g;
    }
    EXPECT_NEAR(s / n, 0.0, 0.01);
    EXPECT_NEAR(ss / n, 1.0, 0.01);
}

class FbmSlope : public ::testing::TestWithParam<double> {};

TEST_P(FbmSlope, RadiallyAveragedPowerFallsAsFToTheMinusBeta) {
    const double beta = GetParam();
    const double slope = fittedSlope(beta, 128, 6, 2.0, 60.0);
    EXPECT_NEAR(slope, -beta, 0.2) << "beta " << beta;
}

INSTANTIATE_TEST_SUITE_P(PaperRange, FbmSlope, ::testing::Values(1.0, 1.5, 2.0, 2.5, 2.8));

TEST(FbmNoise, NormalisedToUnitPeakOnThePaperGrid) {
    const NoiseParams p; // T = 16, beta 2, c 128, low-pass
    const FbmNoise noise(p, 256, 3);
    ASSERT_EQ(noise.values().size(), 16u * 256u);
    double peak = 0.0, mean = 0.0;
    for (double v : noise.values()) {
        peak = std::max(peak, std::abs(v));
        mean += v;
    }
    EXPECT_EQ(peak, 1.0);                                  // max |N| = 1 exactly
    EXPECT_NEAR(mean / noise.values().size(), 0.0, 1e-12); // no DC term
}

/// The spectral power of 64 x 128 noise (seed 9) with `filter` at cut-off 20 that lies on
/// either side of the cut-off: {kept, removed}.
std::pair<double, double> powerAroundCutoff(NoiseFilter filter, double beta) {
    NoiseParams p;
    p.timeSamples = 64;
    p.beta = beta;
    p.cutoff = 20.0;
    p.filter = filter;
    const FbmNoise noise(p, 128, 9);
    const std::vector<double> power = powerSpectrum(noise.values(), 64, 128);
    double kept = 0, removed = 0;
    for (int i = 0; i < 64; ++i) {
        for (int v = 0; v < 65; ++v) {
            const double r = radius(i, v, 64);
            const bool keep = filter == NoiseFilter::LowPass ? r <= 20.0 : r >= 20.0;
            (keep ? kept : removed) += power[i * 65 + v];
        }
    }
    return {kept, removed};
}

TEST(FbmNoise, LowPassRemovesEverythingAboveTheCutoff) {
    const auto [kept, removed] = powerAroundCutoff(NoiseFilter::LowPass, 1.0);
    EXPECT_GT(kept, 0.0);
    EXPECT_LT(removed, 1e-20 * kept);
}

TEST(FbmNoise, HighPassRemovesEverythingBelowTheCutoff) {
    const auto [kept, removed] = powerAroundCutoff(NoiseFilter::HighPass, 2.0);
    EXPECT_GT(kept, 0.0);
    EXPECT_LT(removed, 1e-20 * kept);
}

TEST(FbmNoise, FilterKeepsTheSameCoefficientsItDoesNotRemove) {
    // Low-passed noise equals the unfiltered noise with the high band removed: compare their
    // spectra inside the band (up to normalisation).
    NoiseParams a;
    a.timeSamples = 32;
    a.filter = NoiseFilter::None;
    NoiseParams b = a;
    b.filter = NoiseFilter::LowPass;
    b.cutoff = 10.0;
    const auto pa = powerSpectrum(FbmNoise(a, 64, 5).values(), 32, 64);
    const auto pb = powerSpectrum(FbmNoise(b, 64, 5).values(), 32, 64);
    double ratio = -1.0;
    for (int i = 0; i < 32; ++i) {
        for (int v = 0; v < 33; ++v) {
            if (radius(i, v, 32) == 0.0 || radius(i, v, 32) > 10.0)
                continue;
            const double r = pb[i * 33 + v] / pa[i * 33 + v];
            if (ratio < 0.0)
                ratio = r;
            EXPECT_NEAR(r / ratio, 1.0, 1e-9);
        }
    }
}

TEST(FbmNoise, SameSeedSameBits) {
    const NoiseParams p;
    const FbmNoise a(p, 256, 77);
    const FbmNoise b(p, 256, 77);
    ASSERT_EQ(a.values().size(), b.values().size());
    EXPECT_EQ(std::memcmp(a.values().data(), b.values().data(), a.values().size() * sizeof(double)),
              0);
}

TEST(FbmNoise, DifferentSeedsAreUncorrelated) {
    // White (beta 0) so that a sample correlation has a known spread, 1/sqrt(n) = 1/64.
    NoiseParams p;
    p.timeSamples = 64;
    p.beta = 0.0;
    p.filter = NoiseFilter::None;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const std::vector<double> a = FbmNoise(p, 64, seed).values();
        const std::vector<double> b = FbmNoise(p, 64, seed + 1).values();
        double sab = 0, saa = 0, sbb = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            sab += a[i] * b[i];
            saa += a[i] * a[i];
            sbb += b[i] * b[i];
        }
        EXPECT_LT(std::abs(sab / std::sqrt(saa * sbb)), 5.0 / 64.0)
            << "seeds " << seed << ", " << seed + 1;
    }
    // And the paper's noise differs visibly between neighbouring seeds.
    const NoiseParams paper;
    const std::vector<double> a = FbmNoise(paper, 256, 1).values();
    const std::vector<double> b = FbmNoise(paper, 256, 2).values();
    double maxDiff = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        maxDiff = std::max(maxDiff, std::abs(a[i] - b[i]));
    EXPECT_GT(maxDiff, 0.5);
}

TEST(FbmNoise, BadParametersThrowNamingTheKey) {
    NoiseParams p;
    p.beta = -1.0;
    try {
        FbmNoise(p, 256, 1);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("noise.beta"), std::string::npos);
    }
    NoiseParams q;
    q.cutoff = 0.5; // low-pass keeping only DC, which is always removed
    EXPECT_THROW(FbmNoise(q, 256, 1), std::invalid_argument);
    EXPECT_THROW(FbmNoise(NoiseParams{}, 1, 1), std::invalid_argument);
}

} // namespace swell::runtime
