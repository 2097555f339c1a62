// The replay's time axis (timeline.h): steady window, clamp / loop / seamless, the loop-point
// search and the cross-fade, the bake record and the grid over the water.

#include "swell/runtime/replay/bake_record.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/runtime/replay/surface_envelope.h"
#include "swell/runtime/replay/timeline.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

namespace swell::runtime {
namespace {

using json = nlohmann::json;

/// A header whose metadata carries the bake's "replay" record.
/// Frame f of a wave travelling at one period per 100 frames, 400 surface particles over 4 m.
cache::Frame periodicFrame(std::size_t f) {
    cache::Frame frame;
    for (int p = 0; p < 400; ++p) {
        const double x = (p + 0.5) / 100.0;
        frame.surface.push_back(static_cast<float>(x));
        frame.surface.push_back(static_cast<float>(
            0.5 + 0.05 * std::sin(2.0 * std::numbers::pi * (x - static_cast<double>(f) / 100.0))));
    }
    return frame;
}

cache::Header recordedHeader(double steadyStart, double xMin = 0.5, double xMax = 3.5) {
    cache::Header h = test::syntheticHeader(); // frames every 0.01 s
    h.metadataJson = json{{"replay",
                           {{"water_x_min", xMin},
                            {"water_x_max", xMax},
                            {"still_water_level", 0.5},
                            {"particle_spacing", 0.01},
                            {"steady_start_s", steadyStart},
                            {"steady_reason", "test"}}}}
                         .dump();
    return h;
}

/// A frame whose surface is the flat line y = level over x in [0, 4].
cache::Frame flatFrame(double level, int particles = 200) {
    cache::Frame f;
    for (int p = 0; p < particles; ++p) {
        f.surface.push_back(static_cast<float>(4.0 * (p + 0.5) / particles));
        f.surface.push_back(static_cast<float>(level));
    }
    return f;
}

TEST(Timeline, RangeClampsOrWraps) {
    const Timeline clamp = Timeline::range(10, 5, FramePolicy::Clamp);
    const Timeline loop = Timeline::range(10, 5, FramePolicy::Loop);
    EXPECT_EQ(clamp[clamp.index(-3)].a, 10u);
    EXPECT_EQ(clamp[clamp.index(2)].a, 12u);
    EXPECT_EQ(clamp[clamp.index(99)].a, 14u);
    EXPECT_EQ(loop[loop.index(-1)].a, 14u);
    EXPECT_EQ(loop[loop.index(7)].a, 12u);
    EXPECT_EQ(loop.maxFrame(), 14u);
    EXPECT_THROW(Timeline::range(0, 0, FramePolicy::Loop), std::invalid_argument);
    EXPECT_THROW(Timeline::range(0, 3, FramePolicy::Seamless), std::invalid_argument);
}

TEST(Timeline, SeamlessCrossFadeIsContinuous) {
    const LoopPoints loop{20, 60, 5, 0.0, 0.0};
    const Timeline t = Timeline::seamless(loop);
    ASSERT_EQ(t.size(), 40u);
    EXPECT_EQ(t[0], (TimelineEntry{20, 20, 0.0}));
    EXPECT_EQ(t[34], (TimelineEntry{54, 54, 0.0})); // last pure entry before the fade
    double previous = 0.0;
    for (std::size_t p = 35; p < 40; ++p) {
        const TimelineEntry& e = t[p];
        EXPECT_EQ(e.a, 20 + p);      // the loop's own frames run on ...
        EXPECT_EQ(e.b, 20 + p - 40); // ... and so do the frames it continues from (15 .. 19)
        EXPECT_GT(e.alpha, previous);
        EXPECT_NEAR(e.alpha - previous, 1.0 / 6.0, 1e-12); // linear weights, no jump
        previous = e.alpha;
    }
    EXPECT_NEAR(1.0 - previous, 1.0 / 6.0, 1e-12); // the next entry is frame 20 (weight 1)
    EXPECT_EQ(t[t.index(40)].a, 20u);
    EXPECT_EQ(t[t.index(-1)].a, 59u);
    EXPECT_THROW(Timeline::seamless({3, 60, 5, 0.0, 0.0}), std::invalid_argument);  // in < L
    EXPECT_THROW(Timeline::seamless({20, 30, 5, 0.0, 0.0}), std::invalid_argument); // too short
}

TEST(Timeline, LoopSearchFindsAPlantedNearRepeat) {
    // Profiles of a wave whose phase drifts irregularly; frame 190 is planted as a near copy of
    // frame 30's neighbourhood (frames 185 .. 190 repeat 25 .. 30).
    const int W = 200;
    std::vector<std::vector<double>> profiles(W, std::vector<double>(64));
    auto phaseOf = [](int f) { return 0.137 * f + 0.3 * std::sin(0.05 * f * f); };
    for (int f = 0; f < W; ++f) {
        const int g = f >= 185 && f <= 190 ? f - 160 : f;
        for (int q = 0; q < 64; ++q)
            profiles[f][q] = std::sin(0.2 * q - phaseOf(g));
    }
    const LoopPoints l = findLoop(profiles, 1000, 5);
    EXPECT_EQ(l.in, 1030u);
    EXPECT_EQ(l.out, 1190u);
    EXPECT_NEAR(l.residual, 0.0, 1e-12);
    EXPECT_GT(l.typicalDifference, 0.1);
    // Deterministic.
    const LoopPoints again = findLoop(profiles, 1000, 5);
    EXPECT_EQ(again.in, l.in);
    EXPECT_EQ(again.out, l.out);
    EXPECT_THROW(findLoop(std::span(profiles).first(6), 0, 5), std::invalid_argument);
}

TEST(Timeline, SteadyWindowStartsAtTheRecordedSteadyStart) {
    const cache::Header h = recordedHeader(1.234); // frame time 0.01 s: first frame 124
    const auto frames = test::syntheticFrames(400, 300, 3);
    ReplayParams p;
    p.fluctuation = 0.3;
    p.timeUnitSeconds = 1.0; // spread 0.6 s: the window (2.76 s) holds it
    p.policy = FramePolicy::Clamp;
    const TimelinePlan plan = planTimeline(h, frames.size(), p, [&](std::uint32_t) -> cache::Frame {
        ADD_FAILURE() << "clamp reads no frame";
        return {};
    });
    EXPECT_EQ(plan.windowFirst, 124u);
    EXPECT_EQ(plan.windowLast, 399u);
    EXPECT_EQ(plan.timeline[0].a, 124u);
    // Every frame eq. (5) can pick lies inside the window.
    const SliceSampler s(p, plan.timeline, framesPerTimeUnit(h, p));
    const std::vector<double> taus{0.0, 0.01, 1.5, 2.7, 9.0};
    for (std::uint32_t f : s.framesUsed(taus))
        EXPECT_GE(f, 124u);
    // --window all: every frame, as before the record existed.
    p.steadyWindow = false;
    const TimelinePlan all = planTimeline(h, frames.size(), p, nullptr);
    EXPECT_EQ(all.windowFirst, 0u);
}

TEST(Timeline, ShortOrEmptyWindowsAreClearErrors) {
    ReplayParams p; // F 0.3, time unit 4 s: spread 2.4 s
    p.policy = FramePolicy::Loop;
    auto message = [&](const cache::Header& h, std::size_t frames) {
        try {
            (void)planTimeline(h, frames, p, nullptr);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // 3 s of frames, steady from 1 s: a 2 s window is shorter than the 2.4 s spread.
    const std::string shortWindow = message(recordedHeader(1.0), 300);
    EXPECT_NE(shortWindow.find("shorter than the slice spread"), std::string::npos) << shortWindow;
    EXPECT_NE(shortWindow.find("bake at least 0.40 s longer"), std::string::npos) << shortWindow;
    // Steady only after the bake ends.
    const std::string empty = message(recordedHeader(5.0), 300);
    EXPECT_NE(empty.find("before its flow is steady"), std::string::npos) << empty;
    // F = 0 has no spread; a long enough bake is fine.
    EXPECT_EQ(message(recordedHeader(1.0), 400), "");
    p.fluctuation = 0.0;
    EXPECT_EQ(message(recordedHeader(1.0), 300), "");
}

TEST(Timeline, SeamlessPlanLoopsBetweenTheMostAlikeFrames) {
    // A periodic wave (period 100 frames) steady from frame 50: the loop must span whole
    // periods, so the seam repeats a frame exactly.
    cache::Header h = recordedHeader(0.5, 0.0, 4.0);
    std::vector<cache::Frame> frames(450);
    for (std::size_t f = 0; f < frames.size(); ++f)
        frames[f] = periodicFrame(f);
    ReplayParams p;
    p.policy = FramePolicy::Seamless;
    p.timeUnitSeconds = 1.0;
    p.crossfadeSeconds = 0.1; // 10 frames
    int reads = 0;
    const TimelinePlan plan = planTimeline(h, frames.size(), p, [&](std::uint32_t id) {
        ++reads;
        return frames[id];
    });
    // Only the frames the search compares, once each: in-points 10 .. 110 of the window (its
    // first quarter after the 10 cross-fade frames) with their lead-in 0 .. 9, and out-points
    // 299 .. 399 with theirs, 289 .. 298.
    EXPECT_EQ(reads, 111 + 111);
    const auto& loop = plan.timeline.loop();
    ASSERT_TRUE(loop.has_value());
    EXPECT_EQ(loop->crossfade, 10);
    EXPECT_EQ((loop->out - loop->in) % 100, 0u) << loop->in << " -> " << loop->out;
    EXPECT_LT(loop->residual, 1e-3 * loop->typicalDifference);
    EXPECT_GE(loop->in, plan.windowFirst + 10);
    const json j = toJson(plan);
    EXPECT_EQ(j["policy"], "seamless");
    EXPECT_EQ(j["loop"]["in_frame"], loop->in);
}

TEST(Timeline, LoopSearchCostDoesNotGrowWithTheCache) {
    // 400 frames: the quarters (100 candidates each side); 100,000 frames: the cap.
    const LoopSearch small = loopSearch(400, 10);
    EXPECT_EQ(small.inLo, 10);
    EXPECT_EQ(small.inHi, 110);
    EXPECT_EQ(small.outLo, 299);
    EXPECT_EQ(small.outHi, 399);
    const LoopSearch big = loopSearch(100000, 20);
    EXPECT_EQ(big.inHi - big.inLo, kMaxLoopCandidates);
    EXPECT_EQ(big.outHi - big.outLo, kMaxLoopCandidates);
    EXPECT_EQ(big.outHi, 99999);
    long long reads = 0;
    for (long long i = 0; i < 100000; ++i)
        reads += big.reads(i) ? 1 : 0;
    EXPECT_EQ(reads, 2 * (kMaxLoopCandidates + 21));
    EXPECT_THROW((void)loopSearch(20, 10), std::invalid_argument);

    // A plan over a 20,000-frame window reads only the compared frames, and the loop it finds
    // is a whole number of the wave's periods (100 frames), as with a short window.
    const cache::Header h = recordedHeader(0.0, 0.0, 4.0);
    const std::size_t n = 20000;
    ReplayParams p;
    p.policy = FramePolicy::Seamless;
    p.timeUnitSeconds = 1.0;
    p.crossfadeSeconds = 0.1; // 10 frames
    std::size_t reads20k = 0;
    const TimelinePlan plan = planTimeline(h, n, p, [&](std::uint32_t id) {
        ++reads20k;
        return periodicFrame(id);
    });
    EXPECT_EQ(reads20k, static_cast<std::size_t>(2 * (kMaxLoopCandidates + 1 + 10)));
    const auto& loop = plan.timeline.loop();
    ASSERT_TRUE(loop.has_value());
    EXPECT_EQ((loop->out - loop->in) % 100, 0u) << loop->in << " -> " << loop->out;
    EXPECT_GE(loop->out, n - 1 - kMaxLoopCandidates);
}

TEST(BakeRecord, ReadsTheRecordOrFallsBackToTheDomain) {
    const BakeRecord r = bakeRecord(recordedHeader(2.0, 0.25, 3.0));
    EXPECT_TRUE(r.recorded);
    EXPECT_EQ(r.waterXMin, 0.25);
    EXPECT_EQ(r.waterXMax, 3.0);
    EXPECT_EQ(r.particleSpacing, 0.01);
    EXPECT_EQ(r.steadyStartSeconds, 2.0);
    EXPECT_TRUE(r.note.empty());
    const BakeRecord old = bakeRecord(test::syntheticHeader());
    EXPECT_FALSE(old.recorded);
    EXPECT_EQ(old.waterXMax, 4.0);
    EXPECT_NE(old.note.find("bake again"), std::string::npos);

    cache::Header bad = test::syntheticHeader();
    bad.metadataJson = R"({"replay": {"water_x_min": 1, "water_x_max": 0.5, "still_water_level": 0,
        "particle_spacing": 0.01, "steady_start_s": 0}})";
    EXPECT_THROW(bakeRecord(bad), std::invalid_argument);
    bad.metadataJson = R"({"replay": {"water_x_min": 0, "water_x_max": 1, "still_water_level": 0,
        "particle_spacing": 0.01, "steady_start_s": "late"}})";
    try {
        (void)bakeRecord(bad);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("replay.steady_start_s"), std::string::npos);
    }
}

