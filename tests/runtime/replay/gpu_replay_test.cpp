#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/gpu_replay.h"

#include "swell/runtime/replay/fidelity.h"

#include "gl_fixture.h"
#include "hashing.h"
#include "synthetic_frames.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

namespace swell::runtime {
namespace {

class GpuReconstruction : public swell::test::GlSuite {};

struct Case {
    int N, M, K;
    double F;
    FramePolicy policy;
    std::uint64_t seed;
};

} // namespace

TEST_F(GpuReconstruction, MatchesTheCpuReferenceForRandomTimesSeedsAndSizes) {
    // Frames: 260 frames (2.6 s) of travelling waves with gaps, a dry region and an empty
    // frame; A = 400 frames per time unit, so tau in [-0.5, 1.2] covers clamp and loop.
    const FrameSet set = test::syntheticSet(260, 320, 21);
    const double depth = test::kSyntheticDepth;
    const Case cases[] = {
        {128, 128, 256, 0.3, FramePolicy::Loop, 1},  // the paper's configuration
        {97, 53, 40, 0.4, FramePolicy::Clamp, 2},    // non-square, non-power-of-two
        {64, 200, 16, 0.3, FramePolicy::Loop, 3},    // M > 4K: rows with no slice in the window
        {33, 17, 7, 1.0, FramePolicy::Clamp, 4},     // F = 1, the bound of eq. (6)
        {300, 31, 64, 0.0, FramePolicy::Loop, 5},    // F = 0: no noise, many empty columns
        {256, 96, 128, 0.25, FramePolicy::Clamp, 6}, // narrow cells: fallback columns
    };
    SplitMix64 rng(99);
    for (const Case& c : cases) {
        ReplayParams p = test::sized(c.N, c.M, c.K, ReplayParams{});
        p.fluctuation = c.F;
        p.policy = c.policy;
        p.seed = c.seed;
        const SliceSampler sampler = test::samplerOf(set, p);
        GpuReplay gpu(set, p, sampler);
        const CpuReconstruction cpu(set, p, sampler);
        for (int t = 0; t < 4; ++t) {
            const double tau = -0.5 + 1.7 * rng.uniform();
            SCOPED_TRACE(::testing::Message() << c.N << "x" << c.M << " K " << c.K << " F " << c.F
                                              << " seed " << c.seed << " tau " << tau);
            gpu.update(tau);
            EXPECT_EQ(gpu.readSliceFrames(), sampler.frames(tau)); // eq. (5) exactly
            const HeightField g = gpu.readHeights();
            const HeightField r = cpu.heights(tau);
            ASSERT_EQ(g.heights.size(), r.heights.size());
            double worst = 0.0;
            std::size_t worstCell = 0;
            for (std::size_t i = 0; i < g.heights.size(); ++i) {
                ASSERT_TRUE(std::isfinite(g.heights[i])) << "cell " << i;
                if (std::abs(g.heights[i] - r.heights[i]) > worst) {
                    worst = std::abs(g.heights[i] - r.heights[i]);
                    worstCell = i;
                }
            }
            EXPECT_LE(worst, 1e-4 * depth)
                << "worst at cell (" << worstCell % static_cast<std::size_t>(c.N) << ", "
                << worstCell / static_cast<std::size_t>(c.N) << "): GPU " << g.heights[worstCell]
                << ", CPU " << r.heights[worstCell];
        }
    }
}

TEST_F(GpuReconstruction, FallbackAndWindowKnownAnswers) {
    // x in [0, 16] m over 16 cells: particles in bins 2 (two), 5 and 10.
    cache::Header h;
    h.domain = {0.0f, 0.0f, 16.0f, 2.0f};
    cache::Frame f;
    for (float v : {2.5f, 1.0f, 2.7f, 1.5f, 5.0f, 1.25f, 10.5f, 3.0f})
        f.surface.push_back(v);
    const FrameSet set = FrameSet::whole(h, {f, cache::Frame{}});
    ReplayParams p = test::sized(16, 4, 4, ReplayParams{});
    p.fluctuation = 0.0;
    const SliceSampler s(p, 2, 1.0);
    GpuReplay gpu(set, p, s);
    gpu.update(0.0);
    const HeightField g = gpu.readHeights();
    EXPECT_NEAR(g.at(4, 0), 1.25, 1e-6); // bins 3..5: the particle at 5.0
    EXPECT_NEAR(g.at(8, 0), 3.0, 1e-6);  // bins 7..9 empty; d = 2: bin 10
    EXPECT_NEAR(g.at(7, 0), 1.25, 1e-6); // bins 6..8 empty; d = 2: bins 5, 9
    EXPECT_NEAR(g.at(15, 1), 3.0, 1e-6); // d = 5: bin 10
    gpu.update(1.0);                     // the empty frame: the domain's bottom
    for (double v : gpu.readHeights().heights)
        EXPECT_NEAR(v, 0.0, 1e-6);
}

TEST_F(GpuReconstruction, HoldingOnlyTheUsedFramesGivesTheSameResult) {
    const auto frames = test::syntheticFrames(300, 200, 8);
    const FrameSet whole = FrameSet::whole(test::syntheticHeader(), frames);
    ReplayParams p = test::sized(80, 60, 100, ReplayParams{});
    const double A = framesPerTimeUnit(whole.header, p);
    const SliceSampler sampler(p, whole.frameCount, A);
    const std::vector<double> taus = {0.3, 0.31, 0.32};
    FrameSet part;
    part.header = whole.header;
    part.frameCount = whole.frameCount;
    part.ids = sampler.framesUsed(taus);
    for (std::uint32_t id : part.ids)
        part.frames.push_back(frames[id]);
    ASSERT_LT(part.ids.size(), frames.size() / 2); // most frames are never decoded
    GpuReplay a(whole, p, sampler), b(part, p, sampler);
    for (double tau : taus) {
        a.update(tau);
        b.update(tau);
        const HeightField ha = a.readHeights(), hb = b.readHeights();
        for (std::size_t i = 0; i < ha.heights.size(); ++i)
            EXPECT_EQ(ha.heights[i], hb.heights[i]);
    }
}

TEST_F(GpuReconstruction, HoldsMoreFramesThanOneDispatchHasWorkGroupRows) {
    // The column pass runs one work-group row per held frame; drivers guarantee 65,535 rows per
    // dispatch, and a long cache's seamless loop can hold more frames (the whole loop). Frame f
    // is a flat surface at a height unique to f, so each slot's columns show whether its row ran.
    GLint maxRows = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &maxRows);
    const std::size_t count = static_cast<std::size_t>(maxRows) + 1000;
    cache::Header h;
    h.domain = {0.0f, 0.0f, 8.0f, 2.0f};
    h.dt = 0.001;
    h.frameInterval = 10;
    auto level = [](std::size_t f) { return 0.5 + 1e-5 * static_cast<double>(f % 100000); };
    std::vector<cache::Frame> frames(count);
    for (std::size_t f = 0; f < count; ++f) {
        for (float x : {0.5f, 2.5f, 4.5f, 6.5f}) {
            frames[f].surface.push_back(x);
            frames[f].surface.push_back(static_cast<float>(level(f)));
        }
    }
    const FrameSet set = FrameSet::whole(h, std::move(frames));
    ReplayParams p = test::sized(8, 4, 4, ReplayParams{});
    p.fluctuation = 0.0; // every slice shows frame s = A tau
    p.policy = FramePolicy::Clamp;
    const SliceSampler sampler = test::samplerOf(set, p);
    GpuReplay gpu(set, p, sampler);
    const double A = framesPerTimeUnit(h, p);
    for (std::size_t f : {std::size_t{0}, static_cast<std::size_t>(maxRows) - 1,
                          static_cast<std::size_t>(maxRows), count - 1}) {
        gpu.update(static_cast<double>(f) / A);
        const HeightField g = gpu.readHeights();
        ASSERT_EQ(gpu.readSliceFrames().front(), f);
        for (double v : g.heights)
            ASSERT_NEAR(v, level(f), 1e-5) << "frame " << f;
    }
}

