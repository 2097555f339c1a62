#include "swell/runtime/replay/cpu_reconstruction.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

namespace swell::runtime {
namespace {

/// A cache over x in [0, 16] m with the given frames; with cellsX = 16, one cell is 1 m, so
/// cell units are metres.
FrameSet frameSet(std::vector<cache::Frame> frames, float yMin = 0.0f) {
    cache::Header h;
    h.domain = {0.0f, yMin, 16.0f, 2.0f};
    h.dt = 0.001;
    h.frameInterval = 10;
    return FrameSet::whole(h, std::move(frames));
}

ReplayParams smallParams(int N = 16, int M = 8, int K = 4, double F = 0.0) {
    ReplayParams p = test::sized(N, M, K, ReplayParams{});
    p.fluctuation = F;
    return p;
}

cache::Frame frameOf(std::initializer_list<std::pair<float, float>> particles) {
    cache::Frame f;
    for (auto [x, h] : particles) {
        f.surface.push_back(x);
        f.surface.push_back(h);
    }
    return f;
}

double gauss(double d) {
    return std::exp(-d * d / 8.0);
} // sigma = 2 cells

} // namespace

TEST(WindowSlices, KnownAnswers) {
    Grid g;
    g.cellsZ = 128;
    g.slices = 256;                                                   // slices at (j + 1) / 4 cells
    EXPECT_EQ(windowSlices(g, 0), (std::vector<int>{0, 1, 2, 3, 4})); // [-0.5, 1.5)
    EXPECT_EQ(windowSlices(g, 10),
              (std::vector<int>{37, 38, 39, 40, 41, 42, 43, 44})); // [9.5, 11.5)
    EXPECT_EQ(windowSlices(g, 127).back(), 510);                   // last slice, z = 127.75
    g.cellsZ = 200;
    g.slices = 16; // slices at 6.25 (j + 1) cells: many rows see none
    EXPECT_EQ(windowSlices(g, 3), (std::vector<int>{0}));  // [2.5, 4.5): nearest is z = 6.25
    EXPECT_EQ(windowSlices(g, 6), (std::vector<int>{0}));  // [5.5, 7.5) holds z = 6.25
    EXPECT_EQ(windowSlices(g, 9), (std::vector<int>{1}));  // 9.5: 12.5 is nearer than 6.25
    EXPECT_EQ(windowSlices(g, 10), (std::vector<int>{1})); // 10.5: nearest 12.5
}

TEST(CpuReconstruction, FlatWaterStaysFlatEverywhere) {
    auto frames = test::syntheticFrames(40, 60, 3);
    for (auto& f : frames) {
        for (std::size_t p = 1; p < f.surface.size(); p += 2)
            f.surface[p] = 0.37f;
    }
    frames[5].surface = {0.0f, 0.37f}; // not empty: an empty frame would give yMin
    const FrameSet set = frameSet(frames);
    ReplayParams p = smallParams(23, 11, 9, 0.5);
    p.policy = FramePolicy::Loop;
    const SliceSampler s(p, set.frameCount, 100.0);
    const CpuReconstruction cpu(set, p, s);
    for (double tau : {0.0, 0.13, 0.31}) {
        const HeightField h = cpu.heights(tau);
        for (double v : h.heights)
            EXPECT_NEAR(v, static_cast<double>(0.37f), 1e-12);
    }
}

TEST(CpuReconstruction, LinearProfileIsReproducedExactly) {
    // One particle at each bin centre, h linear in x: the window is symmetric about P, so the
    // Gaussian-weighted mean (eq. 7) is the value at P.
    cache::Frame f;
    for (int i = 0; i < 16; ++i) {
        f.surface.push_back(i + 0.5f);
        f.surface.push_back(0.25f + 0.0625f * i);
    }
    const FrameSet set = frameSet({f});
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    const HeightField h = CpuReconstruction(set, p, s).heights(0.0);
    for (int m = 0; m < 8; ++m) {
        for (int n = 1; n < 15; ++n)
            EXPECT_NEAR(h.at(n, m), 0.25 + 0.0625 * n, 1e-12) << n;
    }
}

TEST(CpuReconstruction, WindowIsThreeBinsHalfOpenWithGaussianWeights) {
    // A at x = 5.0 (bin 5, not 4), C at 6.2 (bin 6), B at 8.99 (bin 8).
    const FrameSet set = frameSet({frameOf({{5.0f, 1.0f}, {6.2f, 3.0f}, {8.99f, 2.0f}})});
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    const HeightField h = CpuReconstruction(set, p, s).heights(0.0);
    const double c = static_cast<double>(6.2f), b = static_cast<double>(8.99f);
    for (int m = 0; m < 8; ++m) {
        EXPECT_DOUBLE_EQ(h.at(4, m), 1.0); // bins 3..5: A
        EXPECT_NEAR(h.at(6, m),
                    (gauss(5.0 - 6.5) * 1 + gauss(c - 6.5) * 3) /
                        (gauss(5.0 - 6.5) + gauss(c - 6.5)),
                    1e-12);
        EXPECT_NEAR(h.at(7, m),
                    (gauss(c - 7.5) * 3 + gauss(b - 7.5) * 2) / (gauss(c - 7.5) + gauss(b - 7.5)),
                    1e-12);
        EXPECT_DOUBLE_EQ(h.at(9, m), 2.0);  // bins 8..10: B
        EXPECT_DOUBLE_EQ(h.at(3, m), 1.0);  // bins 2..4 empty: nearest non-empty bin 5 (d = 2)
        EXPECT_DOUBLE_EQ(h.at(12, m), 2.0); // bins 11..13 empty; d = 4 reaches bin 8
    }
}

TEST(CpuReconstruction, FallbackAveragesTheNearestBinsOnBothSides) {
    const FrameSet set = frameSet({frameOf({{2.5f, 1.0f}, {2.7f, 1.5f}, {10.5f, 3.0f}})});
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    const HeightField h = CpuReconstruction(set, p, s).heights(0.0);
    EXPECT_DOUBLE_EQ(h.at(6, 0), (1.0 + 1.5 + 3.0) / 3.0); // d = 4: bins 2 and 10
    EXPECT_DOUBLE_EQ(h.at(15, 0), 3.0);                    // d = 5: bin 10 only
    for (double v : h.heights)
        EXPECT_TRUE(std::isfinite(v));
}

TEST(CpuReconstruction, EmptyFrameGivesTheDomainBottom) {
    const FrameSet set = frameSet({cache::Frame{}}, 0.1f);
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    const HeightField h = CpuReconstruction(set, p, s).heights(0.0);
    for (double v : h.heights)
        EXPECT_DOUBLE_EQ(v, static_cast<double>(0.1f));
}

TEST(CpuReconstruction, ParticlesJustBeyondTheDomainReachTheEdgeColumns) {
    const FrameSet set = frameSet({frameOf({{-0.5f, 1.0f}, {16.5f, 2.0f}, {8.0f, 5.0f}})});
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    const HeightField h = CpuReconstruction(set, p, s).heights(0.0);
    EXPECT_DOUBLE_EQ(h.at(0, 0), 1.0);  // bin -1 is in column 0's window
    EXPECT_DOUBLE_EQ(h.at(15, 0), 2.0); // bin 16 is in column 15's window
}

TEST(CpuReconstruction, MatchesABruteForceEq7OverContinuousWindows) {
    // Different frames per slice (F > 0); the test sums eq. (7) over every particle of every
    // slice, choosing the window with real-valued |x - P_x| and z - P_z tests (powers of two
    // keep them exact), which must agree with the integer window definitions.
    auto frames = test::syntheticFrames(120, 90, 5);
    cache::Header hdr = test::syntheticHeader();
    const FrameSet set = FrameSet::whole(hdr, frames);
    ReplayParams p = smallParams(32, 16, 16, 0.4);
    p.policy = FramePolicy::Clamp;
    const SliceSampler s(p, set.frameCount, 200.0);
    const CpuReconstruction cpu(set, p, s);
    const double dx = 4.0 / 32;
    for (double tau : {0.2, 0.35}) {
        const HeightField h = cpu.heights(tau);
        const auto slice = s.frames(tau);
        std::set<std::uint32_t> distinct(slice.begin(), slice.end());
        EXPECT_GT(distinct.size(), 3u);
        int checked = 0;
        for (int m = 0; m < 16; ++m) {
            for (int n = 0; n < 32; ++n) {
                double sgh = 0, sg = 0;
                for (int j = 0; j < 31; ++j) {
                    const double dz = (j + 1) * 16.0 / 32.0 - (m + 0.5);
                    if (dz < -1.0 || dz >= 1.0)
                        continue;
                    const auto& sf = frames[slice[static_cast<std::size_t>(j)]].surface;
                    for (std::size_t q = 0; q < sf.size(); q += 2) {
                        const double u = sf[q] / dx;
                        const double ddx = u - (n + 0.5);
                        if (ddx < -1.5 || ddx >= 1.5)
                            continue; // [3 dx) centred on P
                        const double g = std::exp(-(ddx * ddx + dz * dz) / 8.0);
                        sgh += g * sf[q + 1];
                        sg += g;
                    }
                }
                if (sg > 0) {
                    EXPECT_NEAR(h.at(n, m), sgh / sg, 1e-12) << n << "," << m;
                    ++checked;
                }
            }
        }
        EXPECT_GT(checked, 400);
    }
}

TEST(CpuReconstruction, NonFiniteParticlesAreRejected) {
    const FrameSet set = frameSet({frameOf({{1.0f, std::nanf("")}})});
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 1, 100.0);
    EXPECT_THROW(CpuReconstruction(set, p, s), std::invalid_argument);
}

