// Playback (the replay of one cache for embedding) against the analytic wave the cache holds,
// against the double-precision CPU reference, and its errors (llvmpipe in CI).
#include "swell/runtime/playback.h"

#include "swell/cache/synthetic.h"
#include "swell/cache/writer.h"
#include "swell/runtime/modes/mode_splashes.h"

#include "gl_fixture.h"
#include "temp_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <memory>

namespace swell::runtime {
namespace {

/// A swell-cache synth cache of `frames` frames of `wave` at `path` (with the bake's record).
void writeSynthetic(const std::filesystem::path& path, const cache::SyntheticWave& wave,
                    std::size_t frames) {
    cache::Header h;
    h.domain = cache::syntheticDomain(wave);
    h.dt = 0.001;
    h.frameInterval = static_cast<std::uint32_t>(std::lround(wave.frameTime / h.dt));
    h.metadataJson = nlohmann::json{{"replay", cache::syntheticReplayJson(wave)}}.dump();
    cache::Writer w(path, h);
    for (std::size_t i = 0; i < frames; ++i)
        w.addFrame(cache::syntheticFrame(wave, i));
    w.finish();
}

class PlaybackTest : public swell::test::GlSuite {
protected:
    static void SetUpTestSuite() {
        GlSuite::SetUpTestSuite();
        s_dir = std::make_unique<swell::test::TempDir>("swell_playback_");
        s_wave.surfaceCount = 800;
        s_wave.splashCount = 3;
        writeSynthetic(*s_dir / "wave.swell", s_wave, 240);
        writeSynthetic(*s_dir / "short.swell", s_wave, 3);
    }
    static void TearDownTestSuite() {
        s_dir.reset();
        GlSuite::TearDownTestSuite();
    }
    static inline std::unique_ptr<swell::test::TempDir> s_dir;
    static inline cache::SyntheticWave s_wave;
};

/// With F = 0 every slice shows the frame of time t, so every row of the field is that frame's
/// surface: the cache's analytic wave at the cell centres, within the envelope's sampling error.
TEST_F(PlaybackTest, ShowsTheWaveTheCacheHolds) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackConfig config;
    config.params.fluctuation = 0.0;
    config.params.policy = FramePolicy::Clamp;
    config.params.steadyWindow = false;
    config.params.cellsX = 64;
    config.params.cellsZ = 8;
    Playback playback(reader, config);
    const Grid& g = playback.grid();
    for (const double t : {0.4, 1.0, 2.2}) { // whole frames (frame time 0.02 s)
        playback.advance(t);
        const HeightField& h = playback.heights();
        double worst = 0.0;
        for (int m = 0; m < g.cellsZ; ++m) {
            for (int n = 0; n < g.cellsX; ++n) {
                const double x = g.x0 + (n + 0.5) * g.dx;
                worst =
                    std::max(worst, std::abs(h.at(n, m) - cache::syntheticHeight(s_wave, x, t)));
            }
        }
        EXPECT_LT(worst, 0.002) << "t = " << t; // amplitude 0.05 m
    }
}

TEST_F(PlaybackTest, MatchesTheCpuReferenceAndHoldsOnlyTimelineFrames) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackConfig config;
    config.params.cellsX = config.params.cellsZ = 48;
    config.params.slices = 64;
    Playback playback(reader, config);
    EXPECT_EQ(playback.frames().ids, timelineFrames(playback.plan().timeline));
    EXPECT_LT(playback.frames().ids.size(), reader.frameCount()); // the seamless loop's frames
    const std::vector<SliceSampler> samplers =
        makeSamplers(playback.config().params, playback.config().mode, playback.plan().timeline,
                     framesPerTimeUnit(reader.header(), playback.config().params));
    const CpuModeReference cpu(playback.frames(), playback.config().params, playback.config().mode,
                               samplers);
    for (const double t : {0.0, 0.77, 3.1, 40.0}) { // 40 s: far past the cache's 4.8 s (loops)
        playback.advance(t);
        const HeightField& gpu = playback.heights();
        const HeightField ref = cpu.heights(t / playback.config().params.timeUnitSeconds);
        ASSERT_EQ(gpu.heights.size(), ref.heights.size());
        for (std::size_t i = 0; i < ref.heights.size(); ++i)
            ASSERT_NEAR(gpu.heights[i], ref.heights[i], 1e-4) << "t = " << t << ", cell " << i;
    }
}

