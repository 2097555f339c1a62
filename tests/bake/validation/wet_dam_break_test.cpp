#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/bake/validation/wet_dam_break.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {

constexpr double kG = 9.81;
const std::filesystem::path kScenes = SWELL_SCENES_DIR;

/// Depth records of gauges at `gauges` sampled every `dt` to `tEnd` from `depth(dx, t)`.
template <class F>
std::vector<std::vector<double>> records(const std::vector<double>& gauges, double x0,
                                         const std::vector<double>& times, F depth) {
    std::vector<std::vector<double>> out;
    for (double x : gauges) {
        std::vector<double> h;
        for (double t : times)
            h.push_back(depth(x - x0, t));
        out.push_back(h);
    }
    return out;
}

std::vector<double> sampleTimes(double tEnd, double dt) {
    std::vector<double> t;
    for (int k = 0; k * dt <= tEnd + 1e-12; ++k)
        t.push_back(k * dt);
    return t;
}

} // namespace

TEST(WetDamBreak, StokerSatisfiesTheBoreAndFanConditions) {
    // The defining equations, written out here rather than through the solver's own helpers:
    // mass and momentum across the bore, the Riemann invariant u + 2 c = 2 c0 through the fan.
    for (double ratio : {0.05, 0.1, 0.2, 0.45, 0.8}) {
        const double h0 = 0.1, h1 = ratio * h0;
        const StokerDamBreak t = stokerDamBreak(h0, h1, kG);
        const double s = t.boreSpeed;
        EXPECT_NEAR(s * (t.h2 - h1), t.h2 * t.u2, 1e-12) << ratio;
        EXPECT_NEAR(s * t.h2 * t.u2, t.h2 * t.u2 * t.u2 + 0.5 * kG * (t.h2 * t.h2 - h1 * h1), 1e-12)
            << ratio;
        EXPECT_NEAR(t.u2 + 2.0 * std::sqrt(kG * t.h2), 2.0 * std::sqrt(kG * h0), 1e-12) << ratio;
        EXPECT_GT(t.h2, h1);
        EXPECT_LT(t.h2, h0);
        EXPECT_GT(s, std::sqrt(kG * h1)); // a bore outruns the layer's long waves
    }
    // The classic case h1 / h0 = 0.1, h0 = 1 m: 0.3962 m behind the bore (an independent
    // Python solution of the same equations, by bisection on the bore's speed, gives h2 =
    // 0.396175 m, S = 3.105134 m/s and u2 = 2.321355 m/s).
    const StokerDamBreak classic = stokerDamBreak(1.0, 0.1, kG);
    EXPECT_NEAR(classic.h2, 0.396175, 1e-6);
    EXPECT_NEAR(classic.boreSpeed, 3.105134, 1e-6);
    EXPECT_NEAR(classic.u2, 2.321355, 1e-6);
}

TEST(WetDamBreak, StokerDepthIsContinuousThroughTheFan) {
    const StokerDamBreak t = stokerDamBreak(0.1, 0.02, kG);
    const double time = 0.8, eps = 1e-9;
    const double head = -t.c0 * time, tail = (t.u2 - t.c2) * time, bore = t.boreSpeed * time;
    EXPECT_DOUBLE_EQ(t.depth(head - eps, time), 0.1);
    EXPECT_NEAR(t.depth(head + eps, time), 0.1, 1e-8);
    EXPECT_NEAR(t.depth(tail - eps, time), t.h2, 1e-8);
    EXPECT_NEAR(t.depth(tail + eps, time), t.h2, 1e-12);
    EXPECT_NEAR(t.depth(bore - eps, time), t.h2, 1e-12);
    EXPECT_DOUBLE_EQ(t.depth(bore + eps, time), 0.02);
    // In the fan the depth falls monotonically from h0 to h2.
    double last = 0.1;
    for (double dx = head; dx <= tail; dx += 0.01) {
        const double h = t.depth(dx, time);
        EXPECT_LE(h, last + 1e-15);
        last = h;
    }
    EXPECT_TRUE(t.behindBore(0.5 * (tail + bore), time));
    EXPECT_FALSE(t.behindBore(0.5 * (head + tail), time));
    EXPECT_FALSE(t.behindBore(bore + 0.01, time));
    // Before the gate goes: the step.
    EXPECT_DOUBLE_EQ(t.depth(-0.01, 0.0), 0.1);
    EXPECT_DOUBLE_EQ(t.depth(0.01, 0.0), 0.02);
    // As the layer deepens to h0 there is nothing left to break: S -> c0, h2 -> h0.
    const StokerDamBreak flat = stokerDamBreak(0.1, 0.0999999, kG);
    EXPECT_NEAR(flat.boreSpeed / flat.c0, 1.0, 1e-5);
    EXPECT_NEAR(flat.h2, 0.1, 1e-7);
}

