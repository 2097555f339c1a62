#include "mps_bench_cli.h"

#include "command_line.h"

#include <nlohmann/json.hpp>

namespace swell::bake {

std::optional<int> parseMpsBenchCommandLine(int argc, const char* const* argv,
                                            MpsBenchCommandLine& cl, std::ostream& out,
                                            std::ostream& err) {
    CLI::App app{
        "swell-mps-bench: MPS step time by phase, ~10,000 particles (dam break in a 2 m tank)"};
    app.add_option("--threads", cl.threads, "OpenMP threads (default: all)")
        ->check(CLI::Range(1, 1024));
    app.add_option("--warmup", cl.warmup, "steps run before timing")
        ->check(CLI::Range(0, 10000000));
    app.add_option("--steps", cl.steps, "timed steps")->check(CLI::Range(1, 10000000));
    app.add_option("--set", cl.sets, "override a key of the built-in scene: section.key=value")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_flag("--json", cl.asJson, "print one JSON object on stdout");
    return cli::parse(app, argc, argv, "swell-mps-bench", out, err);
}

Scene mpsBenchScene(const MpsBenchCommandLine& cl) {
    using nlohmann::json;
    // A 2.0 m x 1.04 m tank (l0 = 0.01 m, 2 wall + 2 dummy layers: 1,664 fixed particles) with
    // a 1.0 m x 0.84 m water column (8,400 particles) that collapses: a breaking surge like the
    // paper's surging wave (8,376 water + 1,662 fixed, Table 2).
    json j = {{"name", "bench_10k"},
              {"geometry",
               {{"particle_spacing", 0.01},
                {"tank", {{"x0", 0.0}, {"y0", 0.0}, {"x1", 2.0}, {"y1", 1.04}}},
                {"water", json::array({{{"x0", 0.0}, {"y0", 0.0}, {"x1", 1.0}, {"y1", 0.84}}})}}},
              {"solver", {{"dt", 0.0005}}}};
    for (const auto& s : cl.sets)
        applyOverride(j, s);
    return parseScene(j);
}

} // namespace swell::bake