TEST_F(PlaybackTest, AutoResolutionAndPointQueries) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackConfig config;
    config.params.cellsX = 0; // auto: one cell per particle spacing
    config.params.slices = 32;
    Playback playback(reader, config);
    EXPECT_EQ(playback.grid().cellsX, autoCells(reader.header(), config.params));
    EXPECT_GT(playback.grid().cellsX, 100);
    playback.advance(1.3);
    const Grid& g = playback.grid();
    const std::vector<double> x{g.x0 + 2.5 * g.dx, g.x0 - 0.1, g.x0 + 7.5 * g.dx};
    const std::vector<double> z{3.5 * g.dz, 0.5, 11.5 * g.dz};
    std::vector<double> out(3);
    playback.sample(x, z, out);
    EXPECT_DOUBLE_EQ(out[0], playback.heights().at(2, 3));
    EXPECT_TRUE(std::isnan(out[1]));
    EXPECT_DOUBLE_EQ(out[2], playback.heights().at(7, 11));
}

TEST_F(PlaybackTest, SplashesAreTheRenderersAndDeterministic) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackConfig config;
    config.params.cellsX = config.params.cellsZ = 32;
    config.params.slices = 16;
    Playback a(reader, config), b(reader, config);
    a.advance(0.9);
    b.advance(0.9);
    const std::vector<SplashSprite> sa = a.splashes(), sb = b.splashes();
    // 16 real slices x 3 splash particles x (1 real + 6 artificial) = 336 made; the 5 that
    // flew out of the tank are dropped (placeSplashes), every other one is inside it.
    EXPECT_EQ(sa.size(), 16u * 3u * 7u - 5u);
    const Grid& g = a.grid();
    for (const SplashSprite& s : sa) {
        EXPECT_GE(s.x, g.x0);
        EXPECT_LE(s.x, g.x0 + g.cellsX * g.dx);
        EXPECT_GE(s.z, 0.0);
        EXPECT_LE(s.z, g.extentZ);
    }
    ASSERT_EQ(sa.size(), sb.size());
    for (std::size_t i = 0; i < sa.size(); ++i) {
        EXPECT_EQ(sa[i].x, sb[i].x);
        EXPECT_EQ(sa[i].y, sb[i].y);
    }
    config.splash.enabled = false;
    Playback none(reader, config);
    none.advance(0.9);
    EXPECT_TRUE(none.splashes().empty());
}

TEST_F(PlaybackTest, ErrorsNameTheProblem) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackConfig config;
    config.params.cellsX = config.params.cellsZ = 16;
    config.params.slices = 8;
    Playback playback(reader, config);
    EXPECT_THROW(playback.advance(std::nan("")), std::invalid_argument);
    config.params.fluctuation = 2.0;
    EXPECT_THROW(Playback(reader, config), std::invalid_argument);
    config.params.fluctuation = 0.3;
    const cache::Reader tooShort(*s_dir / "short.swell");
    try {
        Playback p(tooShort, config);
        FAIL() << "a 3-frame cache cannot hold a 2.4 s slice spread";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("short.swell"), std::string::npos) << e.what();
    }
}

TEST_F(PlaybackTest, ATimelineBeyondTheMemoryBudgetIsRefusedBeforeDecoding) {
    const cache::Reader reader(*s_dir / "wave.swell");
    PlaybackChoice choice;
    choice.cellsX = choice.cellsZ = 16;
    choice.slices = 8;
    choice.named = {{"memory_budget_gib", 1e-5}}; // about 10 KiB
    const PlaybackConfig config = playbackConfig(choice, "test");
    EXPECT_EQ(config.memoryBudgetGiB, 1e-5);
    try {
        Playback p(reader, config);
        FAIL() << "10 KiB cannot hold the timeline's frames";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("wave.swell"), std::string::npos) << what;
        EXPECT_NE(what.find("above the memory budget"), std::string::npos) << what;
        EXPECT_NE(what.find("memory_budget_gib"), std::string::npos) << what;
    }
    choice.named = {{"memory_budget_gib", 1.0}};
    EXPECT_NO_THROW(Playback(reader, playbackConfig(choice, "test")));
    for (const nlohmann::json& bad :
         {nlohmann::json(0.0), nlohmann::json("2"), nlohmann::json(-1)}) {
        choice.named = {{"memory_budget_gib", bad}};
        EXPECT_THROW((void)playbackConfig(choice, "test"), std::invalid_argument) << bad;
    }
}

} // namespace
} // namespace swell::runtime
