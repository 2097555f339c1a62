// swell-bake: runs a scene's 2D MPS simulation and writes the surface/splash cache
// (README.md, "Programs"). Thin: scene loading, the bake loop and the cache are library code;
// this file parses the command line, reports progress and maps errors to exit codes.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "bake_cli.h"
#include "exit_codes.h"
#include "swell/bake/bake_driver.h"
#include "swell/bake/checkpoint.h"
#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/cache/error.h"
#include "swell/cache/output_lock.h"

using namespace swell::bake;
namespace cli = swell::cli;
using nlohmann::json;

namespace {

// Set by SIGINT/SIGTERM; the bake polls it after every step and stops cleanly (the cache
// writer then removes its temporary file). A signal handler can only reach a static.
volatile std::sig_atomic_t g_stop = 0;
extern "C" void onSignal(int) {
    g_stop = 1;
}

std::string clock(double s) {
    if (!(s >= 0.0) || s > 1e7)
        return "--:--";
    const long t = static_cast<long>(s + 0.5);
    return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
                     : fmt::format("{}:{:02}", t / 60, t % 60);
}

/// Progress on stderr: one updating line on a terminal, a line per 10 % otherwise.
class ProgressReporter {
public:
    explicit ProgressReporter(bool quiet) : m_quiet(quiet), m_tty(isatty(STDERR_FILENO) != 0) {}
    void operator()(const BakeProgress& p) {
        if (m_quiet)
            return;
        const bool last = p.step == p.totalSteps;
        if (m_tty) {
            if (!last && p.wallSeconds - m_lastPrint < 0.25)
                return;
        } else {
            const long tenth = std::max(1L, p.totalSteps / 10);
            if (!last && p.step % tenth != 0)
                return;
        }
        m_lastPrint = p.wallSeconds;
        const double rate = p.wallSeconds > 0.0 ? (p.step - p.firstStep) / p.wallSeconds : 0.0;
        const double eta = rate > 0.0 ? (p.totalSteps - p.step) / rate : -1.0;
        const std::string line =
            fmt::format("step {}/{} ({:.0f}%)  t = {:.3f} s  {:.1f} steps/s  frames {}  "
                        "elapsed {}  ETA {}",
                        p.step, p.totalSteps, 100.0 * p.step / p.totalSteps, p.time, rate, p.frames,
                        clock(p.wallSeconds), clock(eta));
        if (m_tty) {
            std::fprintf(stderr, "\r%s\033[K%s", line.c_str(), last ? "\n" : "");
        } else {
            std::fprintf(stderr, "%s\n", line.c_str());
        }
        std::fflush(stderr);
    }
    void endLine() {
        if (m_tty && !m_quiet && m_lastPrint >= 0.0)
            std::fprintf(stderr, "\n");
    }

private:
    bool m_quiet;
    bool m_tty;
    double m_lastPrint = -1.0;
};

/// The one-line summary of a finished bake on stderr.
void printSummary(const Scene& scene, const BakeSummary& s, const std::string& output) {
    std::fprintf(
        stderr,
        "swell-bake: %s: %zu water + %zu fixed particles, %ld steps, %zu frames; kept per frame "
        "%.1f surface + %.1f splash (%.1fx fewer than water); cache %s, %llu bytes (%.2fx); "
        "%.1f s wall, %.2f ms/step%s\n",
        scene.name.c_str(), s.particlesWater, s.particlesWall, s.steps, s.frames, s.surfaceMean,
        s.splashMean, s.reduction, output.c_str(), static_cast<unsigned long long>(s.cacheBytes),
        s.cacheBytes ? static_cast<double>(s.rawBytes) / s.cacheBytes : 0.0, s.wallSeconds,
        s.msPerStep,
        scene.recycling
            ? fmt::format("; {} particles recycled outflow -> inflow (count conserved)", s.recycled)
                  .c_str()
            : "");
    if (s.resumedFromStep > 0) {
        std::fprintf(stderr, "swell-bake: resumed from step %ld (checkpoint %s, now removed)\n",
                     s.resumedFromStep, checkpointPath(output).c_str());
    }
}

/// Exit status (exit_codes.h) and stderr line of a failed bake: cancelled, diverged (no cache),
/// bad scene, checkpoint, output in use by another process, cache, anything else.
int reportFailure(const std::exception& e, const std::string& scenePath,
                  ProgressReporter& progress) {
    if (const auto* scene = dynamic_cast<const SceneError*>(&e)) {
        // A key's error gets the file's name; an error of the whole file names it already.
        if (scene->key().empty())
            std::fprintf(stderr, "swell-bake: %s\n", e.what());
        else
            std::fprintf(stderr, "swell-bake: %s: %s\n", scenePath.c_str(), e.what());
        return cli::kExitBadInput;
    }
    progress.endLine();
    int code = cli::exitCodeFor(e);
    const char* suffix = "";
    if (dynamic_cast<const BakeCancelled*>(&e) != nullptr) {
        code = cli::kExitCancelled;
    } else if (dynamic_cast<const DivergenceError*>(&e) != nullptr) {
        code = cli::kExitDiverged;
        suffix = "; no cache written";
    } else if (dynamic_cast<const CheckpointError*>(&e) != nullptr) {
        code = cli::kExitCheckpoint;
    }
    std::fprintf(stderr, "swell-bake: %s%s\n", e.what(), suffix);
    return code;
}

/// The output path's problems a bake would only meet at its end: an existing directory there,
/// or a folder that does not exist. "" when it can be written (as far as can be told now).
std::string outputPathProblem(const std::string& output) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path path(output);
    if (fs::is_directory(path, ec)) {
        return fmt::format("-o {}: is a directory; give the cache's file name, e.g. {}", output,
                           (path / "bake.swell").string());
    }
    const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, ec))
        return fmt::format("-o {}: the folder {} does not exist", output, folder.string());
    return std::string();
}

} // namespace