TEST(BakeRecord, GridColumnsLieOverTheWater) {
    const cache::Header h = recordedHeader(0.0, 0.37, 3.11);
    for (int N : {1, 7, 64, 128, 1000}) {
        ReplayParams p;
        p.cellsX = N;
        const Grid g = makeGrid(h, p);
        for (int n = 0; n < N; ++n) {
            const double x = g.x0 + (n + 0.5) * g.dx;
            EXPECT_GE(x, 0.37 - g.dx);
            EXPECT_LE(x, 3.11 + g.dx);
        }
        EXPECT_NEAR(g.x0, 0.37, 1e-12);
        EXPECT_NEAR(g.x0 + N * g.dx, 3.11, 1e-12);
        p.extentX = ExtentX::Domain;
        EXPECT_EQ(makeGrid(h, p).x0, 0.0); // the padded domain on request
        p.extentX = ExtentX::Explicit;
        p.extentX0 = 1.0;
        p.extentX1 = 2.0;
        EXPECT_NEAR(makeGrid(h, p).dx, 1.0 / N, 1e-15);
    }
}

TEST(SurfaceEnvelope, HighestParticlePerBinJoinedLinearly) {
    cache::Frame f;
    // Bin [0, 1): two particles, the higher one (0.5, 2) wins; bin [1, 2): (1.5, 4); bin [3, 4):
    // (3.5, 0) with an empty bin between.
    for (float v : {0.2f, 1.0f, 0.5f, 2.0f, 1.5f, 4.0f, 1.7f, 3.0f, 3.5f, 0.0f})
        f.surface.push_back(v);
    const SurfaceEnvelope e(f, 1.0);
    ASSERT_EQ(e.xs().size(), 3u);
    EXPECT_DOUBLE_EQ(e.at(-5.0), 2.0); // constant before the first point
    EXPECT_DOUBLE_EQ(e.at(1.0), 3.0);  // halfway between (0.5, 2) and (1.5, 4)
    EXPECT_DOUBLE_EQ(e.at(2.5), 2.0);  // halfway between (1.5, 4) and (3.5, 0)
    EXPECT_DOUBLE_EQ(e.at(9.0), 0.0);  // constant after the last
    EXPECT_TRUE(std::isnan(SurfaceEnvelope(cache::Frame{}, 1.0).at(0.0)));
    EXPECT_THROW(SurfaceEnvelope(f, 0.0), std::invalid_argument);
    (void)flatFrame;
}

} // namespace
} // namespace swell::runtime