TEST(WetDamBreak, StokerRejectsWhatIsNotAWetDamBreak) {
    EXPECT_THROW(stokerDamBreak(0.1, 0.0, kG), std::invalid_argument);   // dry bed: Ritter
    EXPECT_THROW(stokerDamBreak(0.1, 0.1, kG), std::invalid_argument);   // no step
    EXPECT_THROW(stokerDamBreak(0.1, 0.2, kG), std::invalid_argument);   // the layer deeper
    EXPECT_THROW(stokerDamBreak(0.1, 0.02, 0.0), std::invalid_argument); // no gravity
    EXPECT_THROW(stokerDamBreak(NAN, 0.02, kG), std::invalid_argument);
}

TEST(WetDamBreak, WindowsEndBeforeAReflectionCanReturn) {
    const StokerDamBreak t = stokerDamBreak(0.1, 0.02, kG);
    const std::vector<double> gauges{0.5, 1.5, 2.9};
    const auto w = stokerWindows(t, 0.0, 1.0, 3.0, 10.0, gauges);
    ASSERT_EQ(w.size(), 3u);
    const double from = kStokerFromTimes * std::sqrt(0.1 / kG);
    const double back = 1.0 / t.c0, forward = std::max(t.c0, t.u2 + t.c2);
    for (std::size_t g = 0; g < 3; ++g) {
        EXPECT_DOUBLE_EQ(w[g].first, from);
        EXPECT_LE(w[g].second, back + gauges[g] / forward + 1e-12);
    }
    // Beside the far wall the bore it sends back comes first: it reaches 2.9 m before the
    // back wall's reflection, and after the bore itself reached the wall.
    EXPECT_LT(w[2].second, back + 2.9 / forward);
    EXPECT_GT(w[2].second, 2.0 / t.boreSpeed);
    // ... at the speed W of the bore that brings (h2, u2) to rest at depth h3: mass gives h3
    // from W, and momentum across it must then hold.
    const double w3 = 0.1 / (w[2].second - 2.0 / t.boreSpeed);
    const double h3 = t.h2 + t.h2 * t.u2 / w3;
    EXPECT_NEAR(t.h2 * t.u2 * t.u2 + 0.5 * kG * t.h2 * t.h2 + w3 * t.h2 * t.u2, 0.5 * kG * h3 * h3,
                1e-9);
    // The run's end caps every window.
    for (const auto& [open, until] : stokerWindows(t, 0.0, 1.0, 3.0, 0.9, gauges))
        EXPECT_DOUBLE_EQ(until, 0.9);
    EXPECT_THROW(stokerWindows(t, 0.0, 1.0, 3.0, 2.0, std::vector<double>{3.5}),
                 std::invalid_argument);
    EXPECT_THROW(stokerWindows(t, 0.0, 1.0, 3.0, 2.0, std::vector<double>{0.0}),
                 std::invalid_argument);
    // A run that ends before 5 sqrt(h0 / g), or a reservoir so short that its reflection
    // returns before then: nothing to compare.
    EXPECT_THROW(stokerWindows(t, 0.0, 1.0, 3.0, 0.4, gauges), std::invalid_argument);
    EXPECT_THROW(stokerWindows(t, 0.9, 1.0, 3.0, 2.0, std::vector<double>{0.95}),
                 std::invalid_argument);
}

