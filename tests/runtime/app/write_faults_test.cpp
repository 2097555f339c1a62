// A full disk or an I/O error (SWELL_FAULT_INJECT, swell/cache/checked_write.h) at each write
// site of swell-play: heights (16-bit PNG; EXR heights, normals and Blender displacement; the
// heights.json sidecar) and render (frame PNGs, contact sheet, render.json, the heights, mesh
// and splash exports). Every run stops with one stderr line naming the file and the reason
// and a non-zero exit, and leaves the folder of the previous good run byte for byte as it
// was: no new file, no temporary, nothing that looks whole.
#include "swell/cache/writer.h"

#include "app_runner.h"
#include "synthetic_frames.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

using Result = swell::test::AppResult;

/// Every file under `dir` (relative name -> bytes).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (e.is_regular_file())
            files[fs::relative(e.path(), dir).string()] = swell::test::slurp(e.path());
    }
    return files;
}

int lines(const std::string& s) {
    int n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

class WriteFaults : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        s_temp = std::make_unique<swell::test::TempDir>("swell_write_faults_");
        cache::Writer w(s_temp->path() / "wave.swell", test::syntheticHeader());
        for (const cache::Frame& f : test::syntheticFrames(200, 200, 3))
            w.addFrame(f);
        w.finish();
    }
    static void TearDownTestSuite() { s_temp.reset(); }

    /// Runs `args` once to have a previous good folder, then again with another seed (whose
    /// files would all differ) and a fault at each of `sites`, checking what is said above.
    static void check(const std::string& command, const std::string& args,
                      const std::vector<std::string>& sites) {
        const fs::path dir = s_temp->path() / command;
        const std::string base = command + " " + (s_temp->path() / "wave.swell").string() +
                                 " --out " + dir.string() + " " + args;
        const Result good = run(base + " --seed 1", "");
        ASSERT_EQ(good.code, 0) << good.err;
        const auto before = snapshot(dir);
        for (const std::string& site : sites) {
            bool named = false; // the site exists in the good run
            for (const auto& [name, bytes] : before)
                named = named || name.find(site) != std::string::npos;
            EXPECT_TRUE(named) << site << " is not a file of the run";
            // A full disk at the file's first byte, an I/O error after its first 100 bytes.
            for (const auto& [kind, after] : {std::pair{"enospc", "0"}, std::pair{"eio", "100"}}) {
                {
                    SCOPED_TRACE(command + " " + site + " " + kind + " after " + after);
                    const std::string env = std::string("SWELL_FAULT_INJECT=") + kind +
                                            ":after=" + after + ":match=" + site;
                    const Result r = run(base + " --seed 2", env);
                    EXPECT_NE(r.code, 0);
                    EXPECT_EQ(lines(r.err), 1) << r.err;
                    EXPECT_NE(r.err.find(site), std::string::npos) << r.err;
                    EXPECT_NE(r.err.find(std::string(kind) == "eio" ? "Input/output error"
                                                                    : "No space left on device"),
                              std::string::npos)
                        << r.err;
                    const auto now = snapshot(dir);
                    EXPECT_EQ(now.size(), before.size()) << "files were added or removed";
                    for (const auto& [name, bytes] : before) {
                        const auto it = now.find(name);
                        EXPECT_TRUE(it != now.end() && it->second == bytes)
                            << name << " changed or went missing";
                    }
                }
            }
        }
    }
    static Result run(const std::string& args, const std::string& env) {
        return swell::test::runApp(SWELL_PLAY_EXE, args, env, s_temp->path());
    }
    static inline std::unique_ptr<swell::test::TempDir> s_temp;
};

constexpr const char* kSmall = "--res 48x32 --slices 16 --seconds 0.2 --fps 20";

TEST_F(WriteFaults, HeightsPng16) {
    check("heights", std::string(kSmall), {"height_00002.png", "heights.json"});
}

TEST_F(WriteFaults, HeightsExrWithNormalsAndBlenderDisplacement) {
    check("heights", std::string(kSmall) + " --format exr-half --normals --blender-disp",
          {"height_00001.exr", "normal_00003.exr", "disp_0001.exr", "heights.json"});
}

TEST_F(WriteFaults, RenderFramesSheetRecordAndExports) {
    check("render",
          std::string(kSmall) + " --size 160x90 --export heights,mesh,splashes --splash-count 2",
          {"frame_00002.png", "contact_sheet.png", "render.json", "heights/height_00001.png",
           "heights/heights.json", "mesh/surface_00003.ply", "splashes/splashes_00000.ply"});
}

} // namespace
} // namespace swell::runtime
