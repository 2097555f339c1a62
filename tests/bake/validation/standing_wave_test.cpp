#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/validation/standing_wave.h"

using namespace swell::bake;
using namespace swell::bake::validation;

TEST(StandingWave, TheoryIsTheLinearDispersionRelation) {
    // The shipped scene: the 1 m tank's first mode (wavelength 2 m) in h = 0.5 m.
    const StandingWaveTheory t = standingWaveTheory(2.0, 0.5, 9.81);
    EXPECT_NEAR(t.wavenumber, std::numbers::pi, 1e-15);
    EXPECT_NEAR(t.kh, std::numbers::pi / 2.0, 1e-15);
    EXPECT_NEAR(t.omega * t.omega, 9.81 * t.wavenumber * std::tanh(t.kh), 1e-12);
    EXPECT_NEAR(t.period, 1.18182, 1e-5); // 2 pi / sqrt(9.81 pi tanh(pi / 2))
    // Deep water: omega^2 -> g k; shallow: omega -> k sqrt(g h).
    EXPECT_NEAR(standingWaveTheory(0.1, 10.0, 9.81).omega,
                std::sqrt(9.81 * 2.0 * std::numbers::pi / 0.1), 1e-9);
    const StandingWaveTheory shallow = standingWaveTheory(100.0, 0.1, 9.81);
    EXPECT_NEAR(shallow.omega / (shallow.wavenumber * std::sqrt(9.81 * 0.1)), 1.0, 1e-4);
    EXPECT_THROW(standingWaveTheory(0.0, 0.5, 9.81), std::invalid_argument);
    EXPECT_THROW(standingWaveTheory(2.0, -0.5, 9.81), std::invalid_argument);
    EXPECT_THROW(standingWaveTheory(2.0, 0.5, 0.0), std::invalid_argument);
}

TEST(StandingWave, SloshRecordRecoversPeriodAndDecayOfADampedCosine) {
    // eta = A exp(-lambda t) cos(omega t) + c, sampled at 1 ms over 5.3 periods.
    const double period = 1.2, lambda = 0.05, A = 0.02, c = 0.003;
    std::vector<double> t, eta;
    for (int k = 0; k <= 6360; ++k) {
        t.push_back(k * 1e-3);
        eta.push_back(A * std::exp(-lambda * t.back()) *
                          std::cos(2.0 * std::numbers::pi * t.back() / period) +
                      c);
    }
    const SloshRecord r = analyseSlosh(t, eta);
    ASSERT_EQ(r.crossings.size(), 5u);                     // at 0.9, 2.1, ... 5.7 s
    EXPECT_NEAR(r.crossings.front(), 0.75 * period, 1e-2); // of the record's mean, a little above c
    EXPECT_NEAR(r.period, period, 5e-4);
    ASSERT_EQ(r.amplitudes.size(), 4u);
    // Half the range from the crest at t = 1.2 s to the trough at 1.8 s.
    EXPECT_NEAR(r.amplitudes[0], 0.5 * A * (std::exp(-lambda * 1.2) + std::exp(-lambda * 1.8)),
                1e-6);
    EXPECT_NEAR(r.decayPerPeriod, 1.0 - std::exp(-lambda * period), 2e-3);

    // An undamped wave keeps its amplitude; a growing one reads a negative decay.
    for (std::size_t k = 0; k < t.size(); ++k)
        eta[k] = A * std::cos(2.0 * std::numbers::pi * t[k] / period);
    EXPECT_NEAR(analyseSlosh(t, eta).decayPerPeriod, 0.0, 1e-4);
    for (std::size_t k = 0; k < t.size(); ++k)
        eta[k] = A * std::exp(lambda * t[k]) * std::cos(2.0 * std::numbers::pi * t[k] / period);
    EXPECT_LT(analyseSlosh(t, eta).decayPerPeriod, -0.05);
}

TEST(StandingWave, SloshRecordRefusesTooShortOrMismatchedRecords) {
    std::vector<double> t, eta;
    for (int k = 0; k <= 2000; ++k) { // 1.7 periods: two upward crossings
        t.push_back(k * 1e-3);
        eta.push_back(std::cos(2.0 * std::numbers::pi * t.back() / 1.2));
    }
    EXPECT_THROW(analyseSlosh(t, eta), std::invalid_argument);
    eta.pop_back();
    EXPECT_THROW(analyseSlosh(t, eta), std::invalid_argument);
    EXPECT_THROW(analyseSlosh({}, {}), std::invalid_argument);
}
