// libFuzzer target for every program's command line: swell-bake (bake/app/bake_cli.h),
// swell-cache (cache/app/cache_cli.h), swell-validate (bake/validation/app/validate_cli.h),
// swell-mps-bench (bake/app/mps_bench_cli.h) and
// swell-play (runtime/app/play_cli.h). The input's first line names the program, the others are
// its arguments. Tokens that start with '@' name a fixed set of files in a temporary folder:
// @scene (a small valid scene), @bad (not JSON), @empty, @dir (a folder), @missing (no such
// file) and @out (where an output would go). Every argument vector must be parsed and checked
// as the program does before its work (for the scene programs: the scene loaded with the --set
// overrides; for swell-play: the subcommand's option values), or be refused with one clear line
// on stderr and a non-zero status: "PROGRAM: ..." for an option, one SceneError line for a
// scene. --help prints on stdout and exits 0. Nothing is written: the folder is unchanged
// afterwards. No program's work (bake, solver, cache, GPU) ever runs.
#include "fuzz_check.h"

#include "bake_cli.h"
#include "cache_cli.h"
#include "mps_bench_cli.h"
#include "play_cli.h"
#include "validate_cli.h"

#include "swell/bake/error.h"

#include "temp_dir.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace swell::bake;
namespace fs = std::filesystem;

namespace {

constexpr const char* kScene = R"({
  "name": "fuzz_tank",
  "geometry": {
    "particle_spacing": 0.01,
    "tank": { "x0": 0.0, "y0": 0.0, "x1": 0.2, "y1": 0.15 },
    "water": [ { "x0": 0.0, "y0": 0.0, "x1": 0.2, "y1": 0.1 } ]
  },
  "solver": { "dt": 0.001, "end_time": 1.0, "expected_speed": 0.1 },
  "output": { "frame_interval": 0.1 }
})";

/// The fixture files, made once per process in a folder removed when the process exits; '@'
/// tokens map to their paths.
const std::map<std::string, std::string>& fixtures() {
    static const swell::test::TempDir folder("swell-options-fuzz-");
    static const std::map<std::string, std::string> files = [] {
        const fs::path& dir = folder.path();
        fs::create_directories(dir / "dir");
        std::ofstream(dir / "scene.json") << kScene;
        std::ofstream(dir / "bad.json") << "{\"geometry\": ";
        std::ofstream(dir / "empty.json");
        return std::map<std::string, std::string>{
            {"@scene", (dir / "scene.json").string()},     {"@bad", (dir / "bad.json").string()},
            {"@empty", (dir / "empty.json").string()},     {"@dir", (dir / "dir").string()},
            {"@missing", (dir / "missing.json").string()}, {"@out", (dir / "out.swell").string()}};
    }();
    return files;
}

void checkUnchanged() {
    const auto& f = fixtures();
    swell::fuzz::require(!fs::exists(f.at("@out")), "a file was written at @out");
    swell::fuzz::require(!fs::exists(f.at("@missing")), "a file was written at @missing");
    swell::fuzz::require(fs::file_size(f.at("@empty")) == 0, "@empty was written to");
    swell::fuzz::require(fs::is_empty(f.at("@dir")), "a file was written in @dir");
}

/// The outcome of parsing: --help (0, text on stdout) or one error line and a non-zero status.
void checkStop(int rc, const std::string& program, const std::ostringstream& out,
               const std::ostringstream& err) {
    if (rc == 0) {
        swell::fuzz::require(err.str().empty() && !out.str().empty(), "--help printed nothing");
        return;
    }
    const std::string e = err.str();
    swell::fuzz::require(!e.empty() && e.back() == '\n', "a refusal without an error line", e);
    swell::fuzz::requireClearError(e.substr(0, e.size() - 1), program + ": ");
    swell::fuzz::require(out.str().empty(), "a refused command line printed on stdout", e);
}

/// Loads a scene as the program would; refused with one SceneError line or loaded.
template <class Load> void checkScene(Load load) {
    try {
        (void)load();
    } catch (const SceneError& e) {
        swell::fuzz::requireClearError(e.what(), e.key().empty() ? "" : "scene key '");
    }
}

/// Parses (and checks) argv as `program` does; true when the program would go on.
bool parseAs(const std::string& program, int argc, const char* const* argv) {
    std::ostringstream out, err;
    std::optional<int> rc;
    if (program == "swell-bake") {
        BakeCommandLine cl;
        rc = parseBakeCommandLine(argc, argv, cl, out, err);
        if (!rc) {
            swell::fuzz::require(!cl.scenePath.empty() && !cl.output.empty(),
                                 "SCENE or -o accepted empty");
            checkScene([&] { return loadBakeScene(cl); });
        }
    } else if (program == "swell-cache") {
        swell::cache::CacheOptions o;
        swell::cache::CacheCommand command{};
        rc = swell::cache::parseCacheCommandLine(argc, argv, o, command, out, err);
    } else if (program == "swell-validate") {
        ValidateCommandLine cl;
        rc = parseValidateCommandLine(argc, argv, cl, out, err);
        if (!rc)
            checkScene([&] { return loadValidateScene(cl); });
    } else if (program == "swell-mps-bench") {
        MpsBenchCommandLine cl;
        rc = parseMpsBenchCommandLine(argc, argv, cl, out, err);
        if (!rc)
            checkScene([&] { return mpsBenchScene(cl); });
    } else {
        swell::play::PlayCommandLine cl;
        rc = cl.parse(argc, argv, out, err);
    }
    if (rc)
        checkStop(*rc, program, out, err);
    else
        swell::fuzz::require(out.str().empty() && err.str().empty(), "parsing printed something");
    checkUnchanged();
    return !rc;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args;
    std::string token;
    for (std::size_t i = 0; i <= size; ++i) {
        if (i == size || data[i] == '\n') {
            const auto it = fixtures().find(token);
            args.push_back(it != fixtures().end() ? it->second : token);
            token.clear();
        } else {
            token += static_cast<char>(data[i]);
        }
    }
    static const std::set<std::string> programs{"swell-bake", "swell-cache", "swell-validate",
                                                "swell-mps-bench", "swell-play"};
    if (!programs.count(args[0]))
        return 0; // not a command line of ours
    if (args.size() == 2 && args[1].empty())
        args.pop_back(); // "PROGRAM\n": no argument at all
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    (void)parseAs(args[0], static_cast<int>(argv.size()), argv.data());
    return 0;
}
