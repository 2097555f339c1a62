#include "bake_cli.h"

#include "command_line.h"

#include "swell/bake/bake_driver.h"

namespace swell::bake {

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
                 "(same scene and --set; same --threads from 4096 particles; any build of the "
                 "same numerics version)");
    app.add_flag("--json", cl.asJson, "print the summary as one JSON object on stdout");
    app.add_flag("-q,--quiet", cl.quiet, "no progress lines");
    if (const auto rc = cli::parse(app, argc, argv, "swell-bake", out, err))
        return rc;
    for (const auto& [name, value] :
         {std::pair{"SCENE", &cl.scenePath}, {"--output", &cl.output}}) {
        if (value->empty()) {
            err << "swell-bake: " << name << ": an empty path (see --help)\n";
            return cli::kExitBadInput;
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
