// Fidelity against the simulated surface (fidelity.h) and the replay of timelines with
// cross-fades on the GPU against the double-precision CPU reference.

#include "swell/cache/synthetic.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/fidelity.h"
#include "swell/runtime/replay/gpu_replay.h"

#include "gl_fixture.h"
#include "synthetic_frames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>

namespace swell::runtime {
namespace {

using json = nlohmann::json;

/// The cache a `swell-cache synth` run writes, in memory, with its water record.
FrameSet syntheticCache(const cache::SyntheticWave& w, int frames) {
    cache::Header h;
    h.domain = cache::syntheticDomain(w);
    h.dt = w.frameTime;
    h.metadataJson = json{{"replay",
                           {{"water_x_min", 0.0},
                            {"water_x_max", w.length},
                            {"still_water_level", w.depth},
                            {"particle_spacing", w.length / (w.surfaceCount - 1.0)},
                            {"steady_start_s", 0.0}}}}
                         .dump();
    std::vector<cache::Frame> f;
    for (int i = 0; i < frames; ++i)
        f.push_back(cache::syntheticFrame(w, static_cast<std::size_t>(i)));
    return FrameSet::whole(h, std::move(f));
}

/// RMS error at F = 0 of the middle row against the analytic surface, over `frames` frames.
FidelityStats analyticError(const FrameSet& set, const cache::SyntheticWave& w, int N,
                            Reconstruction rec) {
    ReplayParams p = test::sized(N, 8, 8, ReplayParams{});
    p.fluctuation = 0.0;
    p.policy = FramePolicy::Clamp;
    p.reconstruction = rec;
    const double A = framesPerTimeUnit(set.header, p);
    const SliceSampler s(p, set.frameCount, A);
    const CpuReconstruction cpu(set, p, s);
    FidelityStats stats;
    for (std::size_t f = 0; f < set.frameCount; ++f) {
        const HeightField h = cpu.heights(static_cast<double>(f) / A);
        const std::vector<double> row(h.heights.begin() + 4 * N, h.heights.begin() + 5 * N);
        const double t = static_cast<double>(f) * w.frameTime;
        stats.add(compareRow(
            row, cpu.grid(), [&](double x) { return cache::syntheticHeight(w, x, t); }, 0.0,
            w.length, 0.0025));
    }
    return stats;
}

TEST(Fidelity, CompareRowKnownAnswers) {
    Grid g;
    g.cellsX = 10;
    g.x0 = 0.0;
    g.dx = 0.1;
    std::vector<double> row(10);
    for (int n = 0; n < 10; ++n)
        row[n] = 2.0 * (n + 0.5) * 0.1; // the line 2x at the cell centres
    auto line = [](double x) { return 2.0 * x; };
    const RowFidelity exact = compareRow(row, g, line, -1.0, 2.0, 0.01);
    EXPECT_NEAR(std::sqrt(exact.sumSquares / exact.samples), 0.0, 1e-12);
    EXPECT_EQ(exact.samples, 91u); // x = 0.05 .. 0.95: clipped to the column centres
    EXPECT_NEAR(exact.crestLoss, 0.0, 1e-12);
    for (double& v : row)
        v -= 0.18; // every height 0.18 low: a tenth of the 1.8 m crest-to-trough height
    const RowFidelity low = compareRow(row, g, line, -1.0, 2.0, 0.01);
    EXPECT_NEAR(low.maxAbs, 0.18, 1e-12);
    EXPECT_NEAR(low.crestLoss, 0.1, 1e-9);
    EXPECT_THROW(compareRow(std::vector<double>(3), g, line, 0.0, 1.0, 0.01),
                 std::invalid_argument);
}

TEST(Fidelity, EnvelopeReplayOfTheAnalyticWaveConvergesWithResolution) {
    cache::SyntheticWave w; // 4 m tank, 1 m waves, 400 jittered surface particles
    const FrameSet set = syntheticCache(w, 12);
    const FidelityStats coarse = analyticError(set, w, 64, Reconstruction::Envelope);
    const FidelityStats fine = analyticError(set, w, 256, Reconstruction::Envelope);
    // Linear interpolation between cell centres: second order until the particle spacing
    // (1 cm) limits it; 4x the resolution must cut the RMS error at least 5-fold.
    EXPECT_LT(coarse.rms(), 2e-3) << coarse.rms();
    EXPECT_LT(fine.rms(), coarse.rms() / 5.0) << coarse.rms() << " -> " << fine.rms();
    EXPECT_LT(fine.meanCrestLoss(), 0.005);
    // The paper's eq. (7) window averages 3 cells: at 64 cells it loses crest height.
    const FidelityStats paper = analyticError(set, w, 64, Reconstruction::Paper);
    EXPECT_GT(paper.meanCrestLoss(), 2.0 * coarse.meanCrestLoss());
}

class CrossFadeReplay : public swell::test::GlSuite {};

TEST_F(CrossFadeReplay, GpuMatchesCpuOnSeamlessTimelinesInBothReconstructions) {
    FrameSet set = test::syntheticSet(60, 300, 11);
    const Timeline timeline = Timeline::seamless({12, 50, 8, 0.0, 0.0}); // frames 4 .. 49
    for (Reconstruction rec : {Reconstruction::Envelope, Reconstruction::Paper}) {
        ReplayParams p = test::sized(97, 41, 24, ReplayParams{});
        p.fluctuation = 0.4;
        p.timeUnitSeconds = 0.3; // A = 30 frames per unit: the slices span the whole loop
        p.reconstruction = rec;
        const double A = framesPerTimeUnit(set.header, p);
        const SliceSampler s(p, timeline, A);
        GpuReplay gpu(set, p, s);
        const CpuReconstruction cpu(set, p, s);
        int blendedSlices = 0;
        for (double tau : {0.0, 0.9, 1.2, 1.25, 2.5, -0.4}) {
            SCOPED_TRACE(::testing::Message() << toString(rec) << " tau " << tau);
            for (std::size_t e : s.entries(tau))
                blendedSlices += timeline[e].blended() ? 1 : 0;
            gpu.update(tau);
            EXPECT_EQ(gpu.readSliceFrames(), s.frames(tau));
            const HeightField g = gpu.readHeights();
            const HeightField r = cpu.heights(tau);
            double worst = 0.0;
            for (std::size_t i = 0; i < g.heights.size(); ++i)
                worst = std::max(worst, std::abs(g.heights[i] - r.heights[i]));
            EXPECT_LE(worst, 1e-4 * test::kSyntheticDepth);
        }
        EXPECT_GT(blendedSlices, 0); // the cross-fade was exercised
        EXPECT_EQ(gpu.slotCount(), gpu.heldFrames() + 8);
    }
}

TEST_F(CrossFadeReplay, NoSliceJumpsAcrossTheSeam) {
    // At F = 0 every slice shows one entry; stepping one entry at a time across the seam, the
    // height field changes by no more than between two ordinary consecutive frames (plus the
    // residual of the seam, here two frames of the same smooth wave).
    FrameSet set = test::syntheticSet(80, 400, 5);
    ReplayParams p = test::sized(64, 4, 4, ReplayParams{});
    p.fluctuation = 0.0;
    p.reconstruction = Reconstruction::Envelope;
    const double A = framesPerTimeUnit(set.header, p);
    const Timeline t = Timeline::seamless({20, 70, 10, 0.0, 0.0});
    const SliceSampler s(p, t, A);
    const CpuReconstruction cpu(set, p, s);
    auto change = [&](long long e) {
        const HeightField a = cpu.heights(static_cast<double>(e) / A);
        const HeightField b = cpu.heights(static_cast<double>(e + 1) / A);
        double d = 0.0;
        for (std::size_t i = 0; i < a.heights.size(); ++i)
            d = std::max(d, std::abs(a.heights[i] - b.heights[i]));
        return d;
    };
    double ordinary = 0.0;
    for (long long e = 0; e < 30; ++e)
        ordinary = std::max(ordinary, change(e));
    double seam = 0.0;
    for (long long e = 38; e < 52; ++e) // the fade (entries 40 .. 49) and the wrap at 50
        seam = std::max(seam, change(e));
    // Frames 60 .. 69 and 10 .. 19 are 50 frames (0.5 s) apart: unlike, yet no jump.
    EXPECT_LT(seam, 1.5 * ordinary) << "ordinary " << ordinary;

    // Without the fade the wrap is one jump from frame 69 to frame 20.
    const Timeline hard = Timeline::seamless({20, 70, 0, 0.0, 0.0});
    const SliceSampler sh(p, hard, A);
    const CpuReconstruction cpuHard(set, p, sh);
    const HeightField a = cpuHard.heights(49.0 / A);
    const HeightField b = cpuHard.heights(50.0 / A);
    double jump = 0.0;
    for (std::size_t i = 0; i < a.heights.size(); ++i)
        jump = std::max(jump, std::abs(a.heights[i] - b.heights[i]));
    EXPECT_GT(jump, 1.5 * seam);
}

} // namespace
} // namespace swell::runtime
