// Ripple (eq. 8) and whirlpool (spiral slices) on the GPU against their double-precision CPU
// references, known answers, determinism and seeds (llvmpipe in CI).
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/modes/mode_replay.h"

#include "swell/runtime/replay/fidelity.h"

#include "hashing.h"
#include "synthetic_suite.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace swell::runtime {
namespace {

class ModeReplayTest : public test::SyntheticGlSuite {};

/// Largest |GPU - CPU| over the cells; fails on a non-finite GPU cell.
double worstError(const HeightField& g, const HeightField& r) {
    EXPECT_EQ(g.heights.size(), r.heights.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < g.heights.size(); ++i) {
        if (!std::isfinite(g.heights[i]) || !std::isfinite(r.heights[i])) {
            ADD_FAILURE() << "non-finite height at cell " << i;
            return INFINITY;
        }
        worst = std::max(worst, std::abs(g.heights[i] - r.heights[i]));
    }
    return worst;
}

struct Case {
    ReplayMode mode;
    int N, M, K;
    double F;
    FramePolicy policy;
    std::uint64_t seed;
    std::vector<double> angles; ///< ripple
    std::vector<double> weights;
    WhirlpoolParams whirlpool;
};

ModeParams modeOf(const Case& c) {
    ModeParams m;
    m.mode = c.mode;
    if (!c.angles.empty())
        m.ripple.anglesDegrees = c.angles;
    m.ripple.weights = c.weights;
    m.whirlpool = c.whirlpool;
    return m;
}

/// A replay of `set` in mode m (its default mode parameters) with `p`.
ModeReplay replayOf(const FrameSet& set, const ReplayParams& p, ReplayMode m) {
    ModeParams mode;
    mode.mode = m;
    return ModeReplay(set, p, mode,
                      makeSamplers(p, mode, set.frameCount, framesPerTimeUnit(set.header, p)));
}

ReplayParams paramsOf(const Case& c) {
    ReplayParams p = paperDefaults(c.mode);
    p = test::sized(c.N, c.M, c.K, p);
    p.fluctuation = c.F;
    p.policy = c.policy;
    p.seed = c.seed;
    return p;
}

} // namespace

TEST_F(ModeReplayTest, MatchesTheCpuReferenceForBothModes) {
    const FrameSet& set = *s_frames;
    WhirlpoolParams tight;
    tight.innerRadiusCells = 4.0;
    tight.growth = 0.45;
    tight.turnsPerTimeUnit = -0.7;
    const Case cases[] = {
        // ripple: the paper's defaults; three directions with weights on a non-square mesh;
        // one direction at 90 degrees (synthesis without a second direction); F = 1
        {ReplayMode::Ripple, 128, 128, 256, 0.4, FramePolicy::Loop, 1, {}, {}, {}},
        {ReplayMode::Ripple,
         77,
         45,
         40,
         0.4,
         FramePolicy::Clamp,
         2,
         {-20, 15, 100},
         {1, 2, 0.5},
         {}},
        {ReplayMode::Ripple, 50, 50, 16, 1.0, FramePolicy::Loop, 3, {90}, {}, {}},
        // whirlpool: the paper's defaults; a tight, fast, reversed spiral on a non-square mesh
        {ReplayMode::Whirlpool, 128, 128, 128, 0.4, FramePolicy::Loop, 4, {}, {}, {}},
        {ReplayMode::Whirlpool, 90, 61, 20, 0.8, FramePolicy::Clamp, 5, {}, {}, tight},
        // degenerate meshes: one column, one row
        {ReplayMode::Ripple, 1, 7, 4, 0.4, FramePolicy::Loop, 6, {0, 45}, {}, {}},
        {ReplayMode::Whirlpool, 5, 1, 3, 0.4, FramePolicy::Loop, 7, {}, {}, {}},
    };
    SplitMix64 rng(7);
    for (const Case& c : cases) {
        const ReplayParams p = paramsOf(c);
        const ModeParams mode = modeOf(c);
        const auto samplers =
            makeSamplers(p, mode, set.frameCount, framesPerTimeUnit(set.header, p));
        ModeReplay gpu(set, p, mode, samplers);
        const CpuModeReference cpu(set, p, mode, samplers);
        for (int t = 0; t < 3; ++t) {
            const double tau = -0.5 + 1.7 * rng.uniform();
            SCOPED_TRACE(::testing::Message()
                         << toString(c.mode) << " " << c.N << "x" << c.M << " K " << c.K << " seed "
                         << c.seed << " tau " << tau);
            gpu.update(tau);
            const auto frames = gpu.readSliceFrames();
            ASSERT_EQ(frames.size(), samplers.size());
            for (std::size_t d = 0; d < samplers.size(); ++d)
                EXPECT_EQ(frames[d], samplers[d].frames(tau)); // eq. (5) exactly, every set
            EXPECT_LE(worstError(gpu.readHeights(), cpu.heights(tau)),
                      1e-4 * test::kSyntheticDepth);
        }
    }
}

