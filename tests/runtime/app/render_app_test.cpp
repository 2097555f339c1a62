// End to end: `swell-play render` on a small cache written with swell::cache::Writer (small
// frames, so the whole file runs in a few seconds on llvmpipe).
#include "swell/cache/writer.h"
#include "swell/runtime/io/exporters.h"
#include "swell/runtime/io/height_exr.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/io/image_io.h"

#include "app_runner.h"
#include "synthetic_frames.h"
#include "temp_dir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
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

class RenderApp : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_temp = std::make_unique<swell::test::TempDir>("swell_render_test_");
        s_dir = s_temp->path();
        cache::Writer w(s_dir / "wave.swell", test::syntheticHeader());
        for (const cache::Frame& f : test::syntheticFrames(400, 200, 3))
            w.addFrame(f);
        w.finish();
        cache::Writer calm(s_dir / "calm.swell", test::syntheticHeader());
        for (cache::Frame f : test::syntheticFrames(100, 200, 4)) {
            f.splash.clear();
            calm.addFrame(f);
        }
        calm.finish();
    }
    static void TearDownTestSuite() { s_temp.reset(); }

    static Result run(const std::string& args, const std::string& env = "") {
        return swell::test::runApp(SWELL_PLAY_EXE, args, env, s_dir);
    }
    static std::string cache(const char* name = "wave.swell") { return (s_dir / name).string(); }
    static inline std::unique_ptr<swell::test::TempDir> s_temp;
    static inline fs::path s_dir;
};

constexpr const char* kSmall = " --res 48x32 --slices 16 --size 160x90 --seconds 0.2 --fps 20";

TEST_F(RenderApp, WritesFramesContactSheetSidecarAndExports) {
    const fs::path out = s_dir / "r";
    const Result r = run("render " + cache() + " --out " + out.string() + kSmall +
                         " --seed 9 --export heights,mesh,splashes --splash-count 2 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    for (int i = 0; i < 4; ++i) {
        const Image im = readPng(out / ("frame_0000" + std::to_string(i) + ".png"));
        EXPECT_EQ(im.width, 160);
        EXPECT_EQ(im.height, 90);
        EXPECT_GT(imageStats(im).stddevLuma, 5.0) << "frame " << i << " is flat";
    }
    EXPECT_FALSE(fs::exists(out / "frame_00004.png"));
    const Image sheet = readPng(out / "contact_sheet.png");
    EXPECT_GT(sheet.width, 160 / 1 * 2); // several tiles
    const nlohmann::json meta = nlohmann::json::parse(slurp(out / "render.json"));
    EXPECT_EQ(meta["seed"], 9);
    EXPECT_EQ(meta["count"], 4);
    EXPECT_EQ(meta["size"], nlohmann::json({160, 90}));
    EXPECT_EQ(meta["res"], nlohmann::json({48, 32}));
    EXPECT_TRUE(meta["splash"]["active"].get<bool>());
    EXPECT_EQ(meta["splash"]["artificial_per_real"], 2);
    EXPECT_TRUE(meta.contains("camera"));
    EXPECT_GT(meta["shaded_fps"].get<double>(), 0.0);
    EXPECT_EQ(meta["frames"].size(), 4u);
    // Exports: height map readable with the recorded scale, a 48 x 32 surface mesh, splashes.
    const HeightScale scale{meta["height_scale"]["offset"].get<double>(),
                            meta["height_scale"]["scale"].get<double>()};
    const nlohmann::json heightsMeta =
        nlohmann::json::parse(slurp(out / "heights" / "heights.json"));
    EXPECT_EQ(heightsMeta["scale"]["offset"].get<double>(), scale.offset);
    EXPECT_EQ(heightsMeta["frames"][2]["file"], "height_00002.png");
    EXPECT_EQ(heightsMeta["seed"], 9);
    const HeightField h = readHeightPng(out / "heights" / "height_00002.png", scale);
    EXPECT_EQ(h.cellsX, 48);
    EXPECT_EQ(h.cellsZ, 32);
    for (double v : h.heights) {
        EXPECT_GT(v, 0.3);
        EXPECT_LT(v, 0.7);
    }
    const PlyData mesh = readPly(out / "mesh" / "surface_00002.ply");
    EXPECT_EQ(mesh.vertices.size(), 48u * 32u * 3u);
    EXPECT_EQ(mesh.triangles.size(), 47u * 31u * 6u);
    // The mesh and the height map are the same surface (within the PNG's quantisation).
    for (std::size_t i = 0; i < h.heights.size(); ++i) {
        EXPECT_NEAR(mesh.vertices[3 * i + 1], h.heights[i], scale.scale);
    }
    const PlyData splashes = readPly(out / "splashes" / "splashes_00001.ply");
    // 16 real slices x 3 splash particles x (1 + 2), except slices showing the empty frame 5.
    EXPECT_EQ(splashes.vertices.size() % 4, 0u);
    EXPECT_GT(splashes.vertices.size() / 4, 100u);
    EXPECT_LE(splashes.vertices.size() / 4, 16u * 3u * 3u);
    EXPECT_EQ(meta["frames"][1]["splash_sprites"].get<std::size_t>(), splashes.vertices.size() / 4);
}

