// swell-mps-bench: per-step time of the MPS solver by phase at the paper's surging-wave size
// (~8,400 water + ~1,660 fixed particles), for docs/BENCHMARKS.md. Not a test.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "swell/bake/error.h"
#include "swell/bake/scene.h"

using namespace swell::bake;
using nlohmann::json;

int main(int argc, char** argv) {
    CLI::App app{
        "swell-mps-bench: MPS step time by phase, ~10,000 particles (dam break in a 2 m tank)"};
    int threads = 0;
    int warmup = 100;
    int steps = 400;
    std::vector<std::string> sets;
    bool asJson = false;
    app.add_option("--threads", threads, "OpenMP threads (default: all)");
    app.add_option("--warmup", warmup, "steps run before timing");
    app.add_option("--steps", steps, "timed steps");
    app.add_option("--set", sets, "override a key of the built-in scene: section.key=value")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_flag("--json", asJson, "print one JSON object on stdout");
    CLI11_PARSE(app, argc, argv);
    if (threads > 0)
        omp_set_num_threads(threads);

    // A 2.0 m x 1.04 m tank (l0 = 0.01 m, 2 wall + 2 dummy layers: 1,664 fixed particles) with
    // a 1.0 m x 0.84 m water column (8,400 particles) that collapses: a breaking surge like the
    // paper's surging wave (8,376 water + 1,662 fixed, Table 2).
    json j = {{"name", "bench_10k"},
              {"geometry",
               {{"particle_spacing", 0.01},
                {"tank", {{"x0", 0.0}, {"y0", 0.0}, {"x1", 2.0}, {"y1", 1.04}}},
                {"water", json::array({{{"x0", 0.0}, {"y0", 0.0}, {"x1", 1.0}, {"y1", 0.84}}})}}},
              {"solver", {{"dt", 0.0005}}}};
    try {
        for (const auto& s : sets)
            applyOverride(j, s);
        const Scene scene = parseScene(j);
        MpsSolver solver = makeSolver(scene);
        const auto& P = solver.particles();
        const std::size_t n = P.size();
        for (int k = 0; k < warmup; ++k)
            solver.step();
        std::array<double, kPhaseCount> phase{};
        double iterations = 0.0;
        int maxIterations = 0;
        double maxResidual = 0.0;
        int rebuilds = 0;
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpuStart = std::clock();
        for (int k = 0; k < steps; ++k) {
            const StepStats& s = solver.step();
            for (std::size_t p = 0; p < kPhaseCount; ++p)
                phase[p] += s.phaseSeconds[p];
            iterations += s.ppeIterations;
            maxIterations = std::max(maxIterations, s.ppeIterations);
            maxResidual = std::max(maxResidual, s.ppeResidual);
            rebuilds += s.neighborRebuilds;
        }
        const double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpu = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
        const double perStep = wall / steps;
        json out{{"threads", omp_get_max_threads()},
                 {"particles", n},
                 {"water", P.count(ParticleKind::Water)},
                 {"fixed", n - P.count(ParticleKind::Water)},
                 {"warmup_steps", warmup},
                 {"steps", steps},
                 {"simulated_time_end", solver.time()},
                 {"ms_per_step", perStep * 1e3},
                 {"us_per_particle_step", perStep * 1e6 / static_cast<double>(n)},
                 // Process CPU time (all threads): with 1 thread it is the step time without
                 // the waits for a core that a shared machine adds to the wall time.
                 {"cpu_ms_per_step", cpu / steps * 1e3},
                 {"ppe_iterations_mean", iterations / steps},
                 {"ppe_iterations_max", maxIterations},
                 {"ppe_residual_max", maxResidual},
                 {"ppe_tolerance", scene.solver.pressure.tolerance},
                 {"preconditioner", std::string(toString(scene.solver.pressure.preconditioner))},
                 {"neighbor_rebuilds_per_step", static_cast<double>(rebuilds) / steps}};
        json ph = json::object();
        for (std::size_t p = 0; p < kPhaseCount; ++p) {
            ph[std::string(toString(static_cast<Phase>(p)))] = phase[p] / steps * 1e3;
        }
        out["phase_ms_per_step"] = ph;
        if (asJson) {
            std::printf("%s\n", out.dump().c_str());
        } else {
            std::printf("%s\n", out.dump(2).c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "swell-mps-bench: %s\n", e.what());
        return 1;
    }
}