TEST(WetDamBreak, AnalysisReadsTheoryAsExactAndFindsAnOffsetAndASlowBore) {
    const StokerDamBreak t = stokerDamBreak(0.1, 0.02, kG);
    const std::vector<double> gauges{0.5, 1.0, 1.5, 1.75, 2.0, 2.25};
    const std::vector<double> times = sampleTimes(2.0, 1e-3);
    const auto windows = stokerWindows(t, 0.0, 1.0, 3.0, 2.0, gauges);
    const auto exact = [&](double dx, double time) { return t.depth(dx, time); };
    const WetDamBreakCheck c =
        analyseWetDamBreak(t, 1.0, gauges, times, records(gauges, 1.0, times, exact), windows);
    ASSERT_EQ(c.gauges.size(), gauges.size());
    EXPECT_EQ(c.boreGauges, 4u); // 1.5 m and beyond: their bore passes after the window opens
    EXPECT_NEAR(c.boreSpeedError, 0.0, 2e-3);
    EXPECT_NEAR(c.plateauDepthError, 0.0, 1e-12);
    EXPECT_LT(c.meanAbsErrorOverH0Worst, 2e-3);       // only the samples at the bore's step
    EXPECT_TRUE(std::isnan(c.gauges[0].boreArrival)); // upstream
    EXPECT_TRUE(std::isnan(c.gauges[1].boreArrival)); // at the gate the record never rises
    EXPECT_NEAR(c.gauges[2].boreArrival, 0.5 / t.boreSpeed, 1e-3);

    // Water 1 mm deeper everywhere: +1 % of h0 at every gauge, the plateau 2 % high.
    const auto deeper = [&](double dx, double time) { return t.depth(dx, time) + 0.001; };
    const WetDamBreakCheck d =
        analyseWetDamBreak(t, 1.0, gauges, times, records(gauges, 1.0, times, deeper), windows);
    for (const WetDamBreakGauge& g : d.gauges) {
        EXPECT_NEAR(g.meanSignedErrorOverH0, 0.01, 2e-3) << g.x;
        EXPECT_GT(g.meanAbsErrorOverH0, 0.008) << g.x;
    }
    EXPECT_NEAR(d.plateauDepthError, 0.001 / t.h2, 1e-9);

    // A bore 5 % slow: its speed reads -5 %.
    const auto slow = [&](double dx, double time) {
        return dx > 0.0 && dx > 0.95 * t.boreSpeed * time ? t.h1 : t.depth(dx, time);
    };
    const WetDamBreakCheck s =
        analyseWetDamBreak(t, 1.0, gauges, times, records(gauges, 1.0, times, slow), windows);
    EXPECT_NEAR(s.boreSpeedError, -0.05, 3e-3);
}

TEST(WetDamBreak, AnalysisRejectsRecordsItCannotRead) {
    const StokerDamBreak t = stokerDamBreak(0.1, 0.02, kG);
    const std::vector<double> gauges{1.5, 2.0};
    const std::vector<double> times = sampleTimes(2.0, 1e-3);
    const auto windows = stokerWindows(t, 0.0, 1.0, 3.0, 2.0, gauges);
    const auto exact = [&](double dx, double time) { return t.depth(dx, time); };
    auto h = records(gauges, 1.0, times, exact);
    h[1][1500] = NAN; // dry inside the window
    EXPECT_THROW(analyseWetDamBreak(t, 1.0, gauges, times, h, windows), std::invalid_argument);
    // No bore at one of the two gauges: its speed cannot be read.
    const auto still = [&](double dx, double time) { return dx > 0.7 ? t.h1 : t.depth(dx, time); };
    EXPECT_THROW(
        analyseWetDamBreak(t, 1.0, gauges, times, records(gauges, 1.0, times, still), windows),
        std::invalid_argument);
    h = records(gauges, 1.0, times, exact);
    h.pop_back();
    EXPECT_THROW(analyseWetDamBreak(t, 1.0, gauges, times, h, windows), std::invalid_argument);
}

TEST(WetDamBreak, RunRejectsScenesThatAreNotAWetDamBreak) {
    // Each before any step: an error naming the key.
    const Scene scene = loadScene(kScenes / "wet_dam_break_small.json");
    const auto key = [](const Scene& s) {
        try {
            runWetDamBreak(s);
        } catch (const SceneError& e) {
            return e.key();
        }
        return std::string("(accepted)");
    };
    Scene one = scene;
    one.geometry.water.pop_back();
    EXPECT_EQ(key(one), "geometry.water");
    Scene dry = scene; // the dry dam break is swell-validate dam-break's
    dry.geometry.water[1].x0 = 1.5;
    EXPECT_EQ(key(dry), "geometry.water");
    Scene deep = scene;
    deep.geometry.water[1].y1 = 0.15;
    EXPECT_EQ(key(deep), "geometry.water");
    Scene gauge = scene;
    gauge.output.gauges = {1.5};
    EXPECT_EQ(key(gauge), "output.gauges");
    Scene outside = scene;
    outside.output.gauges = {1.5, 3.5};
    EXPECT_EQ(key(outside), "output.gauges");
    Scene brief = scene; // ends before the windows open
    brief.run.endTime = 0.3;
    EXPECT_EQ(key(brief), "output.gauges");
    Scene weightless = scene;
    weightless.physics.gravity = 0.0;
    EXPECT_EQ(key(weightless), "physics.gravity");
}