TEST_F(RenderApp, ExportsHalfExrHeightsNormalsAndBlenderDisplacementIntoHeights) {
    // normals and blender-disp bring the height maps along, in the --heights-format.
    const fs::path out = s_dir / "exr";
    const Result r = run("render " + cache() + " --out " + out.string() + kSmall +
                         " --no-splashes --export mesh,normals,blender-disp --heights-format "
                         "exr-half --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json meta = nlohmann::json::parse(slurp(out / "render.json"));
    EXPECT_TRUE(meta["exports"]["heights"].get<bool>());
    EXPECT_EQ(meta["exports"]["heights_format"], "exr-half");
    EXPECT_TRUE(meta["exports"]["blender_disp"].get<bool>());
    EXPECT_EQ(meta["height_scale"]["scale"], 1.0);
    EXPECT_EQ(meta["frames"][1]["heights"], "heights/height_00001.exr");
    EXPECT_EQ(meta["frames"][1]["normals"], "heights/normal_00001.exr");
    EXPECT_EQ(meta["frames"][1]["disp"], "heights/disp_0002.exr");
    const nlohmann::json heightsMeta =
        nlohmann::json::parse(slurp(out / "heights" / "heights.json"));
    EXPECT_EQ(heightsMeta["height_format"], "exr-half");
    EXPECT_EQ(heightsMeta["frames"][1]["disp"], "disp_0002.exr");
    EXPECT_EQ(heightsMeta["displacement"]["reference_level_m"], 0.0); // no record: y = 0
    const ExrImage image = readExr(out / "heights" / "height_00001.exr");
    EXPECT_EQ(image.types, std::vector<std::string>{"half"});
    // The same surface as the mesh, within half precision (2^-11 relative).
    const HeightField h = readHeightExr(out / "heights" / "height_00001.exr");
    const PlyData mesh = readPly(out / "mesh" / "surface_00001.ply");
    ASSERT_EQ(mesh.vertices.size(), h.heights.size() * 3);
    for (std::size_t i = 0; i < h.heights.size(); ++i)
        EXPECT_NEAR(mesh.vertices[3 * i + 1], h.heights[i], h.heights[i] / 2048.0 + 1e-7);
    EXPECT_TRUE(fs::exists(out / "heights" / "disp_0004.exr"));
    EXPECT_TRUE(fs::exists(out / "heights" / "normal_00003.exr"));
}

TEST_F(RenderApp, SameSeedSameFramesOtherSeedOtherFrames) {
    const std::string args = kSmall + std::string(" --json --splash-count 3");
    ASSERT_EQ(
        run("render " + cache() + " --out " + (s_dir / "s1").string() + " --seed 4" + args).code,
        0);
    ASSERT_EQ(
        run("render " + cache() + " --out " + (s_dir / "s2").string() + " --seed 4" + args).code,
        0);
    ASSERT_EQ(
        run("render " + cache() + " --out " + (s_dir / "s3").string() + " --seed 5" + args).code,
        0);
    const Image a = readPng(s_dir / "s1" / "frame_00003.png");
    EXPECT_EQ(a.rgb, readPng(s_dir / "s2" / "frame_00003.png").rgb);
    EXPECT_LT(compareImages(a, readPng(s_dir / "s3" / "frame_00003.png")).psnr, 45.0);
}

TEST_F(RenderApp, RippleAndWhirlpoolDrawSplashesAndTheWhirlpoolIsSeenFromHigher) {
    double eyeHeight[3] = {0.0, 0.0, 0.0};
    std::size_t sprites[3] = {0, 0, 0};
    const char* modes[3] = {"surging", "ripple", "whirlpool"};
    for (int k = 0; k < 3; ++k) {
        const fs::path out = s_dir / (std::string("mode_") + modes[k]);
        // A square mesh: the whirlpool's spirals (inner radius 15 cells) need the room.
        const Result r =
            run("render " + cache() + " --out " + out.string() + " --mode " + modes[k] +
                " --res 64x64 --slices 16 --size 160x90 --seconds 0.2 --fps 20 --json"
                // The whirlpool draws splashes only when asked.
                + (k == 2 ? std::string(" --splashes on") : std::string()) +
                // The first frames: their splashes lie where the whirlpool's spirals reach.
                " --policy loop");
        ASSERT_EQ(r.code, 0) << modes[k] << ": " << r.err;
        const nlohmann::json meta = nlohmann::json::parse(slurp(out / "render.json"));
        EXPECT_TRUE(meta["splash"]["active"].get<bool>()) << modes[k];
        for (const auto& f : meta["frames"])
            sprites[k] += f["splash_sprites"].get<std::size_t>();
        eyeHeight[k] =
            meta["camera"]["position"][1].get<double>() - meta["camera"]["target"][1].get<double>();
    }
    for (int k = 0; k < 3; ++k)
        EXPECT_GT(sprites[k], 0u) << modes[k];
    // Two ripple directions: about twice the surging's sprites (less those past the mesh).
    EXPECT_GT(sprites[1], sprites[0]);
    // 55 degrees above the horizon instead of 28 (relative to the distance: the height over
    // the target grows more than the framing distance changes).
    EXPECT_GT(eyeHeight[2], eyeHeight[0]);
}

TEST_F(RenderApp, TheWhirlpoolDrawsNoSplashRingUnlessAsked) {
    const fs::path out = s_dir / "whirlpool_default";
    const Result r = run("render " + cache() + " --out " + out.string() +
                         " --mode whirlpool --res 64x64 --slices 16 --size 160x90 --seconds 0.1"
                         " --fps 20 --policy loop");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json meta = nlohmann::json::parse(slurp(out / "render.json"));
    EXPECT_FALSE(meta["splash"]["active"].get<bool>());
    for (const auto& f : meta["frames"])
        EXPECT_EQ(f["splash_sprites"].get<std::size_t>(), 0u);
    const Result bad = run("render " + cache() + " --out " + out.string() + " --splashes maybe");
    EXPECT_NE(bad.code, 0);
    EXPECT_NE(bad.err.find("--splashes"), std::string::npos) << bad.err;
}

TEST_F(RenderApp, ACacheWithoutSplashRunsNoSplashPass) {
    const fs::path out = s_dir / "calm";
    const Result r =
        run("render " + cache("calm.swell") + " --out " + out.string() + kSmall + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json meta = nlohmann::json::parse(slurp(out / "render.json"));
    EXPECT_FALSE(meta["splash"]["active"].get<bool>());
    EXPECT_EQ(meta["stage_gpu_ms"]["splashes"].get<double>(), 0.0);
    for (const auto& f : meta["frames"])
        EXPECT_EQ(f["splash_sprites"], 0);
}

TEST_F(RenderApp, VideoWithoutFfmpegWritesPngsAndSaysSo) {
    const fs::path out = s_dir / "v";
    // PATH without ffmpeg: the frames are written, one clear line says why there is no video.
    const Result r = run("render " + cache() + " --out " + out.string() + kSmall + " --video " +
                             (out / "clip.mp4").string(),
                         "PATH=/nonexistent");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("ffmpeg not found"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out / "frame_00003.png"));
    EXPECT_FALSE(fs::exists(out / "clip.mp4"));
    EXPECT_EQ(nlohmann::json::parse(slurp(out / "render.json"))["video_status"],
              "skipped: ffmpeg not found");
}

TEST_F(RenderApp, AFailingFfmpegFailsTheRenderAndLeavesEveryPreviousOutput) {
    const fs::path out = s_dir / "vfail";
    const fs::path clip = out / "clip.mp4";
    ASSERT_EQ(
        run("render " + cache() + " --out " + out.string() + kSmall, "PATH=/nonexistent").code, 0);
    { std::ofstream(clip, std::ios::binary) << "the previous video"; }
    std::map<std::string, std::string> before;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        if (e.is_regular_file())
            before[e.path().string()] = slurp(e.path());
    }
    const fs::path bin = s_dir / "fake_ffmpeg";
    fs::create_directories(bin);
    {
        std::ofstream f(bin / "ffmpeg");
        f << "#!/bin/sh\necho 'No space left on device' >&2\nexit 1\n";
    }
    fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
    const Result r = run("render " + cache() + " --out " + out.string() + kSmall +
                             " --seed 7 --video " + clip.string(),
                         "PATH=" + bin.string());
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("--video " + clip.string() + ": ffmpeg failed (exit 1)"),
              std::string::npos)
        << r.err;
    std::map<std::string, std::string> after;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        if (e.is_regular_file())
            after[e.path().string()] = slurp(e.path());
    }
    EXPECT_EQ(after.size(), before.size()) << "files left behind or removed";
    EXPECT_TRUE(after == before) << "a previous output changed";
}

