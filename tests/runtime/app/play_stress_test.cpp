// Replay stress (docs/validation.md, Stability stress suite): swell-play bench at the extremes of
// its parameters and on degenerate caches. Every case must either give a finite result that matches
// the double-precision CPU reference (exit 0) or stop with one clear stderr line (exit 1); never
// NaN, never a crash. tools/stress runs the slower extremes (4096 x 4096 cells) besides these.
#include "swell/cache/writer.h"

#include "app_runner.h"
#include "synthetic_frames.h"
#include "temp_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;
using Result = swell::test::AppResult;

class PlayStress : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_temp = std::make_unique<swell::test::TempDir>("swell_play_stress_");
        s_dir = s_temp->path();
        write("wave.swell", test::syntheticFrames(120, 200, 3));
        write("one.swell", test::syntheticFrames(1, 200, 3));  // a cache of one frame
        write("empty.swell", std::vector<cache::Frame>(40));   // no surface particle at all
        write("oneempty.swell", std::vector<cache::Frame>(1)); // both
        cache::Header q = test::syntheticHeader();
        q.encoding = cache::Encoding::Quantized16;
        write("wave_q16.swell", test::syntheticFrames(120, 200, 3), q);
    }
    static void TearDownTestSuite() { s_temp.reset(); }

    static void write(const std::string& name, const std::vector<cache::Frame>& frames,
                      const cache::Header& header = test::syntheticHeader()) {
        cache::Writer w(s_dir / name, header);
        for (const cache::Frame& f : frames)
            w.addFrame(f);
        w.finish();
    }
    static std::string cache(const std::string& name) { return (s_dir / name).string(); }
    static Result bench(const std::string& cacheName, const std::string& args) {
        return swell::test::runApp(
            SWELL_PLAY_EXE,
            "bench " + cache(cacheName) +
                " --frames 6 --warmup 1 --error-frames 2 --cpu-frames 1 --json " + args,
            "", s_dir);
    }
    /// Exit 0, finite, within 1e-4 of the depth of the CPU reference, same frames.
    static void expectGood(const std::string& cacheName, const std::string& args) {
        SCOPED_TRACE(cacheName + " " + args);
        const Result r = bench(cacheName, args);
        ASSERT_EQ(r.code, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(r.out);
        const double err = j["max_abs_error"].get<double>();
        EXPECT_TRUE(std::isfinite(err));
        EXPECT_TRUE(std::isfinite(j["rms_error"].get<double>()));
        EXPECT_TRUE(std::isfinite(j["fps"].get<double>()));
        EXPECT_LE(err, 1e-4 * j["water_depth"].get<double>());
        EXPECT_TRUE(j["frames_exact"].get<bool>());
    }
    /// Exit 2 (a bad value) with one stderr line that contains `what`, nothing on stdout.
    static void expectClearError(const std::string& cacheName, const std::string& args,
                                 const std::string& what) {
        SCOPED_TRACE(cacheName + " " + args);
        const Result r = bench(cacheName, args);
        EXPECT_EQ(r.code, 2);
        EXPECT_TRUE(r.out.empty()) << r.out;
        EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    static inline std::unique_ptr<swell::test::TempDir> s_temp;
    static inline fs::path s_dir;
};

} // namespace

TEST_F(PlayStress, FluctuationAtItsBoundWorksAndBeyondItIsRefused) {
    expectGood("wave.swell", "--res 32x32 --slices 16 -F 1");
    expectGood("wave.swell", "--res 32x32 --slices 16 -F 0");
    expectClearError("wave.swell", "--res 32x32 --slices 16 -F 1.0001",
                     "-F/--fluctuation must be in [0, 1] (eq. (6)");
}

TEST_F(PlayStress, NoiseExponentZeroAndFour) {
    expectGood("wave.swell", "--res 32x32 --slices 16 --beta 0");
    expectGood("wave.swell", "--res 32x32 --slices 16 --beta 4");
}