TEST_F(ModeReplayTest, SeamlessTimelinesWithCrossFadesMatchTheCpuReferenceInEveryMode) {
    // Every mode reads its frames through the same timeline (timeline.h): a loop from frame 30
    // to 200 with a 12-frame cross-fade, both reconstructions, taus across the seam.
    const FrameSet& set = *s_frames;
    const Timeline timeline = Timeline::seamless({30, 200, 12, 0.0, 0.0});
    for (ReplayMode m : {ReplayMode::Surging, ReplayMode::Ripple, ReplayMode::Whirlpool}) {
        for (Reconstruction rec : {Reconstruction::Envelope, Reconstruction::Paper}) {
            ReplayParams p = paperDefaults(m);
            p = test::sized(72, 56, 32, p);
            p.timeUnitSeconds = 1.0; // A = 100 frames per unit: the loop is 1.7 units
            p.reconstruction = rec;
            ModeParams mode;
            mode.mode = m;
            const auto samplers = makeSamplers(p, mode, timeline, framesPerTimeUnit(set.header, p));
            ModeReplay gpu(set, p, mode, samplers);
            const CpuModeReference cpu(set, p, mode, samplers);
            for (double tau : {0.2, 1.6, 1.65, 3.35, -0.05}) {
                SCOPED_TRACE(::testing::Message()
                             << toString(m) << " " << toString(rec) << " tau " << tau);
                gpu.update(tau);
                const auto frames = gpu.readSliceFrames();
                for (std::size_t d = 0; d < samplers.size(); ++d)
                    EXPECT_EQ(frames[d], samplers[d].frames(tau));
                EXPECT_LE(worstError(gpu.readHeights(), cpu.heights(tau)),
                          1e-4 * test::kSyntheticDepth);
            }
        }
    }
}

TEST_F(ModeReplayTest, OneRippleDirectionAtZeroIsTheSurgingReplayWithoutSynthesis) {
    const FrameSet& set = *s_frames;
    ReplayParams p = paperDefaults(ReplayMode::Ripple);
    p = test::sized(64, 48, 64, p);
    ModeParams ripple;
    ripple.mode = ReplayMode::Ripple;
    ripple.ripple.anglesDegrees = {0.0};
    ModeParams surging;
    const double A = framesPerTimeUnit(set.header, p);
    const auto rs = makeSamplers(p, ripple, set.frameCount, A);
    const auto ss = makeSamplers(p, surging, set.frameCount, A);
    ModeReplay a(set, p, ripple, rs);
    ModeReplay b(set, p, surging, ss);
    ASSERT_NE(a.ripple(), nullptr);
    EXPECT_FALSE(a.ripple()->synthesises());
    a.update(0.3);
    b.update(0.3);
    EXPECT_EQ(a.readHeights().heights, b.readHeights().heights);
}

