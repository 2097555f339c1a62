#include "swell/bake/piston_motion.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace swell::bake;

namespace {

PistonParams randomParams(std::uint64_t seed) {
    PistonParams p;
    p.kind = PistonKind::Random;
    p.periodMin = 0.8;
    p.periodMax = 1.6;
    p.strokeMin = 0.05;
    p.strokeMax = 0.15;
    p.rampTime = 1.0;
    p.seed = seed;
    return p;
}

} // namespace

TEST(PistonMotion, RandomCyclesStayInTheirRanges) {
    const PistonMotion m(randomParams(7), 60.0);
    ASSERT_GE(m.cycles().size(), 60.0 / 1.6);
    double t = 0.0;
    for (const auto& c : m.cycles()) {
        EXPECT_DOUBLE_EQ(c.start, t);
        EXPECT_GE(c.period, 0.8);
        EXPECT_LE(c.period, 1.6);
        EXPECT_GE(c.stroke, 0.05);
        EXPECT_LE(c.stroke, 0.15);
        t += c.period;
    }
    EXPECT_GT(t, 60.0);
}

TEST(PistonMotion, SeedDeterminesTheMotion) {
    const PistonMotion a(randomParams(7), 20.0), b(randomParams(7), 20.0), c(randomParams(8), 20.0);
    double diff = 0.0;
    for (double t = 0.0; t < 20.0; t += 0.01) {
        EXPECT_EQ(a.at(t).displacement, b.at(t).displacement);
        diff = std::max(diff, std::fabs(a.at(t).displacement - c.at(t).displacement));
    }
    EXPECT_GT(diff, 0.01);
}

TEST(PistonMotion, NoVelocityJumpsAndVelocityIsTheDerivative) {
    for (auto kind : {PistonKind::Random, PistonKind::Sinusoidal}) {
        PistonParams p = randomParams(3);
        p.kind = kind;
        const PistonMotion m(p, 30.0);
        const double h = 1e-5;
        double maxJump = 0.0;
        for (double t = 1e-3; t < 30.0; t += 1e-3) {
            const double fd = (m.at(t + h).displacement - m.at(t - h).displacement) / (2 * h);
            EXPECT_NEAR(m.at(t).velocity, fd, 1e-5) << "t = " << t;
            maxJump = std::max(maxJump, std::fabs(m.at(t + 1e-3).velocity - m.at(t).velocity));
        }
        // Largest acceleration: S/2 (2 pi / T)^2 <= 0.075 * 61.7 = 4.6 m/s^2, so 1 ms
        // changes the velocity by under 5 mm/s: a jump would show as more.
        EXPECT_LT(maxJump, 5e-3);
    }
}

TEST(PistonMotion, RampStartsFromRest) {
    for (auto kind : {PistonKind::Random, PistonKind::Sinusoidal}) {
        PistonParams p = randomParams(3);
        p.kind = kind;
        const PistonMotion m(p, 5.0);
        EXPECT_EQ(m.at(0.0).displacement, 0.0);
        EXPECT_EQ(m.at(0.0).velocity, 0.0);
        // Acceleration also starts at 0: velocity grows faster than linearly from 0.
        EXPECT_LT(std::fabs(m.at(1e-3).velocity), 1e-4);
    }
}

TEST(PistonMotion, SinusoidAfterRamp) {
    PistonParams p;
    p.kind = PistonKind::Sinusoidal;
    p.period = 1.2;
    p.stroke = 0.04;
    p.rampTime = 2.4;
    const PistonMotion m(p, 10.0);
    const double w = 2.0 * std::numbers::pi / 1.2;
    for (double t = 3.0; t < 10.0; t += 0.1) {
        EXPECT_NEAR(m.at(t).displacement, 0.02 * std::sin(w * t), 1e-12);
        EXPECT_NEAR(m.at(t).velocity, 0.02 * w * std::cos(w * t), 1e-12);
    }
}

TEST(PistonMotion, RejectsBadParametersNamingTheField) {
    PistonParams p = randomParams(1);
    p.periodMax = 0.5;
    try {
        PistonMotion m(p, 1.0);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("piston.period_max"), std::string::npos);
    }
    p = randomParams(1);
    p.strokeMin = -1;
    EXPECT_THROW(PistonMotion(p, 1.0), std::invalid_argument);
    p = PistonParams{};
    p.kind = PistonKind::Sinusoidal;
    p.period = 0.0;
    EXPECT_THROW(PistonMotion(p, 1.0), std::invalid_argument);
}

