// End to end: swell-play on a small cache written with swell::cache::Writer.
#include "swell/cache/writer.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

struct Result {
    int code = -1;
    std::string out;
    std::string err;
};

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

class PlayApp : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_dir = fs::temp_directory_path() / ("swell_play_test_" + std::to_string(::getpid()));
        fs::create_directories(s_dir);
        cache::Writer w(s_dir / "wave.swell", test::syntheticHeader());
        for (const cache::Frame& f : test::syntheticFrames(400, 200, 3))
            w.addFrame(f);
        w.finish();
    }
    static void TearDownTestSuite() { fs::remove_all(s_dir); }

    /// Runs swell-play with `args`, environment assignments `env` first.
    static Result run(const std::string& args, const std::string& env = "") {
        const fs::path out = s_dir / "stdout.txt", err = s_dir / "stderr.txt";
        const std::string cmd = env + " " + std::string(SWELL_PLAY_EXE) + " " + args + " >" +
                                out.string() + " 2>" + err.string();
        const int status = std::system(cmd.c_str());
        Result r;
        r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = slurp(out);
        r.err = slurp(err);
        return r;
    }
    static std::string cachePath() { return (s_dir / "wave.swell").string(); }
    static inline fs::path s_dir;
};

} // namespace

TEST_F(PlayApp, BenchJsonReportsTimingAndErrorAgainstTheReference) {
    const Result r = run("bench " + cachePath() +
                         " --res 64x48 --slices 32 --frames 40 --warmup 5 --error-frames 3 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* key :
         {"renderer", "fps", "frame_ms_median", "frame_ms_p95", "max_abs_error", "rms_error",
          "stage_gpu_ms", "mode", "frames_exact", "cpu_reference_fps"}) {
        EXPECT_TRUE(j.contains(key)) << key;
    }
    EXPECT_EQ(j["mode"], "surging");
    EXPECT_TRUE(j["frames_exact"].get<bool>());
    EXPECT_GT(j["fps"].get<double>(), 0.0);
    EXPECT_LE(j["max_abs_error"].get<double>(), 1e-4 * test::kSyntheticDepth);
    EXPECT_EQ(j["res"], nlohmann::json({64, 48}));
    EXPECT_TRUE(j["stage_gpu_ms"].contains("reconstruct"));
    // 45 frames at 30 fps = 1.5 s of a 4 s cache, F = 0.3 of a 4 s time unit: not every frame.
    EXPECT_LT(j["frames_decoded"].get<int>(), j["frames_in_cache"].get<int>());
}

TEST_F(PlayApp, BenchReportsRippleAndWhirlpoolWithTheirTable4Defaults) {
    const std::string common =
        " --res 48x40 --frames 20 --warmup 2 --error-frames 2 --cpu-frames 1 --json";
    const Result r = run("bench " + cachePath() + " --mode ripple --angles 0 30 60" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["mode"], "ripple");
    EXPECT_EQ(j["slice_sets"], 3);
    EXPECT_EQ(j["mode_params"]["ripple"]["angles_degrees"], nlohmann::json({0.0, 30.0, 60.0}));
    EXPECT_EQ(j["slices"], 256); // Table 4: ripple K 256, F 0.4, beta 2.5, c 128
    EXPECT_EQ(j["fluctuation"], 0.4);
    EXPECT_EQ(j["beta"], 2.5);
    EXPECT_TRUE(j["frames_exact"].get<bool>());
    EXPECT_LE(j["max_abs_error"].get<double>(), 1e-4 * test::kSyntheticDepth);
    EXPECT_TRUE(j["stage_gpu_ms"].contains("synthesis"));

    const Result w =
        run("bench " + cachePath() + " --mode whirlpool --cutoff 32 --spiral-a 5" + common);
    ASSERT_EQ(w.code, 0) << w.err;
    j = nlohmann::json::parse(w.out);
    EXPECT_EQ(j["mode"], "whirlpool");
    EXPECT_EQ(j["slices"], 128); // Table 4 / Sec. 6: K 128, c 64 unless given
    EXPECT_EQ(j["cutoff"], 32.0);
    EXPECT_EQ(j["mode_params"]["whirlpool"]["inner_radius_cells"], 5.0);
    EXPECT_TRUE(j["frames_exact"].get<bool>());
    EXPECT_LE(j["max_abs_error"].get<double>(), 1e-4 * test::kSyntheticDepth);
    EXPECT_EQ(j["stage_gpu_ms"]["reconstruct"], 0.0); // no surging reconstruction

    const Result h = run("heights " + cachePath() + " --mode whirlpool --out " +
                         (s_dir / "w").string() + " --res 32x32 --seconds 0.1 --fps 20 --json");
    ASSERT_EQ(h.code, 0) << h.err;
    EXPECT_EQ(nlohmann::json::parse(h.out)["mode"], "whirlpool");
    EXPECT_EQ(nlohmann::json::parse(slurp(s_dir / "w" / "heights.json"))["mode"], "whirlpool");
}