TEST_F(GpuReconstruction, WithoutNoiseEveryRowIsTheSame) {
    // F = 0 (eq. 5): every slice shows the same frame, so the surface is uniform along z
    // (the "plain duplication" of the paper's Fig. 8a).
    const FrameSet set = test::syntheticSet(100, 300, 2);
    ReplayParams p;
    p.fluctuation = 0.0;
    p = test::sized(64, 32, 64, p);
    const SliceSampler sampler = test::samplerOf(set, p);
    GpuReplay gpu(set, p, sampler);
    gpu.update(0.1);
    const HeightField h = gpu.readHeights();
    for (int m = 1; m < 32; ++m) {
        for (int n = 0; n < 64; ++n)
            EXPECT_NEAR(h.at(n, m), h.at(n, 0), 1e-6);
    }
}

TEST_F(GpuReconstruction, SameInputsGiveByteIdenticalHeights) {
    const FrameSet set = test::syntheticSet(200, 320, 4);
    ReplayParams p; // paper defaults, 128 x 128, K = 256
    p.seed = 2024;
    const SliceSampler s1 = test::samplerOf(set, p);
    const SliceSampler s2 = test::samplerOf(set, p);
    GpuReplay a(set, p, s1);
    GpuReplay b(set, p, s2);
    std::uint64_t hashA = 0, hashB = 0, hashFrames = 0xcbf29ce484222325ULL;
    for (double tau : {0.1, 0.25, 0.4}) {
        a.update(tau);
        b.update(tau);
        const auto fa = a.readSliceFrames();
        hashFrames = swell::test::chainFrames(hashFrames, fa);
        hashA = swell::test::chainHeights(hashA, a.readHeights().heights);
        hashB = swell::test::chainHeights(hashB, b.readHeights().heights);
    }
    EXPECT_EQ(hashA, hashB);
    // Golden: the frames chosen by eq. (5) are integers fixed by SplitMix64, FFTW and IEEE
    // double arithmetic, so they are the same on every machine with this FFTW build. A
    // change here means the noise or the slice lookup changed.
    EXPECT_EQ(hashFrames, 0x99a7c2d6e4bae9b9ULL) << std::hex << hashFrames;
}

