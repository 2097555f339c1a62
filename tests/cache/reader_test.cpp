#include "cache_test_util.h"

#include "swell/cache/error.h"
#include "swell/cache/reader.h"

#include <cmath>
#include <nlohmann/json.hpp>

using namespace swell::cache;
using namespace swell::cache::testing;

namespace {

struct Filters {
    bool shuffle, delta;
};

class RoundTrip : public ::testing::TestWithParam<Filters> {};

} // namespace

TEST_P(RoundTrip, Float32IsBitExact) {
    TempDir dir;
    const auto w = smallWave(57, 5);
    Header h = headerFor(w);
    h.shuffle = GetParam().shuffle;
    h.delta = GetParam().delta;
    const auto frames = writeSynthetic(dir / "a.swell", h, w, 25);
    const Reader r(dir / "a.swell");
    ASSERT_EQ(r.frameCount(), frames.size());
    const auto all = r.readAll();
    for (std::size_t i = 0; i < frames.size(); ++i) {
        ASSERT_EQ(all[i].surface.size(), frames[i].surface.size());
        EXPECT_EQ(std::memcmp(all[i].surface.data(), frames[i].surface.data(),
                              frames[i].surface.size() * 4),
                  0);
        EXPECT_EQ(all[i], frames[i]);
        EXPECT_EQ(r.frameInfo(i).surfaceCount, 57u);
        EXPECT_EQ(r.frameInfo(i).splashCount, 5u);
    }
}

TEST_P(RoundTrip, QuantizedWithinStatedError) {
    TempDir dir;
    const auto w = smallWave(300, 7);
    Header h = headerFor(w, Encoding::Quantized16);
    h.shuffle = GetParam().shuffle;
    h.delta = GetParam().delta;
    const auto frames = writeSynthetic(dir / "q.swell", h, w, 10);
    const Reader r(dir / "q.swell");
    const float bound = r.header().maxPositionError();
    EXPECT_GT(bound, 0.0f);
    const Domain d = syntheticDomain(w);
    EXPECT_LE(bound, 0.51 * (d.xMax - d.xMin) / 65535.0 + 1e-6);
    double worst = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Frame f = r.readFrame(i);
        ASSERT_EQ(f.surface.size(), frames[i].surface.size());
        for (std::size_t k = 0; k < f.surface.size(); ++k)
            worst = std::max(worst, std::fabs(double(f.surface[k]) - frames[i].surface[k]));
        for (std::size_t p = 0; p < f.splashCount(); ++p) {
            for (int c = 0; c < 2; ++c)
                worst = std::max(
                    worst, std::fabs(double(f.splash[4 * p + c]) - frames[i].splash[4 * p + c]));
            EXPECT_EQ(f.splash[4 * p + 2], frames[i].splash[4 * p + 2]); // velocities lossless
            EXPECT_EQ(f.splash[4 * p + 3], frames[i].splash[4 * p + 3]);
        }
    }
    EXPECT_LE(worst, bound);
    EXPECT_GT(worst, 0.25 * bound); // really quantized, and the bound is not loose
}

INSTANTIATE_TEST_SUITE_P(Filters, RoundTrip,
                         ::testing::Values(Filters{true, true}, Filters{true, false},
                                           Filters{false, true}, Filters{false, false}),
                         [](const auto& info) {
                             return std::string(info.param.shuffle ? "Shuffle" : "NoShuffle") +
                                    (info.param.delta ? "Delta" : "NoDelta");
                         });

TEST(Reader, HeaderRoundTrips) {
    TempDir dir;
    const auto w = smallWave();
    Header h = headerFor(w);
    h.seed = 0xdeadbeefcafef00dULL;
    h.frameInterval = 37;
    h.dt = 0.0005;
    h.compressionLevel = 7;
    writeSynthetic(dir / "a.swell", h, w, 1);
    const Reader r(dir / "a.swell");
    EXPECT_EQ(r.version(), kFormatVersion);
    EXPECT_EQ(r.header().seed, h.seed);
    EXPECT_EQ(r.header().frameInterval, 37u);
    EXPECT_EQ(r.header().dt, 0.0005);
    EXPECT_EQ(r.header().compressionLevel, 7);
    EXPECT_EQ(r.header().metadataJson, h.metadataJson);
    EXPECT_EQ(r.header().domain.xMax, h.domain.xMax);
    EXPECT_DOUBLE_EQ(r.header().frameTime(), 0.0005 * 37);
    EXPECT_EQ(r.fileSize(), fs::file_size(dir / "a.swell"));
}

