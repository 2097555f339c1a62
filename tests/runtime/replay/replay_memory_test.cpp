// The replay's memory estimate: exact for the decoded frames (from the cache's index), never
// below what GpuReplay actually uploads, and the budget's errors.
#include "swell/runtime/replay/replay_memory.h"

#include "swell/cache/writer.h"
#include "swell/runtime/replay/gpu_replay.h"
#include "swell/runtime/replay/timeline.h"

#include "gl_fixture.h"
#include "synthetic_frames.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <string>

namespace swell::runtime {
namespace {

class ReplayMemoryTest : public swell::test::GlSuite {
protected:
    static void SetUpTestSuite() {
        swell::test::GlSuite::SetUpTestSuite();
        s_temp = new swell::test::TempDir();
        s_path = s_temp->path() / "wave.swell";
        cache::Writer w(s_path, test::syntheticHeader());
        for (const cache::Frame& f : test::syntheticFrames(300, 150, 4))
            w.addFrame(f);
        w.finish();
    }
    static void TearDownTestSuite() {
        delete s_temp;
        swell::test::GlSuite::TearDownTestSuite();
    }
    static inline swell::test::TempDir* s_temp = nullptr;
    static inline std::filesystem::path s_path;
};

TEST_F(ReplayMemoryTest, DecodedBytesComeExactlyFromTheIndex) {
    const cache::Reader reader(s_path);
    std::vector<std::uint32_t> ids(120);
    std::iota(ids.begin(), ids.end(), 100u);
    const Timeline whole = Timeline::whole(reader.frameCount(), FramePolicy::Loop);
    const ReplayMemory m = estimateReplayMemory(reader, ids, ReplayParams{}, 1, whole);
    std::size_t bytes = 0;
    for (std::uint32_t id : ids) {
        const cache::Frame f = reader.readFrame(id);
        bytes += (f.surface.size() + f.splash.size()) * sizeof(float) + sizeof(cache::Frame);
    }
    EXPECT_EQ(m.frames, 120u);
    EXPECT_EQ(m.decodedBytes, bytes);
    // GPU buffers grow with the frames held, the mesh and the slice sets.
    ReplayParams wide;
    wide.cellsX = 4 * wide.cellsX;
    EXPECT_GT(estimateReplayMemory(reader, ids, wide, 1, whole).gpuBytes, 3 * m.gpuBytes / 2);
    EXPECT_GT(estimateReplayMemory(reader, ids, ReplayParams{}, 3, whole).gpuBytes, 2 * m.gpuBytes);
    std::vector<std::uint32_t> fewer(ids.begin(), ids.begin() + 10);
    EXPECT_LT(estimateReplayMemory(reader, fewer, ReplayParams{}, 1, whole).total(), m.total() / 4);
}

TEST_F(ReplayMemoryTest, GpuEstimateCoversWhatTheReplayUploads) {
    const cache::Reader reader(s_path);
    for (const Reconstruction r : {Reconstruction::Paper, Reconstruction::Envelope}) {
        for (const int N : {16, 100, 257}) {
            ReplayParams p = test::sized(N, 64, 32, ReplayParams{});
            p.reconstruction = r;
            p.steadyWindow = false;
            const TimelinePlan plan =
                planTimeline(reader.header(), reader.frameCount(), p,
                             [&](std::uint32_t id) { return reader.readFrame(id); });
            const SliceSampler sampler(p, plan.timeline, framesPerTimeUnit(reader.header(), p));
            const std::vector<double> taus{0.1, 0.2, 0.3, 0.4};
            std::vector<std::uint32_t> ids = sampler.framesUsed(taus);
            FrameSet set;
            set.header = reader.header();
            set.frameCount = reader.frameCount();
            set.ids = ids;
            for (std::uint32_t id : ids)
                set.frames.push_back(reader.readFrame(id));
            const GpuReplay gpu(set, p, sampler);
            const ReplayMemory m = estimateReplayMemory(reader, ids, p, 1, plan.timeline);
            SCOPED_TRACE(::testing::Message() << toString(r) << " N " << N);
            EXPECT_GE(m.gpuBytes, gpu.uploadedBytes());
            EXPECT_LT(m.gpuBytes, 4 * gpu.uploadedBytes() + 64 * 1024 * 4 * 2); // not wildly high
        }
    }
}

TEST(ReplayMemory, BudgetErrorsNameTheOptionAndTheSizes) {
    EXPECT_EQ(budgetBytes(2.0, "--memory-budget"), 2ull << 30);
    for (double bad : {0.0, -1.0, 2000.0, std::nan("")}) {
        try {
            (void)budgetBytes(bad, "--memory-budget");
            ADD_FAILURE() << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("--memory-budget"), std::string::npos);
        }
    }
    ReplayMemory m;
    m.frames = 5000;
    m.decodedBytes = 3ull << 30;
    m.gpuBytes = 512ull << 20;
    m.stagingBytes = 100ull << 10;
    EXPECT_NO_THROW(checkMemoryBudget(m, 4ull << 30, "w", "--memory-budget", "advice"));
    try {
        checkMemoryBudget(m, 2ull << 30, "c.swell: this replay", "--memory-budget", "lower it");
        ADD_FAILURE() << "over budget";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        for (const char* part :
             {"c.swell: this replay needs about 3.50 GiB", "5000 frames", "decoded: 3.00 GiB",
              "GPU buffers: 512.0 MiB", "upload copies: 100 KiB",
              "budget of 2.00 GiB (--memory-budget)", "lower it"})
            EXPECT_NE(what.find(part), std::string::npos) << part << " in: " << what;
    }
}

} // namespace
} // namespace swell::runtime
