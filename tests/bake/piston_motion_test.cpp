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