TEST(Reader, RandomAccessMatchesSequential) {
    TempDir dir;
    const auto w = smallWave(120, 4);
    const auto frames = writeSynthetic(dir / "a.swell", headerFor(w), w, 40);
    const Reader r(dir / "a.swell");
    for (std::size_t i : {39u, 0u, 17u, 17u, 3u, 38u})
        EXPECT_EQ(r.readFrame(i), frames[i]) << "frame " << i;
    EXPECT_THROW((void)r.readFrame(40), std::out_of_range);
}

TEST(Reader, EmptyFramesAndEmptyCache) {
    TempDir dir;
    const auto w = smallWave();
    {
        Writer writer(dir / "e.swell", headerFor(w));
        writer.addFrame(Frame{});
        writer.addFrame(syntheticFrame(w, 1));
        writer.addFrame(Frame{});
        writer.finish();
    }
    const Reader r(dir / "e.swell");
    ASSERT_EQ(r.frameCount(), 3u);
    EXPECT_EQ(r.readFrame(0), Frame{});
    EXPECT_EQ(r.readFrame(1), syntheticFrame(w, 1));
    EXPECT_EQ(r.readAll().size(), 3u);
    {
        Writer writer(dir / "none.swell", headerFor(w));
        writer.finish();
    }
    EXPECT_EQ(Reader(dir / "none.swell").frameCount(), 0u);
    EXPECT_TRUE(Reader(dir / "none.swell").readAll().empty());
}

TEST(Reader, SurvivesTheFileBeingReplaced) {
    // The reader keeps its descriptor: a new bake renamed over the path does not
    // change what an open reader decodes.
    TempDir dir;
    const auto w = smallWave();
    const auto frames = writeSynthetic(dir / "a.swell", headerFor(w), w, 5);
    const Reader r(dir / "a.swell");
    auto w2 = w;
    w2.seed = 99;
    writeSynthetic(dir / "a.swell", headerFor(w2), w2, 2);
    EXPECT_EQ(r.readFrame(4), frames[4]);
}

TEST(Reader, MissingFileNamesIt) {
    try {
        Reader r("/nonexistent/x.swell");
        FAIL();
    } catch (const CacheError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/x.swell"), std::string::npos);
    }
}

TEST(Synthetic, IsDeterministicAndInsideItsDomain) {
    const auto w = smallWave(100, 10);
    EXPECT_EQ(syntheticFrame(w, 5), syntheticFrame(w, 5));
    EXPECT_NE(syntheticFrame(w, 5), syntheticFrame(w, 6));
    const Domain d = syntheticDomain(w);
    for (std::size_t i = 0; i < 50; ++i) {
        const Frame f = syntheticFrame(w, i);
        for (std::size_t k = 0; k < f.surfaceCount(); ++k) {
            EXPECT_GE(f.surface[2 * k], d.xMin);
            EXPECT_LE(f.surface[2 * k], d.xMax);
            EXPECT_NEAR(f.surface[2 * k + 1], syntheticHeight(w, f.surface[2 * k], i * w.frameTime),
                        1e-6);
        }
    }
}

TEST(Synthetic, ReplayBlockDescribesTheWave) {
    // The schema swell-bake writes (docs/cache-format.md): water over [0, length], still water
    // at depth, spacing length / (surfaceCount - 1), steady from the start.
    SyntheticWave w;
    w.surfaceCount = 401;
    w.length = 4.0f;
    w.depth = 0.5f;
    const nlohmann::json j = syntheticReplayJson(w);
    EXPECT_EQ(j.size(), 6u) << j.dump();
    EXPECT_EQ(j["water_x_min"], 0.0);
    EXPECT_EQ(j["water_x_max"], 4.0);
    EXPECT_EQ(j["still_water_level"], 0.5);
    EXPECT_DOUBLE_EQ(j["particle_spacing"].get<double>(), 0.01);
    EXPECT_EQ(j["steady_start_s"], 0.0);
    EXPECT_EQ(j["steady_reason"], "synthetic travelling wave: steady from the start");
}
