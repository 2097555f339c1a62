// swell-mps-bench: per-step time of the MPS solver by phase at the paper's surging-wave size
// (~8,400 water + ~1,660 fixed particles), for docs/BENCHMARKS.md. Not a test.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "exit_codes.h"
#include "mps_bench_cli.h"

#include "swell/bake/error.h"
#include "swell/bake/scene.h"

using namespace swell::bake;
using nlohmann::json;

int main(int argc, char** argv) {
    MpsBenchCommandLine cl;
    if (const auto rc = parseMpsBenchCommandLine(argc, argv, cl, std::cout, std::cerr))
        return *rc;
    if (cl.threads > 0)
        omp_set_num_threads(cl.threads);
    const int warmup = cl.warmup;
    const int steps = cl.steps;
    try {
        const Scene scene = mpsBenchScene(cl);
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
        if (cl.asJson) {
            std::printf("%s\n", out.dump().c_str());
        } else {
            std::printf("%s\n", out.dump(2).c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "swell-mps-bench: %s\n", e.what());
        return swell::cli::exitCodeFor(e);
    }
}