int main(int argc, char** argv) {
    BakeCommandLine cl;
    if (const auto rc = parseBakeCommandLine(argc, argv, cl, std::cout, std::cerr))
        return *rc;
    const std::string& scenePath = cl.scenePath;
    const std::string& output = cl.output;
    const int threads = cl.threads;
    const bool quiet = cl.quiet;
    if (threads > 0)
        omp_set_num_threads(threads);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);

    if (const std::string problem = outputPathProblem(output); !problem.empty()) {
        std::fprintf(stderr, "swell-bake: %s\n", problem.c_str());
        return cli::kExitBadInput;
    }
    ProgressReporter progress(quiet);
    try {
        const Scene scene = loadBakeScene(cl); // bake-specific scene errors before any warning
        const std::vector<std::string> before = sceneWarnings(scene);
        for (const std::string& w : before)
            std::fprintf(stderr, "swell-bake: warning: %s\n", w.c_str());
        BakeOptions opt;
        opt.output = output;
        opt.probes = cl.probes;
        opt.sceneFile = scenePath;
        opt.overrides = cl.sets;
        opt.threads = threads > 0 ? threads : omp_get_max_threads();
        opt.programVersion = SWELL_VERSION;
        opt.checkpointEvery = cl.checkpointEvery;
        opt.resume = cl.resume;
        opt.onProgress = [&](const BakeProgress& p) { progress(p); };
        opt.cancelled = [] { return g_stop != 0; };
        const BakeSummary s = runBake(scene, opt);
        for (std::size_t i = before.size(); i < s.warnings.size(); ++i) // the run's own
            std::fprintf(stderr, "swell-bake: warning: %s\n", s.warnings[i].c_str());
        if (!quiet)
            printSummary(scene, s, output);
        if (cl.asJson)
            std::printf("%s\n", toJson(s).dump().c_str());
        return cli::kExitOk;
    } catch (const std::exception& e) {
        return reportFailure(e, scenePath, progress);
    }
}