TEST_F(GpuReconstruction, DifferentSeedsGiveVisiblyDifferentSurfaces) {
    const FrameSet set = test::syntheticSet(200, 320, 4);
    ReplayParams p;
    p.seed = 1;
    ReplayParams q = p;
    q.seed = 2;
    const SliceSampler sp = test::samplerOf(set, p);
    const SliceSampler sq = test::samplerOf(set, q);
    GpuReplay a(set, p, sp), b(set, q, sq);
    a.update(0.25);
    b.update(0.25);
    const HeightField ha = a.readHeights(), hb = b.readHeights();
    HeightDifference difference;
    difference.add(ha, hb);
    // The surfaces differ by a sizeable fraction of the wave's own variation.
    EXPECT_GT(difference.rms(), 0.3 * fieldSpread(ha));
}

TEST_F(GpuReconstruction, HeightTextureHoldsTheLatestHeights) {
    const FrameSet set = test::syntheticSet(120, 200, 4);
    ReplayParams p = test::sized(45, 38, 50, ReplayParams{});
    const SliceSampler s = test::samplerOf(set, p);
    GpuReplay gpu(set, p, s);
    for (double tau : {0.05, 0.2}) {
        gpu.update(tau);
        const GlName texture = gpu.heightTexture();
        std::vector<float> texels(45 * 38);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(texels.size() * 4),
                          texels.data());
        const HeightField h = gpu.readHeights();
        for (int m = 0; m < 38; ++m) {
            for (int n = 0; n < 45; ++n)
                ASSERT_EQ(texels[m * 45 + n], static_cast<float>(h.at(n, m)));
        }
    }
}

TEST_F(GpuReconstruction, StageTimesComeFromTimerQueries) {
    const FrameSet set = test::syntheticSet(50, 100, 4);
    ReplayParams p = test::sized(32, 32, 32, ReplayParams{});
    const SliceSampler s = test::samplerOf(set, p);
    GpuReplay gpu(set, p, s);
    EXPECT_THROW(gpu.stageTimes(), std::logic_error);
    gpu.setTiming(true);
    gpu.update(0.05);
    const StageTimes t = gpu.stageTimes();
    EXPECT_GT(t.sliceLookupMs + t.reconstructMs, 0.0);
    EXPECT_GE(gpu.columnPassMs(), 0.0);
    EXPECT_THROW(gpu.update(std::nan("")), std::invalid_argument);
}

} // namespace swell::runtime

namespace swell::runtime {

TEST_F(GpuReconstruction, LinearTimeSamplingMatchesTheCpuReference) {
    // Between stored frames (TimeSampling::Linear): the same frames, slots and blended heights
    // as the CPU reference, for both column profiles, clamp and loop, with and without noise.
    const FrameSet set = test::syntheticSet(260, 320, 21);
    const double depth = test::kSyntheticDepth;
    const Case cases[] = {
        {128, 128, 256, 0.3, FramePolicy::Loop, 1},
        {97, 53, 40, 0.4, FramePolicy::Clamp, 2},
        {64, 200, 16, 0.0, FramePolicy::Loop, 3},
    };
    SplitMix64 rng(7);
    for (const Reconstruction reconstruction : {Reconstruction::Paper, Reconstruction::Envelope}) {
        for (const Case& c : cases) {
            ReplayParams p = test::sized(c.N, c.M, c.K, ReplayParams{});
            p.fluctuation = c.F;
            p.policy = c.policy;
            p.seed = c.seed;
            p.reconstruction = reconstruction;
            p.timeSampling = TimeSampling::Linear;
            const SliceSampler sampler = test::samplerOf(set, p);
            GpuReplay gpu(set, p, sampler);
            const CpuReconstruction cpu(set, p, sampler);
            for (int t = 0; t < 3; ++t) {
                const double tau = -0.5 + 1.7 * rng.uniform();
                SCOPED_TRACE(::testing::Message() << toString(reconstruction) << " " << c.N << "x"
                                                  << c.M << " F " << c.F << " tau " << tau);
                gpu.update(tau);
                EXPECT_EQ(gpu.readSliceFrames(), sampler.frames(tau));
                const HeightField g = gpu.readHeights();
                const HeightField r = cpu.heights(tau);
                ASSERT_EQ(g.heights.size(), r.heights.size());
                double worst = 0.0;
                for (std::size_t i = 0; i < g.heights.size(); ++i) {
                    ASSERT_TRUE(std::isfinite(g.heights[i])) << "cell " << i;
                    worst = std::max(worst, std::abs(g.heights[i] - r.heights[i]));
                }
                EXPECT_LE(worst, 1e-5 * depth);
            }
        }
    }
}

} // namespace swell::runtime
