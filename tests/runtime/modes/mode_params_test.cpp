// Mode parameters and the ripple / whirlpool geometry against known answers (CPU only).
#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/modes/ripple.h"
#include "swell/runtime/modes/whirlpool.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <set>
#include <string>

namespace swell::runtime {
namespace {

using json = nlohmann::json;
constexpr double kPi = std::numbers::pi;

Grid squareGrid(int N, int K) {
    Grid g;
    g = test::sized(N, N, K, g);
    g.x0 = -3.0;
    g.dx = 0.5;
    g.dz = 0.5;
    g.extentZ = N * 0.5;
    return g;
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "no exception";
}

} // namespace

TEST(ReplayMode, NamesRoundTripAndBadNamesAreNamed) {
    for (ReplayMode m : {ReplayMode::Surging, ReplayMode::Ripple, ReplayMode::Whirlpool})
        EXPECT_EQ(replayModeFromString(toString(m)), m);
    EXPECT_NE(messageOf([] { replayModeFromString("tsunami"); }).find("mode"), std::string::npos);
}

TEST(ReplayMode, PaperDefaultsAreTable4) {
    const ReplayParams s = paperDefaults(ReplayMode::Surging);
    EXPECT_EQ(s.slices, 256);
    EXPECT_EQ(s.fluctuation, 0.3);
    EXPECT_EQ(s.noise.beta, 2.0);
    EXPECT_EQ(s.noise.cutoff, 128.0);
    const ReplayParams r = paperDefaults(ReplayMode::Ripple);
    EXPECT_EQ(r.slices, 256);
    EXPECT_EQ(r.fluctuation, 0.4);
    EXPECT_EQ(r.noise.beta, 2.5);
    EXPECT_EQ(r.noise.cutoff, 128.0);
    const ReplayParams w = paperDefaults(ReplayMode::Whirlpool);
    EXPECT_EQ(w.slices, 128);
    EXPECT_EQ(w.fluctuation, 0.4);
    EXPECT_EQ(w.noise.beta, 2.5);
    EXPECT_EQ(w.noise.cutoff, 64.0);
    const ModeParams m;
    ASSERT_EQ(m.ripple.anglesDegrees.size(), 2u); // two directions, 30 degrees apart
    EXPECT_EQ(m.ripple.anglesDegrees[1] - m.ripple.anglesDegrees[0], 30.0);
    EXPECT_EQ(m.ripple.normalisedWeights(), (std::vector<double>{0.5, 0.5})); // the mean
}

TEST(ReplayMode, JsonRoundTripAndErrorsNameTheKey) {
    ModeParams p;
    p.mode = ReplayMode::Ripple;
    p.ripple.anglesDegrees = {-10.0, 20.0, 75.0};
    p.ripple.weights = {1.0, 2.0, 1.0};
    p.whirlpool.growth = 0.3;
    const ModeParams q = modeParamsFromJson(toJson(p));
    EXPECT_EQ(toJson(q), toJson(p));
    EXPECT_EQ(q.ripple.normalisedWeights(), (std::vector<double>{0.25, 0.5, 0.25}));

    EXPECT_NE(messageOf([] {
                  modeParamsFromJson(json{{"speed", 1}});
              }).find("speed"),
              std::string::npos);
    EXPECT_NE(messageOf([] {
                  modeParamsFromJson(json{{"mode", "ripple"}, {"ripple", {{"weights", {1.0}}}}});
              }).find("ripple.weights"),
              std::string::npos);
    EXPECT_NE(
        messageOf([] {
            modeParamsFromJson(json{{"mode", "ripple"}, {"ripple", {{"weights", {-1.0, 2.0}}}}});
        }).find("ripple.weights"),
        std::string::npos);
    EXPECT_NE(messageOf([] {
                  modeParamsFromJson(
                      json{{"mode", "ripple"}, {"ripple", {{"angles_degrees", json::array()}}}});
              }).find("ripple.angles"),
              std::string::npos);
    EXPECT_NE(messageOf([] {
                  modeParamsFromJson(json{{"mode", "whirlpool"}, {"whirlpool", {{"growth", 0.0}}}});
              }).find("whirlpool.growth"),
              std::string::npos);
    EXPECT_NE(messageOf([] {
                  modeParamsFromJson(
                      json{{"mode", "whirlpool"}, {"whirlpool", {{"inner_radius_cells", "x"}}}});
              }).find("whirlpool.inner_radius_cells"),
              std::string::npos);
}

TEST(ReplayMode, SliceSetSeedsAreTheRunSeedFirstThenDistinct) {
    EXPECT_EQ(sliceSetSeed(77, 0), 77u);
    std::set<std::uint64_t> seen;
    for (std::uint64_t seed : {1ull, 2ull, 77ull}) {
        for (int d = 0; d < 6; ++d)
            seen.insert(sliceSetSeed(seed, d));
    }
    EXPECT_EQ(seen.size(), 18u);
    EXPECT_EQ(sliceSetSeed(5, 3), sliceSetSeed(5, 3)); // a function of (seed, d) only
    ModeParams mode;
    mode.mode = ReplayMode::Ripple;
    mode.ripple.anglesDegrees = {0.0, 30.0, 60.0};
    ReplayParams p;
    p.slices = 16;
    const auto samplers = makeSamplers(p, mode, 100, 10.0);
    ASSERT_EQ(samplers.size(), 3u);
    EXPECT_NE(samplers[0].noise()->values(), samplers[1].noise()->values());
    const std::vector<double> taus{0.1, 0.2};
    const auto used = framesUsed(samplers, taus);
    for (const SliceSampler& s : samplers) {
        for (std::uint32_t f : s.framesUsed(taus))
            EXPECT_TRUE(std::binary_search(used.begin(), used.end(), f));
    }
}

TEST(RippleTaps, ZeroDegreesReadsTheCellItself) {
    const Grid g = squareGrid(12, 8);
    RippleParams r;
    r.anglesDegrees = {0.0};
    const auto taps = rippleTaps(g, r);
    for (int m = 0; m < 12; ++m) {
        for (int n = 0; n < 12; ++n) {
            const RippleTap& t = taps[static_cast<std::size_t>(m * 12 + n)];
            // bilinear weight 1 on (n, m): (n0, fx) = (n, 0) or (n - 1, 1) at the last column
            EXPECT_NEAR(t.n0 + t.fx, n, 1e-12);
            EXPECT_NEAR(t.m0 + t.fz, m, 1e-12);
            EXPECT_TRUE(t.inside);
            EXPECT_EQ(t.weight, 1.0);
        }
    }
}

TEST(RippleTaps, NinetyDegreesOnASquareMeshIsACellPermutation) {
    // q = R(-90) (P - C) + C: u = m + 1/2, v = N - n - 1/2, exactly on cell centres.
    const int N = 10;
    const Grid g = squareGrid(N, 8);
    RippleParams r;
    r.anglesDegrees = {0.0, 90.0};
    r.weights = {3.0, 1.0};
    const auto taps = rippleTaps(g, r);
    for (int m = 0; m < N; ++m) {
        for (int n = 0; n < N; ++n) {
            const RippleTap& t = taps[static_cast<std::size_t>(m * N + n) * 2 + 1];
            const double col = t.fx < 0.5 ? t.n0 + t.fx : t.n1 - (1.0 - t.fx);
            EXPECT_NEAR(col, m, 1e-9);
            const double d = std::fmod(t.m0 + t.fz - (N - 1 - n) + 2.0 * N, N); // periodic
            EXPECT_NEAR(std::min(d, N - d), 0.0, 1e-9);
            EXPECT_EQ(t.weight, 0.25);
            EXPECT_EQ(taps[static_cast<std::size_t>(m * N + n) * 2].weight, 0.75);
        }
    }
}

TEST(RippleTaps, CornersOutsideARotatedGridWrapAcrossAndClampAlong) {
    const int N = 16;
    const Grid g = squareGrid(N, 8);
    RippleParams r;
    r.anglesDegrees = {30.0};
    const auto taps = rippleTaps(g, r);
    int outside = 0;
    for (int m = 0; m < N; ++m) {
        for (int n = 0; n < N; ++n) {
            const RippleTap& t = taps[static_cast<std::size_t>(m * N + n)];
            EXPECT_EQ(t.weight, 1.0);
            EXPECT_GE(t.n0, 0);
            EXPECT_LT(t.n1, N);
            EXPECT_GE(t.m0, 0);
            EXPECT_LT(t.m0, N);
            EXPECT_EQ(t.m1, (t.m0 + 1) % N); // periodic along the transverse axis
            EXPECT_GE(t.fx, 0.0);
            EXPECT_LE(t.fx, 1.0);
            EXPECT_GE(t.fz, 0.0);
            EXPECT_LT(t.fz, 1.0);
            outside += t.inside ? 0 : 1;
        }
    }
    // Rotating a square by 30 degrees leaves its four corners outside.
    EXPECT_GT(outside, 4);
    EXPECT_FALSE(taps[0].inside);
    EXPECT_FALSE(taps[static_cast<std::size_t>(N * N - 1)].inside);
    EXPECT_TRUE(taps[static_cast<std::size_t>((N / 2) * N + N / 2)].inside);
}

TEST(SpiralGeometry, CellsLieOnTheSpiralOfTheirSliceCoordinate) {
    const int N = 120;
    const Grid g = squareGrid(N, 8); // J = 15
    WhirlpoolParams w;
    w.innerRadiusCells = 10.0;
    w.growth = 0.2;
    const SpiralGeometry geo(g, w);
    EXPECT_NEAR(geo.innerRadius(), 10.0 * g.dx, 1e-12);
    EXPECT_NEAR(geo.outerRadius(), 10.0 * g.dx * std::exp(2.0 * kPi * 0.2), 1e-12);
    EXPECT_NEAR(geo.centreX(), g.x0 + 60.0 * g.dx, 1e-12);
    const int J = geo.sliceCount();
    ASSERT_EQ(J, 15);
    int onSpiral = 0, eye = 0, rim = 0;
    for (int m = 0; m < N; ++m) {
        for (int n = 0; n < N; ++n) {
            const SpiralPoint p = geo.at(n, m);
            const double x = g.x0 + (n + 0.5) * g.dx;
            const double z = (m + 0.5) * g.dz;
            const double r = std::hypot(x - geo.centreX(), z - geo.centreZ());
            ASSERT_GE(p.s, 0.0);
            ASSERT_LT(p.s, J);
            ASSERT_GE(p.u, 0.0);
            ASSERT_LE(p.u, N);
            if (r < geo.innerRadius()) {
                EXPECT_EQ(p.u, 0.0);
                ++eye;
                continue;
            }
            // The slice-s spiral at parameter t passes through the cell: r = a e^(b t) at
            // angle 2 pi s / J + t.
            const double angle = 2.0 * kPi * p.s / J + p.t;
            EXPECT_NEAR(geo.innerRadius() * std::exp(w.growth * p.t), r, 1e-9);
            EXPECT_NEAR(geo.centreX() + r * std::cos(angle), x, 1e-9);
            EXPECT_NEAR(geo.centreZ() + r * std::sin(angle), z, 1e-9);
            if (r <= geo.outerRadius()) {
                EXPECT_NEAR(p.u, N * p.t / (2.0 * kPi), 1e-9); // x runs along the spiral
                ++onSpiral;
            } else {
                EXPECT_NEAR(p.u, N, 1e-12); // beyond R: the outer end
                ++rim;
            }
        }
    }
    EXPECT_GT(onSpiral, 1000);
    EXPECT_GT(eye, 100);
    EXPECT_GT(rim, 100);
}

TEST(SpiralGeometry, SpinTurnsTheSpiralsWithAnimationTime) {
    const Grid g = squareGrid(32, 64); // J = 127
    WhirlpoolParams w;
    w.turnsPerTimeUnit = 0.125;
    const SpiralGeometry geo(g, w);
    EXPECT_NEAR(geo.spinSlices(0.0), 0.0, 1e-12);
    EXPECT_NEAR(geo.spinSlices(4.0), 127.0 / 2.0, 1e-9); // half a turn
    EXPECT_NEAR(geo.spinSlices(8.0), 0.0, 1e-9);         // a whole turn
    EXPECT_NEAR(geo.spinSlices(-2.0), 127.0 * 0.75, 1e-9);
    w.turnsPerTimeUnit = 0.0;
    EXPECT_EQ(SpiralGeometry(g, w).spinSlices(123.4), 0.0);
}

TEST(CpuWhirlpool, WithoutNoiseTheHeightDependsOnTheRadiusOnly) {
    // F = 0: every spiral shows the same frame, so the field is the profile at u(r).
    const FrameSet set = test::syntheticSet(60, 240, 9);
    ReplayParams p = paperDefaults(ReplayMode::Whirlpool);
    p = test::sized(40, 40, 32, p);
    p.fluctuation = 0.0;
    const SliceSampler s = test::samplerOf(set, p);
    const CpuWhirlpool cpu(set, p, WhirlpoolParams{}, s);
    const HeightField h = cpu.heights(0.05);
    double spread = 0.0;
    for (int m = 0; m < 40; ++m) {
        for (int n = 0; n < 40; ++n) {
            ASSERT_TRUE(std::isfinite(h.at(n, m)));
            EXPECT_NEAR(h.at(n, m), h.at(39 - n, 39 - m), 1e-12); // same r
            EXPECT_NEAR(h.at(n, m), h.at(m, n), 1e-12);           // same r
            spread = std::max(spread, std::abs(h.at(n, m) - h.at(20, 20)));
        }
    }
    EXPECT_GT(spread, 0.01); // but not flat: the profile varies along the spiral
}

} // namespace swell::runtime
