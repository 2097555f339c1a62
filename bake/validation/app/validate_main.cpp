// swell-validate: developer runs behind docs/validation.md (dam break against Martin & Moyce
// and against the water levels of Lobovsky et al. 2014, regular waves against linear wavemaker
// theory, still-tank hydrostatics, a standing wave against linear theory, a solitary wave against
// Boussinesq's and Rayleigh's theory, a dam breaking onto a wet bed against Stoker's solution,
// a solitary wave shoaling up a beach against Grilli et al. 1994).
// Thin: scene loading, the solver and the comparisons are library code.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>
#include <omp.h>

#include "case_reports.h"
#include "ensemble.h"
#include "ensemble_figures.h"
#include "exit_codes.h"
#include "report_files.h"
#include "validate_cli.h"

#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/shoaling.h"
#include "swell/bake/validation/validation.h"
#include "swell/bake/validation/wall_pressure.h"

using namespace swell::bake;
using namespace swell::bake::validation;
using nlohmann::json;

namespace {

/// One check: run(scene, single) runs it once; a single run also writes the files its options
/// name (--csv, --keep), an ensemble member does not. `figures` reads what an ensemble spreads.
struct Check {
    std::function<json(const Scene&, bool)> run;
    std::function<Figures(const json&)> figures;
};

/// The check the command line names, with its options; `cl` must outlive it.
Check checkFor(const ValidateCommandLine& cl, const Scene& scene) {
    using Run = ValidateCommandLine::Run;
    switch (cl.run) {
    case Run::DamBreak:
        return {[&cl](const Scene& s, bool single) {
                    return damBreak(s, cl.damUntil, single ? cl.csv : "");
                },
                damBreakFigures};
    case Run::Lobovsky:
        return {[&cl](const Scene& s, bool single) {
                    return lobovsky(s, cl.lobovskyUntil, single ? cl.csv : "");
                },
                lobovskyFigures};
    case Run::RegularWave:
        return {[&cl](const Scene& s, bool single) {
                    return regularWave(s, cl.waveFrom, cl.waveTo, single ? cl.keep : "", cl.probes);
                },
                regularWaveFigures};
    case Run::StandingWave:
        return {
            [&cl](const Scene& s, bool single) { return standingWave(s, single ? cl.csv : ""); },
            standingWaveFigures};
    case Run::SolitaryWave:
        return {
            [&cl](const Scene& s, bool single) { return solitaryWave(s, single ? cl.csv : ""); },
            solitaryWaveFigures};
    case Run::WetDamBreak:
        return {[&cl](const Scene& s, bool single) { return wetDamBreak(s, single ? cl.csv : ""); },
                wetDamBreakFigures};
    case Run::Shoaling:
        return {[&cl](const Scene& s, bool single) { return shoaling(s, single ? cl.csv : ""); },
                shoalingFigures};
    case Run::StillTank:
        break;
    }
    const long steps =
        cl.steps >= 0 ? cl.steps : std::lround(scene.run.endTime / scene.solver.time.dt);
    return {[&cl, steps](const Scene& s, bool) { return stillTank(s, cl.settle, steps, cl.trace); },
            stillTankFigures};
}

/// Writes the experiments' records that --records and --pressure-records name, before the
/// run: a bad path fails now, not after it.
void writeRecords(const ValidateCommandLine& cl) {
    using Run = ValidateCommandLine::Run;
    if (!cl.records.empty())
        writeTextFile(cl.records,
                      cl.run == Run::DamBreak   ? martinMoyceRecordsCsv()
                      : cl.run == Run::Shoaling ? grilli1994RecordsCsv()
                                                : lobovskyRecordsCsv(),
                      "--records");
    if (!cl.pressureRecords.empty())
        writeTextFile(cl.pressureRecords, buchnerP1RecordsCsv(), "--pressure-records");
}

/// Prints the report on stdout: one JSON object, or one line per key (its value as JSON).
void printReport(const json& out, bool asJson) {
    if (asJson) {
        std::printf("%s\n", out.dump().c_str());
    } else {
        for (const auto& [k, v] : out.items())
            std::printf("%-26s %s\n", k.c_str(), v.dump().c_str());
    }
}

/// kExitOk for a stable run; kExitDiverged for a stopped one, which keeps its figures in the
/// report (stdout) and says why on stderr.
int exitStatus(const json& out, const std::string& scene) {
    const json& outcome = out.at("outcome");
    if (outcome.is_string() && outcome.get_ref<const std::string&>() == kStable)
        return swell::cli::kExitOk;
    std::fprintf(stderr, "swell-validate: %s: %s\n", scene.c_str(),
                 outcome.get<std::string>().c_str());
    return swell::cli::kExitDiverged;
}

} // namespace

int main(int argc, char** argv) {
    ValidateCommandLine cl;
    if (const auto rc = parseValidateCommandLine(argc, argv, cl, std::cout, std::cerr))
        return *rc;
    if (cl.threads > 0)
        omp_set_num_threads(cl.threads);
    try {
        const auto start = std::chrono::steady_clock::now();
        const Scene scene = loadValidateScene(cl);
        writeRecords(cl);
        const Check check = checkFor(cl, scene);
        json out = cl.ensemble > 0
                       ? ensemble(
                             scene, cl.ensemble,
                             [&](const Scene& s) { return check.run(s, false); }, check.figures)
                       : check.run(scene, true);
        out["wall_seconds"] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out["threads"] = omp_get_max_threads();
        out["overrides"] = cl.sets;
        printReport(out, cl.asJson);
        return exitStatus(out, cl.scene);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "swell-validate: %s\n", e.what());
        return swell::cli::exitCodeFor(e);
    }
}