TEST_F(ModeReplayTest, RippleAtZeroAndNinetyDegreesWithoutNoiseIsTheMeanOfTwoProfiles) {
    // F = 0: every direction's field is the same profile p(n) on every row. Direction 90 reads
    // base cell (n, m) at its cell (m, N - 1 - n), so eq. (8) gives the mean of p(n) and p(m)
    // weighted by the edge tapers e(n + 1/2) and e(m + 1/2) of the two directions.
    const FrameSet& set = *s_frames;
    ReplayParams p = paperDefaults(ReplayMode::Ripple);
    p = test::sized(40, 40, 32, p);
    p.fluctuation = 0.0;
    ModeParams mode;
    mode.mode = ReplayMode::Ripple;
    mode.ripple.anglesDegrees = {0.0, 90.0};
    const double A = framesPerTimeUnit(set.header, p);
    const auto samplers = makeSamplers(p, mode, set.frameCount, A);
    ModeReplay gpu(set, p, mode, samplers);
    gpu.update(0.2);
    const HeightField h = gpu.readHeights();
    GpuReplay surging(set, p, samplers[0]);
    surging.update(0.2);
    const HeightField s = surging.readHeights();
    double spread = 0.0;
    for (int m = 0; m < 40; ++m) {
        for (int n = 0; n < 40; ++n) {
            const double side = std::min({n + 0.5, 39.5 - n, m + 0.5, 39.5 - m});
            const double e0 = rippleEdgeWeight(n + 0.5, 40, side);
            const double e1 = rippleEdgeWeight(m + 0.5, 40, side);
            EXPECT_NEAR(h.at(n, m), (e0 * s.at(n, 0) + e1 * s.at(m, 0)) / (e0 + e1), 1e-5)
                << n << ", " << m;
            spread = std::max(spread, std::abs(s.at(n, 0) - s.at(0, 0)));
        }
    }
    EXPECT_GT(spread, 0.01); // the profile is not flat, so the test can tell directions apart
}

TEST(RippleTaps, WeightsFadeSmoothlyWhereADirectionsFieldEnds) {
    // Two directions, 0 and 30 degrees: the rotated one's field ends inside the base mesh.
    Grid g;
    g.cellsX = g.cellsZ = 64;
    g.slices = 16;
    g.dx = g.dz = 0.05;
    g.extentZ = 64 * 0.05;
    RippleParams r;
    r.anglesDegrees = {0.0, 30.0};
    const std::vector<RippleTap> taps = rippleTaps(g, r);
    double worstStep = 0.0, least = 1.0;
    for (int m = 0; m < 64; ++m) {
        for (int n = 0; n < 64; ++n) {
            const RippleTap* c = &taps[(static_cast<std::size_t>(m) * 64 + n) * 2];
            EXPECT_NEAR(c[0].weight + c[1].weight, 1.0, 1e-12);
            least = std::min(least, c[1].weight);
            if (n + 1 < 64)
                worstStep = std::max(worstStep, std::abs(c[3].weight - c[1].weight));
            if (m + 1 < 64)
                worstStep = std::max(worstStep, std::abs(c[129].weight - c[1].weight));
        }
    }
    // Outside its field the rotated direction keeps only the floor's share...
    EXPECT_LT(least, 2.0 * kRippleEdgeFloor);
    // ...and fades there over the margin (9.6 cells): no weight jumps between neighbours (a
    // cut at the field's end would step by 0.5).
    EXPECT_LT(worstStep, 0.12);
}

TEST_F(ModeReplayTest, WhirlpoolRotatesWithAnimationTime) {
    // The same tau (same frames) with and without spin: at a quarter turn the spinning field
    // is the still one turned by 90 degrees about the centre (counter-clockwise in (x, z)):
    // h_spin(P) = h_still(R(-90) P), i.e. cell (n, m) reads the still cell (m, N - 1 - n).
    const FrameSet& set = *s_frames;
    ReplayParams p = paperDefaults(ReplayMode::Whirlpool);
    p = test::sized(48, 48, 24, p); // J = 47: a quarter turn is 11.75 slices, exact in float
    ModeParams mode;
    mode.mode = ReplayMode::Whirlpool;
    mode.whirlpool.turnsPerTimeUnit = 2.5;
    ModeParams still = mode;
    still.whirlpool.turnsPerTimeUnit = 0.0;
    const auto samplers = makeSamplers(p, mode, set.frameCount, framesPerTimeUnit(set.header, p));
    ModeReplay spinning(set, p, mode, samplers);
    ModeReplay fixed(set, p, still, samplers);
    const double tau = 0.1; // 0.25 turns
    spinning.update(tau);
    fixed.update(tau);
    const HeightField a = spinning.readHeights();
    const HeightField b = fixed.readHeights();
    double moved = 0.0, worst = 0.0;
    for (int m = 0; m < 48; ++m) {
        for (int n = 0; n < 48; ++n) {
            moved = std::max(moved, std::abs(a.at(n, m) - b.at(n, m)));
            worst = std::max(worst, std::abs(a.at(n, m) - b.at(m, 47 - n)));
        }
    }
    EXPECT_GT(moved, 0.01); // it turned
    EXPECT_LT(worst, 1e-4); // by exactly a quarter turn
}