TEST(PistonMotion, MoreRandomCyclesThanTheLimitAreRefused) {
    PistonParams p = randomParams(1);
    p.periodMin = 1e-6;
    p.periodMax = 1e-6;
    try {
        PistonMotion m(p, 10.0); // 1e7 cycles
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("piston.period_min"), std::string::npos);
    }
    EXPECT_NO_THROW(PistonMotion(p, 0.5)); // 5e5 cycles
}

namespace {

PistonParams solitaryParams(double height, double depth) {
    PistonParams p;
    p.kind = PistonKind::Solitary;
    p.height = height;
    p.depth = depth;
    p.gravity = 9.81;
    return p;
}

} // namespace

TEST(PistonMotion, SolitaryStrokeIsGoringsAndItsVelocityTheWavesWater) {
    // H = 0.04 m in h = 0.2 m (scenes/solitary_wave.json): k = sqrt(3 H / (4 h^3)) = 1.936 /m,
    // c = sqrt(g (h + H)) = 1.534 m/s. Goring (1978): the stroke is about sqrt(16 H h / 3)
    // = 0.2066 m, and the piston is fastest under the crest, at c H / (h + H) = 0.2557 m/s.
    const PistonParams p = solitaryParams(0.04, 0.2);
    const SolitaryWaveShape w = solitaryWaveShape(p.height, p.depth, p.gravity);
    EXPECT_NEAR(w.wavenumber, std::sqrt(3.75), 1e-12);
    EXPECT_NEAR(w.celerity, std::sqrt(9.81 * 0.24), 1e-12);
    const PistonMotion m(p, 10.0);
    const double stroke = m.at(100.0).displacement;
    EXPECT_NEAR(stroke / std::sqrt(16.0 * 0.04 * 0.2 / 3.0), 1.0, 0.01) << stroke;
    EXPECT_EQ(m.at(100.0).velocity, 0.0);
    // The stroke ends where theta = k (c t - X) - 4 reaches 4.
    EXPECT_NEAR(w.wavenumber * (w.celerity * m.strokeEnd() - stroke), 8.0, 0.01);
    double fastest = 0.0, previous = 0.0;
    const double h = 1e-5;
    for (double t = 1e-3; t < m.strokeEnd() - 1e-3; t += 1e-3) {
        const PistonState s = m.at(t);
        EXPECT_GE(s.displacement, previous) << "t = " << t; // one forward stroke
        previous = s.displacement;
        const double fd = (m.at(t + h).displacement - m.at(t - h).displacement) / (2 * h);
        EXPECT_NEAR(s.velocity, fd, 1e-6) << "t = " << t;
        // dX/dt = c eta / (h + eta) with eta at the piston (the equation it integrates).
        const double sech =
            1.0 / std::cosh(w.wavenumber * (w.celerity * t - s.displacement) - kSolitaryHalfWidth);
        const double eta = p.height * sech * sech;
        EXPECT_NEAR(s.velocity, w.celerity * eta / (p.depth + eta), 1e-8) << "t = " << t;
        fastest = std::max(fastest, s.velocity);
    }
    EXPECT_NEAR(fastest, w.celerity * 0.04 / 0.24, 1e-4);
    // It starts and ends at 1.3e-3 of that speed (sech^2(4)): no ramp.
    EXPECT_LT(m.at(1e-9).velocity, 2e-3 * fastest);
}

TEST(PistonMotion, SolitaryRefusesHeightsThatBreakAndNamesTheField) {
    const auto fieldOf = [](const PistonParams& p) -> std::string {
        try {
            PistonMotion m(p, 1.0);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what()).substr(0, std::string(e.what()).find(':'));
        }
        return "";
    };
    EXPECT_EQ(fieldOf(solitaryParams(0.04, 0.2)), "");
    EXPECT_EQ(fieldOf(solitaryParams(0.78 * 0.2, 0.2)), "");              // McCowan's highest
    EXPECT_EQ(fieldOf(solitaryParams(0.79 * 0.2, 0.2)), "piston.height"); // breaks
    EXPECT_EQ(fieldOf(solitaryParams(0.0, 0.2)), "piston.height");
    EXPECT_EQ(fieldOf(solitaryParams(0.04, 0.0)), "piston.depth");
    EXPECT_EQ(fieldOf(solitaryParams(std::nan(""), 0.2)), "piston.height");
    EXPECT_THROW(solitaryWaveShape(0.04, 0.2, 0.0), std::invalid_argument);
}
