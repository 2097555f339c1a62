#include "bake_cli.h"

#include <CLI/CLI.hpp>

#include "swell/bake/bake_driver.h"

namespace swell::bake {
namespace {

/// CLI11's message with control characters (an argument may hold any) escaped: one line.
std::string oneLine(const std::string& message) {
    std::string out;
    for (const char c : message) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
            static constexpr char kHex[] = "0123456789abcdef";
            out += "\\x";
            out += kHex[(static_cast<unsigned char>(c) >> 4) & 0xf];
            out += kHex[static_cast<unsigned char>(c) & 0xf];
        } else {
            out += c;
        }
    }
    return out;
}

} // namespace

std::optional<int> parseBakeCommandLine(int argc, const char* const* argv, BakeCommandLine& cl,
                                        std::ostream& out, std::ostream& err) {
    CLI::App app{"swell-bake: run a scene's 2D MPS simulation and write the surface/splash cache"};
    app.add_option("SCENE", cl.scenePath, "scene file (JSON, docs/scenes.md)")->required();
    app.add_option("-o,--output", cl.output,
                   "cache file to write (.swell); appears only when the bake completes")
        ->required();
    app.add_option("--set", cl.sets,
                   "override a scene key before validation: section.key=value (repeatable)");
    app.add_option("--threads", cl.threads, "OpenMP threads (default: OpenMP's choice)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--probes", cl.probes, "write a CSV time,front_x,gauge_<x>... per stored frame");
    app.add_option("--checkpoint-every", cl.checkpointEvery,
                   "write a checkpoint CACHE.ckpt every N steps (and on SIGINT/SIGTERM); removed "
                   "when the bake "
                   "completes")
        ->check(CLI::Range(1L, 1000000000L));
    app.add_flag("--resume", cl.resume,
                 "continue from CACHE.ckpt; the cache is byte-identical to an uninterrupted bake "
                 "(same scene, "
                 "--set, --threads and build)");
    app.add_flag("--json", cl.asJson, "print the summary as one JSON object on stdout");
    app.add_flag("-q,--quiet", cl.quiet, "no progress lines");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0)
            return app.exit(e, out, err);
        err << "swell-bake: " << oneLine(e.what()) << " (see --help)\n";
        return 2;
    }
    for (const auto& [name, value] :
         {std::pair{"SCENE", &cl.scenePath}, {"--output", &cl.output}}) {
        if (value->empty()) {
            err << "swell-bake: " << name << ": an empty path (see --help)\n";
            return 2;
        }
    }
    return std::nullopt;
}

Scene loadBakeScene(const BakeCommandLine& cl) {
    Scene scene = loadScene(cl.scenePath, cl.sets);
    (void)frameIntervalSteps(scene);
    (void)totalSteps(scene);
    return scene;
}

} // namespace swell::bake