TEST_F(ModeReplayTest, SameInputsGiveByteIdenticalHeightsAndGoldenFrames) {
    const FrameSet& set = *s_frames;
    std::uint64_t golden[2] = {0, 0};
    int i = 0;
    for (ReplayMode m : {ReplayMode::Ripple, ReplayMode::Whirlpool}) {
        ReplayParams p = paperDefaults(m);
        p.seed = 2024;
        ModeReplay a = replayOf(set, p, m), b = replayOf(set, p, m);
        std::uint64_t hashA = 0, hashB = 0, hashFrames = 0xcbf29ce484222325ULL;
        for (double tau : {0.1, 0.25, 0.4}) {
            a.update(tau);
            b.update(tau);
            for (const auto& f : a.readSliceFrames())
                hashFrames = swell::test::chainFrames(hashFrames, f);
            hashA = swell::test::chainHeights(hashA, a.readHeights().heights);
            hashB = swell::test::chainHeights(hashB, b.readHeights().heights);
        }
        EXPECT_EQ(hashA, hashB) << toString(m);
        golden[i++] = hashFrames;
    }
    // Golden: the frames of eq. (5) for every slice set are integers fixed by SplitMix64, FFTW
    // and IEEE double arithmetic (see gpu_reconstruction_test). A change here means the noise,
    // the per-direction seeds or the slice lookup changed.
    EXPECT_EQ(golden[0], 0x68893766ffb400ebULL) << std::hex << golden[0];
    EXPECT_EQ(golden[1], 0x0999b73942fa9290ULL) << std::hex << golden[1];
}

TEST_F(ModeReplayTest, DifferentSeedsGiveVisiblyDifferentSurfaces) {
    const FrameSet& set = *s_frames;
    for (ReplayMode m : {ReplayMode::Ripple, ReplayMode::Whirlpool}) {
        ReplayParams p = paperDefaults(m);
        p.cellsX = 96;
        p.cellsZ = 96;
        ReplayParams q = p;
        q.seed = 2;
        ModeReplay a = replayOf(set, p, m), b = replayOf(set, q, m);
        a.update(0.25);
        b.update(0.25);
        const HeightField ha = a.readHeights(), hb = b.readHeights();
        HeightDifference difference;
        difference.add(ha, hb);
        EXPECT_GT(difference.rms(), 0.3 * fieldSpread(ha)) << toString(m);
    }
}

TEST_F(ModeReplayTest, HeightTextureAndStageTimes) {
    const FrameSet& set = *s_frames;
    for (ReplayMode m : {ReplayMode::Ripple, ReplayMode::Whirlpool}) {
        ReplayParams p = paperDefaults(m);
        p = test::sized(45, 38, 50, p);
        ModeParams mode;
        mode.mode = m;
        const auto samplers =
            makeSamplers(p, mode, set.frameCount, framesPerTimeUnit(set.header, p));
        ModeReplay gpu(set, p, mode, samplers);
        EXPECT_THROW(gpu.stageTimes(), std::logic_error);
        gpu.setTiming(true);
        for (double tau : {0.05, 0.2}) {
            gpu.update(tau);
            std::vector<float> texels(45 * 38);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glGetTextureImage(gpu.heightTexture(), 0, GL_RED, GL_FLOAT,
                              static_cast<GLsizei>(texels.size() * 4), texels.data());
            const HeightField h = gpu.readHeights();
            for (int r = 0; r < 38; ++r) {
                for (int n = 0; n < 45; ++n)
                    ASSERT_EQ(texels[r * 45 + n], static_cast<float>(h.at(n, r)));
            }
        }
        const StageTimes t = gpu.stageTimes();
        if (m == ReplayMode::Ripple) {
            EXPECT_GT(t.synthesisMs + t.reconstructMs, 0.0);
            EXPECT_EQ(t.spiralMs, 0.0);
        } else {
            EXPECT_GT(t.spiralMs + t.sliceLookupMs, 0.0);
            EXPECT_EQ(t.reconstructMs, 0.0); // the whirlpool runs no surging reconstruction
            EXPECT_EQ(t.synthesisMs, 0.0);
        }
        EXPECT_THROW(gpu.update(std::nan("")), std::invalid_argument);
    }
}

} // namespace swell::runtime
