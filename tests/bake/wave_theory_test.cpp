#include "swell/bake/wave_theory.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace swell::bake;

TEST(WaveTheory, DispersionRelationHolds) {
    const double g = 9.81;
    for (double h : {0.05, 0.3, 1.0, 10.0})
        for (double T : {0.5, 1.0, 2.0, 8.0}) {
            const double w = 2.0 * std::numbers::pi / T;
            const double k = dispersionWavenumber(w, h, g);
            EXPECT_NEAR(w * w, g * k * std::tanh(k * h), 1e-12 * w * w) << "h " << h << " T " << T;
        }
}

TEST(WaveTheory, DispersionLimits) {
    const double g = 9.81, w = 2.0 * std::numbers::pi;
    // Deep water: k = w^2 / g.
    EXPECT_NEAR(dispersionWavenumber(w, 100.0, g), w * w / g, 1e-9);
    // Shallow water: k -> w / sqrt(g h).
    const double h = 1e-4;
    EXPECT_NEAR(dispersionWavenumber(w, h, g), w / std::sqrt(g * h), 1e-3 * w / std::sqrt(g * h));
    EXPECT_THROW(dispersionWavenumber(0.0, 1.0, g), std::invalid_argument);
    EXPECT_THROW(dispersionWavenumber(w, -1.0, g), std::invalid_argument);
}

TEST(WaveTheory, GroupVelocity) {
    const double g = 9.81, twoPi = 2.0 * std::numbers::pi;
    // T = 1 s, h = 0.3 m: kh = 1.37292, c = 1.37296 m/s, c_g = c/2 (1 + 2kh / sinh 2kh) = 0.929481
    // m/s (computed independently, Python).
    EXPECT_NEAR(groupVelocity(twoPi / 1.0, 0.3, g), 0.929481, 1e-6);
    // Deep water: c_g = c / 2 = g T / (4 pi).
    EXPECT_NEAR(groupVelocity(twoPi / 1.0, 100.0, g), g / (4.0 * std::numbers::pi), 1e-9);
    // Shallow water (T = 100 s, h = 1 cm, kh = 0.002): c_g = sqrt(g h), non-dispersive.
    EXPECT_NEAR(groupVelocity(twoPi / 100.0, 0.01, g), std::sqrt(g * 0.01), 1e-5);
    // Group velocity below phase velocity at finite depth.
    const double w = twoPi / 1.0, k = dispersionWavenumber(w, 0.3, g);
    EXPECT_LT(groupVelocity(w, 0.3, g), w / k);
    EXPECT_THROW(groupVelocity(w, 0.0, g), std::invalid_argument);
}

TEST(WaveTheory, BieselTransferFunction) {
    // Values of 2 (cosh 2kh - 1) / (sinh 2kh + 2kh), computed independently (Python).
    EXPECT_NEAR(pistonHeightOverStroke(1.0), 0.981789, 1e-6);
    EXPECT_NEAR(pistonHeightOverStroke(1.5), 1.393109, 1e-6);
    EXPECT_NEAR(pistonHeightOverStroke(20.0), 2.0, 1e-12);       // deep water: H = 2 S
    EXPECT_NEAR(pistonHeightOverStroke(1e-3) / 1e-3, 1.0, 1e-3); // shallow water: H/S = kh
}

TEST(WaveTheory, PistonWaveAndBreakingLimit) {
    EXPECT_NEAR(micheLimitSteepness(50.0), 0.142, 1e-12);
    const auto calm = linearPistonWave(0.02, 1.0, 0.3, 9.81);
    EXPECT_NEAR(calm.wavelength, 2.0 * std::numbers::pi / calm.wavenumber, 1e-12);
    EXPECT_NEAR(calm.height, 0.02 * pistonHeightOverStroke(calm.kh), 1e-15);
    EXPECT_FALSE(calm.breaks());
    const auto steep = linearPistonWave(0.3, 0.6, 0.3, 9.81);
    EXPECT_TRUE(steep.breaks());
}