TEST_F(PlayApp, HeightsAreByteIdenticalForTheSameSeedAndDifferForAnother) {
    const std::string common = " --res 40x24 --slices 64 --seconds 0.2 --fps 20 --json";
    ASSERT_EQ(
        run("heights " + cachePath() + " --out " + (s_dir / "a").string() + " --seed 5" + common)
            .code,
        0);
    ASSERT_EQ(
        run("heights " + cachePath() + " --out " + (s_dir / "b").string() + " --seed 5" + common)
            .code,
        0);
    const Result c =
        run("heights " + cachePath() + " --out " + (s_dir / "c").string() + " --seed 6" + common);
    ASSERT_EQ(c.code, 0) << c.err;
    int differ = 0;
    for (int i = 0; i < 4; ++i) {
        const std::string name = "height_0000" + std::to_string(i) + ".png";
        const std::string a = slurp(s_dir / "a" / name);
        ASSERT_FALSE(a.empty()) << name;
        EXPECT_EQ(a, slurp(s_dir / "b" / name)) << name;
        differ += a != slurp(s_dir / "c" / name);
    }
    EXPECT_GE(differ, 3);
    const nlohmann::json meta = nlohmann::json::parse(slurp(s_dir / "a" / "heights.json"));
    EXPECT_EQ(meta["seed"], 5);
    EXPECT_EQ(meta["count"], 4);
    EXPECT_GT(meta["scale"]["scale"].get<double>(), 0.0);
    EXPECT_EQ(meta["frames"].size(), 4u);
}

TEST_F(PlayApp, BadInputGivesOneClearLineAndNonZeroExit) {
    const std::array<std::pair<std::string, std::string>, 9> cases = {{
        {"bench " + cachePath() + " --mode tsunami", "--mode"},
        {"bench " + cachePath() + " --mode ripple --angles 0 30 --weights 1", "ripple.weights"},
        {"bench " + cachePath() + " --mode whirlpool --spiral-b 25", "whirlpool.growth"},
        {"bench " + cachePath() + " --no-such-option", "no-such-option"},
        {"bench", "CACHE"},
        {"bench " + (s_dir / "missing.swell").string(), "missing.swell"},
        {"bench " + cachePath() + " --res 64by64", "--res"},
        {"bench " + cachePath() + " -F 1.5", "eq. (6)"},
        {"heights " + cachePath() + " --out " + (s_dir / "x").string() + " --policy bounce",
         "policy"},
    }};
    for (const auto& [args, needle] : cases) {
        const Result r = run(args);
        EXPECT_NE(r.code, 0) << args;
        EXPECT_NE(r.err.find("swell-play: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_EQ(run("--help").code, 0);
}

TEST_F(PlayApp, NoEglIsOneClearLine) {
    // glvnd with no vendor library: no EGL display can be had.
    const Result r = run("bench " + cachePath() + " --frames 5",
                         "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("swell-play: no usable EGL display"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

} // namespace swell::runtime
