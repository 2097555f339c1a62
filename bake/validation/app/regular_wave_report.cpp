// swell-validate regular-wave: a bake's wave heights and wavelength against linear theory.
#include "case_reports.h"

#include <cstddef>
#include <filesystem>
#include <vector>

#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include "report_figures.h"

#include "swell/bake/bake_driver.h"
#include "swell/bake/error.h"
#include "swell/bake/probes.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/regular_wave.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {
namespace {

/// Bakes the scene with probes, or reads the probes CSV `probes` a bake of it wrote (then
/// nothing is baked and the bake's figures are left out); `keep`: where the bake's cache and
/// probes stay.
std::vector<ProbeSample> regularWaveRecord(const Scene& scene, const std::string& keep,
                                           const std::string& probes, json& out) {
    namespace fs = std::filesystem;
    if (!probes.empty()) {
        std::vector<ProbeSample> samples = readProbeCsv(probes, scene.output.gauges);
        requireRecordCoversWindows(samples, regularWaveGaugeWindows(scene),
                                   1.5 * scene.output.frameInterval, probes);
        out["probes"] = probes;
        out["outcome"] = kStable;
        return samples;
    }
    const fs::path dir =
        keep.empty() ? fs::temp_directory_path() / fmt::format("swell_regular_wave_{}", ::getpid())
                     : fs::path(keep);
    fs::create_directories(dir);
    BakeOptions opt;
    opt.output = dir / (scene.name + ".swell");
    opt.probes = dir / (scene.name + ".probes.csv");
    opt.threads = omp_get_max_threads();
    try {
        const BakeSummary summary = runBake(scene, opt);
        out["outcome"] = kStable;
        out["water"] = summary.particlesWater;
        out["fixed"] = summary.particlesWall;
        out["steps"] = summary.steps;
        out["ms_per_step"] = summary.msPerStep;
        out["us_per_particle_step"] =
            1e3 * summary.msPerStep /
            static_cast<double>(summary.particlesWater + summary.particlesWall);
        out["ppe_iterations_mean"] = summary.ppeIterationsMean;
    } catch (const DivergenceError& e) {
        out["outcome"] = std::string("stopped: ") + e.what();
        if (keep.empty())
            fs::remove_all(dir);
        return {};
    }
    std::vector<ProbeSample> samples = readProbeCsv(opt.probes);
    if (keep.empty())
        fs::remove_all(dir);
    return samples;
}

} // namespace

json regularWave(const Scene& scene, double from, double to, const std::string& keep,
                 const std::string& probes) {
    json out{{"scene", scene.name}, {"l0", scene.geometry.particleSpacing}};
    const std::vector<ProbeSample> samples = regularWaveRecord(scene, keep, probes, out);
    if (out["outcome"] != kStable)
        return out;
    WaveWindow window = regularWaveWindow(scene);
    std::vector<WaveWindow> gaugeWindows = regularWaveGaugeWindows(scene);
    if (from >= 0.0 || to >= 0.0) { // one window for every gauge, as the user set it
        if (from >= 0.0)
            window.start = from;
        if (to >= 0.0)
            window.end = to;
        gaugeWindows.assign(gaugeWindows.size(), window);
    }
    const RegularWaveCheck c = checkRegularWave(scene, samples, window, gaugeWindows);
    out["depth"] = c.depth;
    out["kh"] = c.theory.kh;
    out["window"] = {c.window.start, c.window.end};
    out["samples"] = c.samples;
    out["gauges"] = c.gauges;
    json windows = json::array();
    for (const WaveWindow& w : c.gaugeWindows)
        windows.push_back({w.start, w.end});
    out["gauge_windows"] = windows;
    out["gauge_samples"] = c.gaugeSamples;
    out["height_theory"] = c.theory.height;
    out["heights"] = c.heights;
    json errors = json::array();
    json commonErrors = json::array();
    for (std::size_t g = 0; g < c.heights.size(); ++g) {
        errors.push_back(c.heightError(g));
        commonErrors.push_back(c.heightsCommonWindow[g] / c.theory.height - 1.0);
    }
    out["height_errors"] = errors;
    // Each height error's standard error from its record's fluctuations, of theory's H.
    json standardErrors = json::array();
    for (double se : c.heightStandardErrors)
        standardErrors.push_back(finiteOrNull(se / c.theory.height));
    out["height_errors_standard_error"] = standardErrors;
    // Every gauge's height error fitted in the common window instead of its own.
    out["height_errors_common_window"] = commonErrors;
    out["wavelength_theory"] = c.theory.wavelength;
    out["wavelength"] = c.wavelength;
    out["wavelength_error"] = c.wavelengthError();
    out["wavelength_fit"] = c.wavelengthFit;
    out["wavelength_fit_error"] = c.wavelengthFitError();
    out["decay_per_wavelength"] = c.decayPerWavelength;
    out["decay_total"] = c.decayTotal;
    out["decay_total_fit"] = c.decayOverSpan;
    // The same measurement of linear theory's record of the same piston in the same tank
    // (linearTheoryRecord, the far wall reflecting): what the windows and fits alone make of an
    // undamped wave train.
    std::vector<double> times;
    for (const ProbeSample& s : samples)
        times.push_back(s.time);
    const RegularWaveCheck lin =
        checkRegularWave(scene, linearTheoryRecord(scene, times), window, c.gaugeWindows);
    json linErrors = json::array();
    for (std::size_t g = 0; g < lin.heights.size(); ++g)
        linErrors.push_back(lin.heightError(g));
    out["theory_record_height_errors"] = linErrors;
    out["theory_record_decay_per_wavelength"] = lin.decayPerWavelength;
    out["theory_record_decay_total"] = lin.decayTotal;
    out["theory_record_decay_total_fit"] = lin.decayOverSpan;
    // The height lost over the gauges against what linear theory loses in the same tank and
    // windows: 1 - (1 - lost) / (1 - lost by theory's record).
    out["decay_total_fit_against_theory_record"] =
        1.0 - (1.0 - c.decayOverSpan) / (1.0 - lin.decayOverSpan);
    // Their standard errors, from the record's fluctuations: linear theory's record has none.
    out["decay_total_fit_standard_error"] = finiteOrNull(c.decayOverSpanStandardError);
    out["decay_total_fit_against_theory_record_standard_error"] =
        finiteOrNull(c.decayOverSpanStandardError / (1.0 - lin.decayOverSpan));
    out["steepness_theory"] = c.theory.steepness;
    out["ppe_tolerance"] = scene.solver.pressure.tolerance;
    return out;
}

} // namespace swell::bake
