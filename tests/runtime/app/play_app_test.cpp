// End to end: swell-play on a small cache written with swell::cache::Writer.
#include "swell/cache/writer.h"
#include "swell/runtime/io/height_exr.h"
#include "swell/runtime/io/height_png.h"

#include "app_runner.h"
#include "synthetic_frames.h"
#include "temp_dir.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

using Result = swell::test::AppResult;
using swell::test::slurp;

class PlayApp : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_temp = std::make_unique<swell::test::TempDir>("swell_play_test_");
        s_dir = s_temp->path();
        cache::Writer w(s_dir / "wave.swell", test::syntheticHeader());
        for (const cache::Frame& f : test::syntheticFrames(400, 200, 3))
            w.addFrame(f);
        w.finish();
    }
    static void TearDownTestSuite() { s_temp.reset(); }

    /// Runs swell-play with `args`, environment assignments `env` first.
    static Result run(const std::string& args, const std::string& env = "") {
        return swell::test::runApp(SWELL_PLAY_EXE, args, env, s_dir);
    }
    static std::string cachePath() { return (s_dir / "wave.swell").string(); }
    static inline std::unique_ptr<swell::test::TempDir> s_temp;
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

TEST_F(PlayApp, HeightsBeyondTheMemoryBudgetStreamInChunksWithTheSameHeights) {
    // Halve the budget until the replay no longer fits at once: it must then run in chunks and
    // write the same files; below what one output frame needs it must stop before writing.
    const std::string common =
        " --res 40x24 --slices 64 --seconds 4 --fps 10 --policy loop --window all --json";
    const fs::path whole = s_dir / "budget-whole";
    const Result w = run("heights " + cachePath() + " --out " + whole.string() + common);
    ASSERT_EQ(w.code, 0) << w.err;
    ASSERT_EQ(nlohmann::json::parse(w.out)["stream_chunks"], 1);
    bool streamed = false, refused = false;
    for (double budget = 0.01; budget > 1e-7 && !refused; budget /= 2) {
        const fs::path out = s_dir / fmt::format("budget-{}", budget);
        const Result r = run("heights " + cachePath() + " --out " + out.string() + common +
                             " --memory-budget " + fmt::format("{}", budget));
        if (r.code != 0) {
            refused = true;
            EXPECT_NE(r.err.find("--memory-budget"), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("one output frame alone needs about"), std::string::npos) << r.err;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
            EXPECT_FALSE(fs::exists(out)) << "nothing is written when the budget is too small";
            break;
        }
        const nlohmann::json j = nlohmann::json::parse(r.out);
        if (j["stream_chunks"].get<int>() == 1)
            continue;
        streamed = true;
        EXPECT_GT(j["frames_decoded"].get<int>(), 0);
        for (int i = 0; i < 40; ++i) {
            const std::string name = fmt::format("height_{:05}.png", i);
            const std::string a = slurp(whole / name);
            ASSERT_FALSE(a.empty()) << name;
            EXPECT_EQ(a, slurp(out / name)) << name << " with a budget of " << budget << " GiB";
        }
        const nlohmann::json meta = nlohmann::json::parse(slurp(out / "heights.json"));
        EXPECT_EQ(meta["memory"]["stream_chunks"], j["stream_chunks"]);
        EXPECT_EQ(meta["memory"]["budget_gib"], budget);
    }
    EXPECT_TRUE(streamed);
    EXPECT_TRUE(refused);
}

