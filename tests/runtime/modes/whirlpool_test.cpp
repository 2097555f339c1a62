// The whirlpool's footprint filter, eye and funnel on synthetic caches (whirlpool.h), and
// its GPU path with time blending and a funnel against the CPU reference.
#include "swell/runtime/modes/whirlpool.h"

#include "swell/runtime/replay/picture_measures.h"

#include "synthetic_suite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace swell::runtime {
namespace {

class WhirlpoolTest : public test::SyntheticGlSuite {};

ReplayParams whirlpoolParams(bool paper) {
    ReplayParams p =
        paper ? paperDefaults(ReplayMode::Whirlpool) : swellDefaults(ReplayMode::Whirlpool);
    p = test::sized(96, 96, p.slices, p);
    p.policy = FramePolicy::Loop;
    p.timeSampling = paper ? TimeSampling::Nearest : TimeSampling::Linear;
    return p;
}

/// The paper's point sampling (no footprint filter): the two nearest spirals, each read
/// linearly between column centres at u.
HeightField pointSampled(const FrameSet& set, const ReplayParams& p, const SliceSampler& sampler,
                         const SpiralGeometry& geometry, double tau) {
    const CpuReconstruction profiles(set, p, sampler);
    const Grid& g = profiles.grid();
    const int J = g.sliceCount();
    HeightField out;
    out.cellsX = g.cellsX;
    out.cellsZ = g.cellsZ;
    const double spin = geometry.spinSlices(tau);
    auto along = [&](int j, double u) {
        const TimelineEntry& e = sampler.timeline()[sampler.entry(tau, j)];
        const double fu = std::clamp(u - 0.5, 0.0, g.cellsX - 1.0);
        const int n0 = std::min(static_cast<int>(fu), g.cellsX - 2);
        const double b = fu - n0;
        return (1.0 - b) * profiles.profile(e, n0) + b * profiles.profile(e, n0 + 1);
    };
    for (int m = 0; m < g.cellsZ; ++m) {
        for (int n = 0; n < g.cellsX; ++n) {
            const SpiralPoint q = geometry.at(n, m);
            double s = q.s - spin;
            if (s < 0.0)
                s += J;
            const int j0 = static_cast<int>(s) % J;
            const double a = s - std::floor(s);
            out.heights.push_back((1.0 - a) * along(j0, q.u) + a * along((j0 + 1) % J, q.u));
        }
    }
    return out;
}

} // namespace

TEST(Whirlpool, FootprintWeightsSumToOne) {
    for (double w : {1.0, 1.7, 6.0, 40.5, 255.0}) {
        for (double s : {0.0, 0.3, 7.77, 100.5}) {
            double sum = 0.0;
            for (int j = static_cast<int>(s - w) - 3; j <= static_cast<int>(s + w) + 3; ++j)
                sum += footprintWeight(j - s, w);
            EXPECT_NEAR(sum, 1.0, 1e-12) << "w " << w << " s " << s;
        }
    }
    // Width 1: the box of the hat, symmetric and peaked on the spiral itself.
    EXPECT_NEAR(footprintWeight(0.0, 1.0), 0.75, 1e-12);
    EXPECT_NEAR(footprintWeight(1.0, 1.0), 0.125, 1e-12);
    EXPECT_EQ(footprintWeight(2.0, 1.0), 0.0);
}

TEST_F(WhirlpoolTest, TheFootprintFilterLeavesNoNeedlesWherePointSamplingMakesThem) {
    const FrameSet& set = *s_frames;
    for (bool paper : {true, false}) {
        const ReplayParams p = whirlpoolParams(paper);
        const SliceSampler sampler = test::samplerOf(set, p);
        const WhirlpoolParams w;
        const CpuWhirlpool whirlpool(set, p, w, sampler);
        for (double tau : {0.1, 0.35}) {
            SCOPED_TRACE(::testing::Message() << (paper ? "paper" : "swell") << " tau " << tau);
            const double filtered = needleShare(whirlpool.heights(tau), 0.01);
            const double point =
                needleShare(pointSampled(set, p, sampler, whirlpool.geometry(), tau), 0.01);
            if (paper) {
                // Table 4's noise: neighbouring spirals show frames far apart; the paper's
                // sampling aliases them into needles, the filter cuts them to a fraction.
                EXPECT_GT(point, 0.01);
                EXPECT_LT(filtered, 0.25 * point);
            } else {
                EXPECT_LE(filtered, 0.001); // the target: at most 0.1 % needle cells
            }
        }
    }
}

TEST_F(WhirlpoolTest, TheEyeIsSteadierThanTheBakeAndTheFunnelHasItsDepth) {
    const FrameSet& set = *s_frames;
    ReplayParams p = whirlpoolParams(false);
    const SliceSampler sampler = test::samplerOf(set, p);
    WhirlpoolParams flat;
    WhirlpoolParams funnel;
    funnel.eyeDepth = 0.2;
    const CpuWhirlpool a(set, p, flat, sampler), b(set, p, funnel, sampler);
    // The bake's own change: every slice the same frame (F = 0), one output frame apart.
    ReplayParams still = p;
    still.fluctuation = 0.0;
    const SliceSampler stillSampler = test::samplerOf(set, still);
    const CpuReconstruction bake(set, still, stillSampler);
    const double cn = 48.0, cm = 48.0, radius = 0.5 * 15.0; // a / 2, cells
    const double step = 1.0 / 30.0 / p.timeUnitSeconds;     // 30 frames per simulated second
    for (double tau = 0.1; tau < 0.3; tau += step) {
        const HeightField h0 = a.heights(tau), h1 = a.heights(tau + step);
        const double eyeChange =
            std::abs(discMean(h1, cn, cm, radius) - discMean(h0, cn, cm, radius));
        const double bakeChange = meanChange(bake.heights(tau + step), bake.heights(tau));
        EXPECT_LE(eyeChange, bakeChange) << "tau " << tau;
        // The funnel: exactly d(r) lower.
        const HeightField f = b.heights(tau);
        for (int m = 0; m < 96; m += 7) {
            for (int n = 0; n < 96; n += 5)
                EXPECT_NEAR(h0.at(n, m) - f.at(n, m), b.geometry().at(n, m).dip, 1e-12);
        }
    }
    // D at the centre, the Rankine parabola inside the eye, nothing beyond R.
    const SpiralGeometry& g = b.geometry();
    EXPECT_NEAR(g.at(47, 47).dip, 0.2, 0.2 * 0.01);
    EXPECT_EQ(g.at(0, 0).dip, 0.0);         // the corner lies beyond R = 51 cells
    const double r = std::hypot(14.5, 0.5); // cell (62, 48) from the centre, cells
    EXPECT_NEAR(g.at(62, 48).dip, 0.2 * (1.0 - r * r / (2.0 * 15.0 * 15.0)), 1e-12);
}

TEST_F(WhirlpoolTest, GpuWithTimeBlendingAndAFunnelMatchesTheCpuReference) {
    const FrameSet& set = *s_frames;
    const ReplayParams p = whirlpoolParams(false);
    const SliceSampler sampler = test::samplerOf(set, p);
    WhirlpoolParams w;
    w.eyeDepth = 0.1;
    const CpuWhirlpool cpu(set, p, w, sampler);
    GpuWhirlpool gpu(set, p, w, sampler);
    for (double tau : {0.0, 0.123, 0.4567}) {
        gpu.update(tau);
        HeightDifference d;
        d.add(gpu.readHeights(), cpu.heights(tau));
        EXPECT_LE(d.maxAbs, 1e-5 * test::kSyntheticDepth) << "tau " << tau;
    }
}

} // namespace swell::runtime