TEST_F(RenderApp, AShorterRenderReplacesTheFolderWithoutTheOldFrames) {
    const fs::path out = s_dir / "shorter";
    const std::string common = " --res 48x32 --slices 16 --size 160x90 --fps 20";
    ASSERT_EQ(run("render " + cache() + " --out " + out.string() + common + " --seconds 0.5").code,
              0);
    ASSERT_TRUE(fs::exists(out / "frame_00009.png"));
    const Result r = run("render " + cache() + " --out " + out.string() + common +
                         " --seconds 0.2 --export heights");
    ASSERT_EQ(r.code, 0) << r.err;
    std::size_t frames = 0;
    for (const auto& e : fs::directory_iterator(out))
        frames += e.path().filename().string().rfind("frame_", 0) == 0;
    const auto meta = nlohmann::json::parse(slurp(out / "render.json"));
    EXPECT_EQ(frames, meta["frames"].size());
    EXPECT_EQ(frames, 4u);
    EXPECT_FALSE(fs::exists(out / "frame_00004.png"));
}

TEST_F(RenderApp, VideoThroughFfmpegWhenInstalled) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "ffmpeg is not installed";
    const fs::path out = s_dir / "mp4";
    const Result r = run("render " + cache() + " --out " + out.string() + kSmall + " --video " +
                         (out / "clip.mp4").string() + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string mp4 = slurp(out / "clip.mp4");
    ASSERT_GT(mp4.size(), 100u);
    EXPECT_EQ(mp4.substr(4, 4), "ftyp"); // an ISO media file
}