TEST_F(PlayApp, BadInputGivesOneClearLineAndNonZeroExit) {
    const std::array<std::pair<std::string, std::string>, 15> cases = {{
        {"rendr " + cachePath(), "unknown subcommand 'rendr'; did you mean 'render'?"},
        {"xyzzy", "unknown subcommand 'xyzzy'; the subcommands are "},
        {"bench " + cachePath() + " --mode tsunami", "--mode"},
        {"bench " + cachePath() + " --mode ripple --angles 0 30 --weights 1", "--weights"},
        {"bench " + cachePath() + " --mode whirlpool --spiral-b 25",
         "--spiral-b must be in (0, 2] per radian, got 25"},
        {"bench " + cachePath() + " --no-such-option", "no-such-option"},
        {"bench", "CACHE"},
        {"bench " + (s_dir / "missing.swell").string(), "missing.swell"},
        {"bench " + cachePath() + " --res 64by64", "--res"},
        {"bench " + cachePath() + " -F 1.5", "-F/--fluctuation must be in [0, 1]"},
        {"heights " + cachePath() + " --out " + (s_dir / "x").string() + " --policy bounce",
         "policy"},
        {"bench " + cachePath() + " --memory-budget 0", "--memory-budget"},
        {"bench " + cachePath() + " --memory-budget 1e-6", "above the memory budget"},
        // Sizes refused before any work: frames, and what they would take on the disk.
        {"heights " + cachePath() + " --out " + (s_dir / "x").string() +
             " --seconds 1e6 --fps 1000 --res 8x8",
         "--seconds 1000000 x --fps 1000 asks for 1000000000 output frames; at most 1000000"},
        {"heights " + cachePath() + " --out " + (s_dir / "x").string() +
             " --seconds 33333 --fps 30 --res 8192x8192 --window all",
         "GB free: about "},
    }};
    for (const auto& [args, needle] : cases) {
        const Result r = run(args);
        EXPECT_NE(r.code, 0) << args;
        EXPECT_NE(r.err.find("swell-play: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(fs::exists(s_dir / "x")); // no output folder left by a refused run
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

namespace swell::runtime {
namespace {

/// A cache with the bake's "replay" record: water over x in [0.4, 3.6] m of the 4 m domain,
/// l0 = 1 cm, steady from `steadyStart` s; 400 frames 0.01 s apart (4 s).
fs::path recordedCache(const fs::path& dir, const std::string& name, double steadyStart) {
    cache::Header h = test::syntheticHeader();
    h.metadataJson = nlohmann::json{{"replay",
                                     {{"water_x_min", 0.4},
                                      {"water_x_max", 3.6},
                                      {"still_water_level", test::kSyntheticDepth},
                                      {"particle_spacing", 0.01},
                                      {"steady_start_s", steadyStart},
                                      {"steady_reason", "test record"}}}}
                         .dump();
    const fs::path path = dir / name;
    cache::Writer w(path, h);
    for (const cache::Frame& f : test::syntheticFrames(400, 200, 3))
        w.addFrame(f);
    w.finish();
    return path;
}

TEST_F(PlayApp, HeightsSpanTheWaterAndStartInTheSteadyWindow) {
    const fs::path c = recordedCache(s_dir, "recorded.swell", 1.0);
    const fs::path out = s_dir / "recorded_heights";
    const Result r = run("heights " + c.string() + " --out " + out.string() +
                         " --res 64x16 --time-unit 1 --seconds 0.3 --fps 10 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("note"), std::string::npos) << r.err; // recorded: nothing to say
    const nlohmann::json meta = nlohmann::json::parse(slurp(out / "heights.json"));
    EXPECT_DOUBLE_EQ(meta["x0"].get<double>(), 0.4);
    EXPECT_NEAR(meta["dx"].get<double>(), 3.2 / 64, 1e-12);
    EXPECT_EQ(meta["timeline"]["policy"], "seamless");
    EXPECT_EQ(meta["timeline"]["window"]["first_frame"], 100);
    const auto in = meta["timeline"]["loop"]["in_frame"].get<int>();
    EXPECT_GE(in, 100);
    EXPECT_GT(meta["timeline"]["loop"]["out_frame"].get<int>(), in);
    EXPECT_TRUE(meta["bake_record"]["recorded"].get<bool>());
    EXPECT_EQ(meta["params"]["reconstruction"], "envelope");
}

TEST_F(PlayApp, HeightsAsOpenExrMatchThePng16ExportWithNormalsAndBlenderDisplacement) {
    // The same replay written twice: 16-bit PNG, and float EXR with normals and displacement.
    const fs::path c = recordedCache(s_dir, "exr.swell", 1.0); // still water at 0.5 m
    const fs::path png = s_dir / "exr_png16", exr = s_dir / "exr_float";
    const std::string common = " --res 40x24 --slices 64 --time-unit 1 --seconds 0.2 --fps 20 "
                               "--seed 4 --json";
    ASSERT_EQ(run("heights " + c.string() + " --out " + png.string() + common).code, 0);
    const Result r = run("heights " + c.string() + " --out " + exr.string() + common +
                         " --format exr-float --normals --blender-disp");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["format"], "exr-float");
    const nlohmann::json pngMeta = nlohmann::json::parse(slurp(png / "heights.json"));
    const nlohmann::json meta = nlohmann::json::parse(slurp(exr / "heights.json"));
    const HeightScale scale{pngMeta["scale"]["offset"].get<double>(),
                            pngMeta["scale"]["scale"].get<double>()};
    EXPECT_EQ(meta["height_format"], "exr-float");
    EXPECT_EQ(meta["exr"]["channel"], "Y");
    EXPECT_EQ(meta["scale"]["scale"], 1.0);
    EXPECT_EQ(meta["cells"], nlohmann::json({40, 24}));
    EXPECT_EQ(meta["count"], 4);
    EXPECT_EQ(meta["displacement"]["reference_level_m"], test::kSyntheticDepth);
    EXPECT_NE(meta["displacement"]["reference"].get<std::string>().find("still_water_level"),
              std::string::npos);
    for (int i = 0; i < 4; ++i) {
        const std::string n = std::to_string(i);
        const HeightField p = readHeightPng(png / ("height_0000" + n + ".png"), scale);
        const HeightField e = readHeightExr(exr / ("height_0000" + n + ".exr"));
        ASSERT_EQ(e.cellsX, 40);
        ASSERT_EQ(e.cellsZ, 24);
        // The PNG rounds to its step; the EXR holds the GPU's floats.
        for (std::size_t k = 0; k < e.heights.size(); ++k)
            ASSERT_NEAR(e.heights[k], p.heights[k], 0.5 * scale.scale + 1e-7) << i << ": " << k;
        EXPECT_EQ(meta["frames"][i]["disp"], "disp_000" + std::to_string(i + 1) + ".exr");
        // Blender's displacement: height above the still water in G, nothing in R and B.
        const ExrImage d = readExr(exr / meta["frames"][i]["disp"].get<std::string>());
        for (int m = 0; m < 24; m += 5) {
            for (int x = 0; x < 40; x += 7) {
                EXPECT_NEAR(d.at(x, m, d.channel("G")), e.at(x, m) - test::kSyntheticDepth, 1e-6);
                EXPECT_EQ(d.at(x, m, d.channel("R")), 0.0f);
                EXPECT_EQ(d.at(x, m, d.channel("B")), 0.0f);
            }
        }
    }
    EXPECT_FALSE(fs::exists(exr / "disp_0000.exr"));
    EXPECT_FALSE(fs::exists(exr / "disp_0005.exr"));
    // The normals are those of the written heights on the recorded grid.
    const HeightField e = readHeightExr(exr / "height_00003.exr");
    const std::vector<double> want =
        surfaceNormals(e, meta["dx"].get<double>(), meta["dz"].get<double>());
    const ExrImage normals = readExr(exr / meta["frames"][3]["normals"].get<std::string>());
    for (std::size_t k = 0; k < want.size(); ++k) {
        const int cell = static_cast<int>(k / 3);
        const char* channel = k % 3 == 0 ? "R" : k % 3 == 1 ? "G" : "B";
        ASSERT_NEAR(normals.at(cell % 40, cell / 40, normals.channel(channel)), want[k], 1e-6);
    }
    for (const auto& file : fs::directory_iterator(exr))
        EXPECT_EQ(file.path().string().find(".tmp-"), std::string::npos) << file.path();
}

TEST_F(PlayApp, HeightsFormatErrorsNameTheOptionOrTheFileAndExitNonZero) {
    // A bad --format lists the valid ones and writes nothing.
    const fs::path none = s_dir / "bad_format";
    Result r = run("heights " + cachePath() + " --out " + none.string() +
                   " --res 16x16 --slices 8 --seconds 0.05 --format exr");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("swell-play: --format takes png16, exr-half or exr-float; got 'exr'"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(none));
    // A file that cannot be written (a folder stands in its place) is named.
    const fs::path blocked = s_dir / "blocked";
    fs::create_directories(blocked / "height_00000.exr");
    r = run("heights " + cachePath() + " --out " + blocked.string() +
            " --res 16x16 --slices 8 --seconds 0.05 --format exr-half");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("swell-play: cannot write " + (blocked / "height_00000.exr").string()),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(blocked / "heights.json"));
}

TEST_F(PlayApp, AutoResolutionIsOneCellPerParticleSpacing) {
    const fs::path c = recordedCache(s_dir, "auto.swell", 0.0);
    const Result r = run("bench " + c.string() +
                         " --frames 3 --warmup 0 --error-frames 1 --cpu-frames 0 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["res"], nlohmann::json({320, 320})); // 3.2 m / 1 cm
}

TEST_F(PlayApp, ASteadyWindowShorterThanTheSliceSpreadIsOneClearLine) {
    // Steady from 2 s of a 4 s bake: 2 s of steady flow, less than the paper preset's
    // 2 F x time unit = 2.4 s.
    const fs::path c = recordedCache(s_dir, "short.swell", 2.0);
    const Result r = run("bench " + c.string() + " --res 32x8 --frames 3 --preset paper");
    EXPECT_EQ(r.code, 2); // parameters the cache cannot serve: a bad value
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("short.swell"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("shorter than the slice spread"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bake at least 0.40 s longer"), std::string::npos) << r.err;
    // Every frame on request, a smaller F, or the swell preset's F is fine.
    EXPECT_EQ(
        run("bench " + c.string() + " --res 32x8 --frames 3 --preset paper --window all").code, 0);
    EXPECT_EQ(run("bench " + c.string() + " --res 32x8 --frames 3 --preset paper -F 0.1").code, 0);
    EXPECT_EQ(run("bench " + c.string() + " --res 32x8 --frames 3").code, 0);
}

TEST_F(PlayApp, OldCachesFallBackToTheDomainWithANoteAfterTheRun) {
    const Result r = run("bench " + cachePath() + " --res 32x8 --frames 3 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("note: " + cachePath() + ": the cache records no water extent"),
              std::string::npos)
        << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["grid_x"]["x0"], 0.0);
    EXPECT_EQ(j["grid_x"]["x1"], 4.0);
    EXPECT_EQ(j["res"], nlohmann::json({32, 8}));
}

TEST_F(PlayApp, FidelityReportsTheErrorAgainstTheSimulatedSurface) {
    const fs::path c = recordedCache(s_dir, "fidelity.swell", 0.0);
    const Result r = run("fidelity " + c.string() +
                         " --res 128x8 --time-unit 1 --frames 20 --mix-times 2 --seam-seconds 0.5"
                         " --fps 20 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["f0"]["rows"], 20);
    // The synthetic wave (amplitude 6 cm + 2.5 cm, 4 mm particle noise) at 2.5 cm cells:
    // a few millimetres, far below the wave.
    EXPECT_LT(j["f0"]["rms_m"].get<double>(), 0.005);
    EXPECT_GT(j["f0"]["rms_m"].get<double>(), 0.0);
    EXPECT_GT(j["mixing"]["rows"].get<int>(), 0);
    EXPECT_EQ(j["continuity"]["frames"], 10);
    EXPECT_GT(j["steady_spread_m"].get<double>(), 0.01);
    // Deterministic, to the byte.
    const Result again = run("fidelity " + c.string() +
                             " --res 128x8 --time-unit 1 --frames 20 --mix-times 2"
                             " --seam-seconds 0.5 --fps 20 --json");
    EXPECT_EQ(again.out, r.out);
}

} // namespace
} // namespace swell::runtime

namespace swell::runtime {

TEST_F(PlayApp, PresetsSetTheNoiseAndTimeSamplingDefaults) {
    const std::string common = " --res 32x24 --frames 5 --warmup 1 --error-frames 1 "
                               "--cpu-frames 1 --json";
    Result r = run("bench " + cachePath() + common);
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["preset"], "swell");
    EXPECT_EQ(j["fluctuation"], 0.07);
    EXPECT_EQ(j["beta"], 4.0);
    EXPECT_EQ(j["cutoff"], 4.0);
    EXPECT_EQ(j["time_sampling"], "linear");
    EXPECT_TRUE(j["frames_exact"].get<bool>());
    EXPECT_LE(j["max_abs_error"].get<double>(), 1e-5 * test::kSyntheticDepth);

    r = run("bench " + cachePath() + " --preset paper" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["fluctuation"], 0.3); // Table 4, surging
    EXPECT_EQ(j["beta"], 2.0);
    EXPECT_EQ(j["cutoff"], 128.0);
    EXPECT_EQ(j["time_sampling"], "nearest");

    r = run("bench " + cachePath() + " --preset paper --time-sampling linear -F 0.2" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["fluctuation"], 0.2); // given options win over the preset
    EXPECT_EQ(j["time_sampling"], "linear");

    // The whirlpool: the swell preset's noise and time sampling and a funnel of half the
    // still-water depth; the paper's flat eye and nearest frame with --preset paper.
    r = run("bench " + cachePath() + " --mode whirlpool" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["fluctuation"], 0.07);
    EXPECT_EQ(j["time_sampling"], "linear");
    EXPECT_GT(j["mode_params"]["whirlpool"]["eye_depth"].get<double>(), 0.0);
    EXPECT_LE(j["max_abs_error"].get<double>(), 1e-5 * test::kSyntheticDepth);
    r = run("bench " + cachePath() + " --mode whirlpool --preset paper" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["fluctuation"], 0.4); // Table 4, whirlpool
    EXPECT_EQ(j["time_sampling"], "nearest");
    EXPECT_EQ(j["mode_params"]["whirlpool"]["eye_depth"].get<double>(), 0.0);

    for (const std::string bad : {"--preset fancy", "--time-sampling cubic",
                                  "--mode whirlpool --eye-depth 1.5", "--eye-depth -0.1"}) {
        r = run("bench " + cachePath() + " " + bad + common);
        EXPECT_NE(r.code, 0) << bad;
        const std::string option = bad.substr(bad.rfind("--"), bad.rfind(' ') - bad.rfind("--"));
        EXPECT_NE(r.err.find(option), std::string::npos) << bad << ": " << r.err;
    }
}

} // namespace swell::runtime

namespace swell::runtime {

TEST_F(PlayApp, LookMeasuresThePictureAgainstItsTargets) {
    const std::string common = " --res 64x64 --seconds 0.5 --json";
    Result r = run("look " + cachePath() + common);
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    const nlohmann::json& m = j["measures"];
    EXPECT_EQ(j["frames"], 15);
    EXPECT_EQ(j["preset"], "swell");
    // The defaults: long crests, no needles, seeds that differ.
    EXPECT_TRUE(m["slope_ratio_mean"]["met"].get<bool>()) << m.dump();
    EXPECT_TRUE(m["slope_ratio_p99"]["met"].get<bool>()) << m.dump();
    EXPECT_TRUE(m["needle_share"]["met"].get<bool>()) << m.dump();
    EXPECT_TRUE(m["seed_difference"]["met"].get<bool>()) << m.dump();
    EXPECT_GT(m["frame_change_ratio"]["value"].get<double>(), 0.0);
    // Table 4's values stripe the same wave: the check says so.
    r = run("look " + cachePath() + " --preset paper" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_FALSE(j["measures"]["slope_ratio_mean"]["met"].get<bool>()) << j.dump();
    EXPECT_GT(j["measures"]["slope_ratio_mean"]["value"].get<double>(), 0.6);

    // The whirlpool at its defaults: no needles, an eye steadier than the bake.
    r = run("look " + cachePath() + " --mode whirlpool" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["measures"]["needle_share"]["met"].get<bool>()) << j.dump();
    EXPECT_TRUE(j["measures"]["eye_step_ratio"]["met"].get<bool>()) << j.dump();
    EXPECT_FALSE(j["measures"].contains("slope_ratio_mean"));

    // The ripple: a crease ratio per end of the rotated direction's field inside the mesh.
    r = run("look " + cachePath() + " --mode ripple --angles 0 30" + common);
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["measures"].contains("crease_ratio_0")) << j.dump();
    for (const auto& [name, v] : j["measures"].items()) {
        if (name.rfind("crease_ratio_", 0) == 0) {
            EXPECT_TRUE(v["met"].get<bool>()) << name << ": " << v.dump();
        }
    }

    // The same inputs give the same report; bad values are one clear line.
    EXPECT_EQ(run("look " + cachePath() + common).out, run("look " + cachePath() + common).out);
    r = run("look " + cachePath() + " --seconds 0");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("--seconds"), std::string::npos) << r.err;
}

} // namespace swell::runtime