TEST(CpuReconstruction, AFrameOutsideTheSetIsAnError) {
    FrameSet set = frameSet({cache::Frame{}, cache::Frame{}, cache::Frame{}});
    set.ids = {0};
    set.frames.resize(1);
    const ReplayParams p = smallParams();
    const SliceSampler s(p, 3, 1.0);
    const CpuReconstruction cpu(set, p, s);
    EXPECT_NO_THROW(cpu.heights(0.0));
    EXPECT_THROW(cpu.heights(2.0), std::invalid_argument);
}

} // namespace swell::runtime

namespace swell::runtime {

TEST(CpuReconstruction, LinearTimeSamplingShowsTheHalfWayProfile) {
    // A travelling wave stored every frame: at a time half-way between two stored frames the
    // replay shows the mean of their profiles (envelope columns are exact), nearest sampling
    // shows one of them, and on a stored frame both agree.
    std::vector<cache::Frame> frames;
    for (int f = 0; f < 8; ++f) {
        cache::Frame fr;
        for (int i = 0; i <= 64; ++i) {
            const double x = 0.25 * i;
            fr.surface.push_back(static_cast<float>(x));
            fr.surface.push_back(static_cast<float>(1.0 + 0.2 * std::sin(0.8 * x - 0.5 * f)));
        }
        frames.push_back(std::move(fr));
    }
    const FrameSet set = frameSet(std::move(frames));
    ReplayParams p = smallParams(16, 8, 4, 0.0);
    p.reconstruction = Reconstruction::Envelope;
    p.policy = FramePolicy::Clamp;
    p.timeSampling = TimeSampling::Linear;
    // A = timeUnitSeconds / (dt frameInterval) = 4 / 0.01 = 400 frames per time unit.
    const double A = framesPerTimeUnit(set.header, p);
    const SliceSampler linear(p, set.frameCount, A);
    const CpuReconstruction cpu(set, p, linear);
    ReplayParams pn = p;
    pn.timeSampling = TimeSampling::Nearest;
    const SliceSampler nearest(pn, set.frameCount, A);
    const CpuReconstruction cpuNearest(set, pn, nearest);
    const HeightField h2 = cpu.heights(2.0 / A);
    const HeightField h3 = cpu.heights(3.0 / A);
    const HeightField half = cpu.heights(2.5 / A);
    const HeightField quarter = cpu.heights(2.25 / A);
    EXPECT_EQ(cpuNearest.heights(2.0 / A).heights, h2.heights);
    double differs = 0.0;
    for (std::size_t i = 0; i < half.heights.size(); ++i) {
        EXPECT_NEAR(half.heights[i], 0.5 * (h2.heights[i] + h3.heights[i]), 1e-12) << i;
        EXPECT_NEAR(quarter.heights[i], 0.75 * h2.heights[i] + 0.25 * h3.heights[i], 1e-12) << i;
        differs = std::max(differs, std::abs(h3.heights[i] - h2.heights[i]));
    }
    EXPECT_GT(differs, 0.01); // the two frames differ, so the blend is not trivially met
    const SliceBlend b = linear.blend(2.5 / A, 0);
    EXPECT_EQ(b.first, 2u);
    EXPECT_EQ(b.second, 3u);
    EXPECT_NEAR(b.weight, 0.5, 1e-9);
    EXPECT_EQ(linear.frame(2.5 / A, 0), nearest.frame(2.5 / A, 0)); // the heavier frame
    EXPECT_EQ(linear.framesUsed(std::vector<double>{2.25 / A}), (std::vector<std::uint32_t>{2, 3}));
    EXPECT_EQ(nearest.framesUsed(std::vector<double>{2.25 / A}), (std::vector<std::uint32_t>{2}));
}

TEST(ReplayParams, TimeSamplingReadsByNameAndRejectsOthers) {
    EXPECT_EQ(replayParamsFromJson(nlohmann::json{{"time_sampling", "linear"}}).timeSampling,
              TimeSampling::Linear);
    EXPECT_EQ(toJson(ReplayParams{})["time_sampling"], "nearest");
    try {
        (void)replayParamsFromJson(nlohmann::json{{"time_sampling", "cubic"}});
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("time_sampling"), std::string::npos) << e.what();
    }
}

} // namespace swell::runtime