TEST_F(RenderApp, BadInputGivesOneClearLineAndNonZeroExit) {
    // Each case names every option once; a check that failed to fire would render 32 x 32.
    const std::string out = " --out " + (s_dir / "bad").string() + " --res 16x16 --slices 4";
    const std::string rest = " --seconds 0.05 --size 32x32";
    const std::pair<std::string, std::string> cases[] = {
        {"render " + cache() + out + " --seconds 0.05 --size 160by90", "--size"},
        {"render " + cache() + out + " --seconds 0.05 --size 8x8",
         "--size must be within 16..8192 pixels, got 8x8"},
        {"render " + cache() + out + " --seconds 0 --size 32x32", "--seconds"},
        {"render " + cache() + out + " --seconds 1e9 --size 32x32", "at most 1000000 fit"},
        {"render " + cache() + out + rest + " --fov 0", "--fov must be in (0, 180) degrees, got 0"},
        {"render " + cache() + out + rest + " --export heights,pictures", "pictures"},
        {"render " + cache() + out + rest + " --heights-format tiff",
         "png16, exr-half or exr-float"},
        {"render " + cache() + out + rest + " --splash-count -2",
         "--splash-count must be in [0, 1000], got -2"},
        {"render " + cache() + out + rest + " --video clip.avi", ".mp4"},
        {"render " + cache() + out + rest + " --camera 1 2 3", "--target"},
        {"render " + cache() + out + rest + " --camera 1 2 3 --target 1 2 3",
         "--camera/--target coincide"},
        {"render " + cache() + out + rest + " --sky " + (s_dir / "nosky").string(), "px.png"},
        {"render " + (s_dir / "missing.swell").string() + out + rest, "missing.swell"},
        {"render " + cache() + rest, "--out"},
    };
    for (const auto& [args, needle] : cases) {
        const Result r = run(args);
        EXPECT_NE(r.code, 0) << args;
        EXPECT_NE(r.err.find("swell-play: "), std::string::npos) << args << ": " << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        // A failed render leaves no output folder it made (some cases fail after making it).
        EXPECT_FALSE(fs::exists(s_dir / "bad")) << args;
    }
}

} // namespace
} // namespace swell::runtime
