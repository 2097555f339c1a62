// libFuzzer target for swell-bake's command line (bake/app/bake_cli.h): the input's lines are
// the arguments after the program name. Tokens that start with '@' name a fixed set of files in
// a temporary folder: @scene (a small valid scene), @bad (not JSON), @empty, @dir (a folder),
// @missing (no such file) and @out (where an output would go). Every argument vector must be
// parsed and its scene (with the --set overrides) loaded and checked as a bake would before its
// first step, or be refused with one clear line and a non-zero status: "swell-bake: ... (see
// --help)" for an option, one SceneError line for the scene. Nothing is written: @out and the
// scene files are unchanged afterwards. The bake itself never runs.
#include "fuzz_check.h"

#include "bake_cli.h"
#include "swell/bake/error.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

/// The fixture files, made once per process; '@' tokens map to their paths.
const std::map<std::string, std::string>& fixtures() {
    static const std::map<std::string, std::string> files = [] {
        const fs::path dir =
            fs::temp_directory_path() / ("swell-options-fuzz-" + std::to_string(::getpid()));
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
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"swell-bake"};
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
    if (size == 0)
        args.pop_back(); // no argument at all
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());

    BakeCommandLine cl;
    std::ostringstream out, err;
    const auto rc = parseBakeCommandLine(static_cast<int>(argv.size()), argv.data(), cl, out, err);
    if (rc) {
        if (*rc == 0) {
            swell::fuzz::require(err.str().empty() && !out.str().empty(), "--help printed nothing");
        } else {
            const std::string e = err.str();
            swell::fuzz::require(*rc == 2, "a bad option exits with a status other than 2", e);
            swell::fuzz::require(!e.empty() && e.back() == '\n', "no error line", e);
            swell::fuzz::requireClearError(e.substr(0, e.size() - 1), "swell-bake: ");
            swell::fuzz::require(out.str().empty(), "a refused command line printed on stdout");
        }
        checkUnchanged();
        return 0;
    }
    swell::fuzz::require(out.str().empty() && err.str().empty(), "parsing printed something");
    swell::fuzz::require(!cl.scenePath.empty() && !cl.output.empty(), "SCENE or -o accepted empty");
    try {
        (void)loadBakeScene(cl);
    } catch (const SceneError& e) {
        swell::fuzz::requireClearError(e.what(), "scene key '");
    }
    checkUnchanged();
    return 0;
}