TEST_F(PlayStress, SliceCountOneIsRefusedAndFourThousandNinetySixWorks) {
    expectClearError("wave.swell", "--res 16x16 --slices 1",
                     "--slices must be in [2, 16384], got 1");
    expectGood("wave.swell", "--res 16x16 --slices 4096");
    expectGood("wave.swell", "--res 16x16 --slices 2");
}

TEST_F(PlayStress, OneCellAndFourThousandNinetySixCellsPerSide) {
    expectGood("wave.swell", "--res 1x1 --slices 4");
    expectGood("wave.swell", "--res 4096x1 --slices 4");
    // Found by the stress suite: rows far from their only slice (M > 2K) had G_z = 0 in float
    // and the GPU wrote 0 / 0 = NaN there; the CPU reference did the same when the slice was
    // more than ~77 sigma away (K = 2, M = 4096).
    expectGood("wave.swell", "--res 1x4096 --slices 64");
    expectGood("wave.swell", "--res 1x4096 --slices 2");
    expectGood("wave.swell", "--res 16x4096 --slices 4 --mode ripple");
    expectClearError("wave.swell", "--res 0x16", "");
}

// Found by the stress suite: at sigma 0.1 cells the GPU's float32 Gaussian weights underflowed
// inside the window and the GPU fell back where the reference did not (0.16 m apart).
TEST_F(PlayStress, TinySigmaIsRefusedInsteadOfDisagreeingWithTheReference) {
    expectClearError("wave.swell", "--res 32x32 --slices 16 --sigma 0.1", "sigma must be >= 0.25");
    expectGood("wave.swell", "--res 32x32 --slices 16 --sigma 0.25");
    expectGood("wave.swell", "--res 32x32 --slices 16 --sigma 64");
}

TEST_F(PlayStress, CacheOfOneFrameInEveryModeAndPolicy) {
    expectGood("one.swell", "--res 32x32 --slices 16");
    expectGood("one.swell", "--res 32x32 --slices 16 --policy clamp");
    expectGood("one.swell", "--res 32x32 --slices 16 --mode ripple");
    expectGood("one.swell", "--res 32x32 --slices 16 --mode whirlpool");
}

TEST_F(PlayStress, FramesWithoutSurfaceParticlesGiveTheDomainBottom) {
    for (const char* c : {"empty.swell", "oneempty.swell"}) {
        expectGood(c, "--res 32x32 --slices 16");
        expectGood(c, "--res 32x32 --slices 16 --mode ripple");
        expectGood(c, "--res 32x32 --slices 16 --mode whirlpool");
    }
    // The height field itself: every cell at the domain's yMin (0 here), none NaN.
    const Result r = swell::test::runApp(SWELL_PLAY_EXE,
                                         "heights " + cache("empty.swell") + " --out " +
                                             (s_dir / "empty_heights").string() +
                                             " --res 8x8 --slices 4 --seconds 0.1 --json",
                                         "", s_dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(s_dir / "empty_heights" / "height_00000.png"));
}

// Compression against error (tools/bench): the CPU reference reads the float32 original.
TEST_F(PlayStress, ReferenceCacheMeasuresTheQuantizationError) {
    const Result r =
        bench("wave_q16.swell", "--res 64x32 --slices 16 --reference-cache " + cache("wave.swell"));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const double err = j["max_abs_error"].get<double>();
    EXPECT_GT(err, 1e-7); // the encoding's error shows
    // Quantized16 moves particles by at most 31 um in x here, but one that crosses a bin edge
    // enters or leaves eq. (7)'s cut-off window (weight exp(-1.5^2 / 8) = 0.75 at its edge), so
    // the height error is millimetres, not micrometres.
    EXPECT_LT(err, 0.01);
    EXPECT_EQ(j["reference_cache"], cache("wave.swell"));
    // A reference with another frame count is refused.
    const Result bad = bench("wave_q16.swell", "--reference-cache " + cache("one.swell"));
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("--reference-cache"), std::string::npos) << bad.err;
}
} // namespace swell::runtime