#include "swell/runtime/modes/mode_params.h"

namespace swell::runtime {

namespace {

/// mean |dh/dz| / mean |dh/dx| over the inner 80 % of a height field: about tan of the crests'
/// angle to z for waves running along x (0 for an extrusion, 0.15-0.6 for a natural sea).
double crestRatio(const HeightField& h) {
    double gx = 0.0, gz = 0.0;
    const int N = h.cellsX, M = h.cellsZ;
    for (int m = M / 10; m < M - M / 10; ++m) {
        for (int n = N / 10; n < N - N / 10; ++n) {
            const double c = h.heights[static_cast<std::size_t>(m) * N + n];
            gx += std::abs(h.heights[static_cast<std::size_t>(m) * N + n + 1] - c);
            gz += std::abs(h.heights[static_cast<std::size_t>(m + 1) * N + n] - c);
        }
    }
    return gz / gx;
}

} // namespace

TEST(CpuReconstruction, SwellDefaultsGiveLongCrestsWherePaperDefaultsStripe) {
    // A tank the size of scenes/surging_small.json (2 m of water 0.16 m deep, l0 = 0.02 m):
    // waves of 1 m at the shallow-water speed sqrt(g h) = 1.25 m/s, stored at 50 fps for 8 s.
    std::vector<cache::Frame> frames;
    for (int f = 0; f < 400; ++f) {
        cache::Frame fr;
        const double t = 0.02 * f;
        for (int i = 0; i <= 200; ++i) {
            const double x = 0.01 * i;
            const double eta = 0.02 * std::sin(2.0 * std::numbers::pi * (x - 1.25 * t)) +
                               0.008 * std::sin(2.0 * std::numbers::pi * (2.3 * x - 2.0 * t));
            fr.surface.push_back(static_cast<float>(x));
            fr.surface.push_back(static_cast<float>(0.16 + eta));
        }
        frames.push_back(std::move(fr));
    }
    cache::Header h;
    h.domain = {0.0f, 0.0f, 2.0f, 0.5f};
    h.dt = 0.001;
    h.frameInterval = 20;
    const FrameSet set = FrameSet::whole(h, std::move(frames));
    auto ratioOf = [&](ReplayParams p, TimeSampling sampling, std::uint64_t seed) {
        p = test::sized(100, 100, p.slices, p);
        p.reconstruction = Reconstruction::Envelope;
        p.policy = FramePolicy::Loop;
        p.timeSampling = sampling;
        p.seed = seed;
        const SliceSampler sampler = test::samplerOf(set, p);
        const CpuReconstruction cpu(set, p, sampler);
        double sum = 0.0;
        for (int i = 0; i < 3; ++i)
            sum += crestRatio(cpu.heights(0.4 + 0.3 * i));
        return sum / 3.0;
    };
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        const double swell =
            ratioOf(swellDefaults(ReplayMode::Surging), TimeSampling::Linear, seed);
        EXPECT_GE(swell, 0.15);
        EXPECT_LE(swell, 0.6);
        EXPECT_GT(ratioOf(paperDefaults(ReplayMode::Surging), TimeSampling::Nearest, seed), 1.0);
    }
}

} // namespace swell::runtime
