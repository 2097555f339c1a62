// swell-validate: developer runs behind docs/validation.md (dam break against Martin & Moyce
// and against the water levels of Lobovsky et al. 2014, regular waves against linear wavemaker
// theory, still-tank hydrostatics, a standing wave against linear theory, a solitary wave against
// Boussinesq's and Rayleigh's theory, a dam breaking onto a wet bed against Stoker's solution,
// a solitary wave shoaling up a beach against Grilli et al. 1994).
// Thin: scene loading, the solver and the comparisons are library code.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <unistd.h>

#include "validate_cli.h"

#include "swell/bake/bake_driver.h"
#include "swell/bake/error.h"
#include "swell/bake/probes.h"
#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/dam_break_run.h"
#include "swell/bake/validation/lobovsky2014.h"
#include "swell/bake/validation/lobovsky_run.h"
#include "swell/bake/validation/regular_wave.h"
#include "swell/bake/validation/shoaling.h"
#include "swell/bake/validation/solitary_wave.h"
#include "swell/bake/validation/standing_wave.h"
#include "swell/bake/validation/still_tank.h"
#include "swell/bake/validation/validation.h"
#include "swell/bake/validation/wall_pressure.h"
#include "swell/bake/validation/wet_dam_break.h"
#include "swell/cache/checked_write.h"

using namespace swell::bake;
using namespace swell::bake::validation;
using nlohmann::json;

namespace {

/// A figure as JSON: null where the run could not measure it (NaN).
json finiteOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

/// A member's figure for the ensemble's spread: NaN for null, which stays out of the spread.
double numberOrNaN(const json& v) {
    return v.is_null() ? std::nan("") : v.get<double>();
}

/// Solver time per step and particle (µs), 0 for a run that took no step.
double usPerParticleStep(double seconds, long steps, std::size_t particles) {
    return steps > 0 ? 1e6 * seconds / (static_cast<double>(steps) * static_cast<double>(particles))
                     : 0.0;
}

/// Writes `text` to `path` whole or not at all: to a temporary name in the same folder,
/// renamed when complete. Throws std::runtime_error naming the option, the file and the error.
void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* option) {
    if (const swell::cache::ReplaceResult r =
            swell::cache::replaceFile(path, text.data(), text.size());
        r.error != 0) {
        throw std::runtime_error(
            fmt::format("{} {}: cannot write: {}", option, path.string(), std::strerror(r.error)));
    }
}

/// Writes a wave check's gauge records (GaugeRecords) to `path` as CSV: a column t (s), then one
/// per gauge, named by `columns`, of the elevations (m).
void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::vector<std::string>& columns) {
    std::string text = "t";
    for (const std::string& c : columns)
        text += "," + c;
    text += '\n';
    for (std::size_t k = 0; k < r.times.size(); ++k) {
        text += fmt::format("{:.5f}", r.times[k]);
        for (const std::vector<double>& e : r.elevations)
            text += fmt::format(",{:.6f}", e[k]);
        text += '\n';
    }
    writeTextFile(path, text, "--csv");
}

/// The same with one column per gauge at x (m), named PREFIX_x.
void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::string& prefix, std::span<const double> gauges) {
    std::vector<std::string> columns;
    for (double x : gauges)
        columns.push_back(fmt::format("{}_{}", prefix, x));
    writeGaugeSeries(path, r, columns);
}

/// A wave check's cost in its report: steps, PPE iterations, solver time, and that time per
/// step and particle.
void addRunCost(json& out, const GaugeRecords& r, std::size_t particles) {
    out["steps"] = r.steps;
    out["ppe_iterations_mean"] = r.ppeIterationsMean;
    out["solver_seconds"] = r.solverSeconds;
    out["us_per_particle_step"] = usPerParticleStep(r.solverSeconds, r.steps, particles);
}

json damBreak(const Scene& scene, double tEnd, const std::string& csv) {
    const DamBreakRun run = runDamBreak(scene, tEnd);
    const std::vector<FrontPoint>& series = run.series;
    const StepTotals& totals = run.totals;
    json out{
        {"scene", scene.name},        {"a", run.a},         {"l0", scene.geometry.particleSpacing},
        {"particles", run.particles}, {"water", run.water}, {"outcome", run.outcome}};
    if (!csv.empty()) {
        std::string text = "T,Z\n";
        for (const auto& p : series)
            text += fmt::format("{:.5f},{:.5f}\n", p.T, p.Z);
        writeTextFile(csv, text, "--csv");
    }
    if (run.outcome == kStable) {
        const FrontError e225 = compareFront(series, martinMoyceA225(), 0.8, 3.0);
        const FrontError e1125 = compareFront(series, martinMoyceA1125(), 0.8, 3.0);
        const FrontError raw = pooled(e225, e1125);
        out["front_error_mean"] = raw.mean;
        out["front_error_max"] = raw.max;
        out["front_error_mean_signed"] = raw.meanSigned;
        out["front_error_mean_a225"] = e225.mean;
        out["front_error_mean_a1125"] = e1125.mean;
        out["points"] = raw.points;
        // Time origin tied to the front (alignedFront): each series shifted so that the front
        // reaches that series' first recorded position at its T; pooled like the raw figures.
        const AlignedFront a225 = alignedFront(series, martinMoyceA225(), 0.8, 3.0);
        const AlignedFront a1125 = alignedFront(series, martinMoyceA1125(), 0.8, 3.0);
        const FrontError aligned = pooled(a225.error, a1125.error);
        out["aligned_front_error_mean"] = aligned.mean;
        out["aligned_front_error_max"] = aligned.max;
        out["aligned_front_error_mean_signed"] = aligned.meanSigned;
        out["aligned_shift_T"] =
            (a225.shift * a225.error.points + a1125.shift * a1125.error.points) / aligned.points;
        out["aligned_front_error_mean_a225"] = a225.error.mean;
        out["aligned_front_error_mean_a1125"] = a1125.error.mean;
        out["aligned_shift_T_a225"] = a225.shift;
        out["aligned_shift_T_a1125"] = a1125.shift;
        out["aligned_points"] = aligned.points;
        // The experiment against itself under the same rule (martinMoyceScatter).
        const AlignedFront scatter = martinMoyceScatter(0.8, 3.0);
        out["experiment_scatter_mean"] = scatter.error.mean;
        out["experiment_scatter_max"] = scatter.error.max;
        json z = json::object();
        for (double T : {1.0, 2.0, 3.0}) {
            for (std::size_t k = 1; k < series.size(); ++k) {
                if (series[k].T >= T) {
                    z[fmt::format("{:.1f}", T)] = series[k].Z;
                    break;
                }
            }
        }
        out["Z_at_T"] = z;
    }
    out["steps"] = totals.steps;
    out["ppe_iterations_mean"] = totals.ppeIterationsMean();
    out["ppe_tolerance"] = scene.solver.pressure.tolerance;
    out["solver_seconds"] = totals.seconds;
    return out;
}

/// What a pressure series says (wall_pressure.h), as JSON; null where it says nothing.
json pressureFiguresJson(std::span<const PressurePoint> series) {
    const PressureFigures f = pressureFigures(series);
    const auto orNull = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
    return {{"impact_time", orNull(f.impactTime)},
            {"second_peak_time", orNull(f.peakTime)},
            {"second_peak", f.peakTime ? json(f.peak) : json(nullptr)}};
}

/// The far wall's pressure at Buchner's sensor P1 against the experiment and Marrone et al.'s
/// delta-SPH (buchner2002.h; docs/validation.md, Far-wall pressure), in t sqrt(g / H) and
/// p / (rho g H).
json farWallPressure(std::span<const PressurePoint> p1, double low, double high,
                     std::size_t particles) {
    json out = pressureFiguresJson(p1);
    out["units"] = "t sqrt(g / H), p / (rho g H)";
    out["sensor"] = "P1";
    out["band"] = {low, high};
    out["sensor_particles"] = particles;
    // The rule every figure is read by (wall_pressure.h), for plots that draw the same.
    out["smoothing_half_width"] = kPressureSmoothing;
    out["impact_level"] = kImpactLevel;
    out["second_peak_window"] = {kSecondPeakFrom, kSecondPeakTo};
    for (const auto& [name, column] : buchnerP1Columns()) {
        const std::vector<PressurePoint> record = buchnerP1Series(column);
        json r = pressureFiguresJson(record);
        const std::optional<double> e = meanAbsPressureError(p1, record);
        r["mean_abs_error"] = e ? json(*e) : json(nullptr);
        out[name] = r;
    }
    return out;
}

/// Lobovsky et al. (2014) dam break: water height at the gauges H1..H4 against the records.
/// Sampled after every solver step (denser than the records' 300 Hz); the simulated series is
/// interpolated at the record times (compareLevel). Height: top of the highest non-splash water
/// particle within l0 of the gauge (sampleProbes with the tank floor as level), 0 where dry
/// (runLobovsky). Over [0, 1.5] s, and over the first impact and run-up alone, until the
/// record's water lands on the far gauge (lobovskyRunUpEnd), with the time the run's lands there.
json lobovsky(const Scene& scene, double tEnd, const std::string& csv) {
    const LobovskyRun run = runLobovsky(scene, tEnd);
    const std::span<const LevelGauge> gauges = lobovskyH300Gauges();
    const double H = run.H;
    json out{{"scene", scene.name},
             {"H", H},
             {"gravity", scene.physics.gravity},
             {"l0", scene.geometry.particleSpacing},
             {"dt", scene.solver.time.dt},
             {"particles", run.particles},
             {"water", run.water},
             {"outcome", run.outcome}};
    // The far wall's pressure at sensor P1 in the records' units (buchner2002.h).
    const double pressureScale = scene.physics.density * scene.physics.gravity * H;
    const double timeScale = std::sqrt(scene.physics.gravity / H);
    std::vector<PressurePoint> p1;
    for (const PressureSample& q : run.farWallPressure)
        p1.push_back({q.t * timeScale, q.p / pressureScale});
    if (!csv.empty()) {
        std::string text = "t";
        for (const LevelGauge& g : gauges)
            text += fmt::format(",h_{}", g.name);
        text += ",p_P1_over_rho_g_H\n";
        for (std::size_t k = 0; k < run.top[0].size(); ++k) {
            text += fmt::format("{:.5f}", run.top[0][k].t);
            for (const auto& s : run.top)
                text += fmt::format(",{:.5f}", s[k].h);
            text += fmt::format(",{:.5f}\n", p1[k].p);
        }
        writeTextFile(csv, text, "--csv");
    }
    if (run.outcome == kStable) {
        const double tLo = 0.0;
        const double tHi = std::min(1.5, tEnd);
        // The first impact and run-up: until the far wall's water lands on the gauge nearest it
        // in the record (lobovskyRunUpEnd). The level that says so is half the experiment's
        // column, not the scene's: the window is the record's whatever H a scene has.
        const double recordH = lobovskyH300Geometry().columnHeight;
        const double landsRecord = lobovskyRunUpEnd(gauges, recordH);
        const double tRunUp = std::min(landsRecord, tEnd);
        json list = json::array();
        double worst = 0.0, worstRunUp = 0.0;
        for (std::size_t g = 0; g < gauges.size(); ++g) {
            const LevelError e = compareLevel(run.top[g], gauges[g].series, tLo, tHi);
            const LevelError runUp = compareLevel(run.top[g], gauges[g].series, tLo, tRunUp);
            // The experiment against itself over the same window (null: no second series).
            const std::optional<LevelError> scatter = lobovskyScatter(gauges[g], tLo, tHi);
            list.push_back(
                {{"name", gauges[g].name},
                 {"x", gauges[g].x},
                 {"mean_abs_error_over_H", e.mean / H},
                 {"max_abs_error_over_H", e.max / H},
                 {"mean_signed_error_over_H", e.meanSigned / H},
                 {"points", e.points},
                 {"mean_abs_error_over_H_run_up", runUp.mean / H},
                 {"experiment_scatter_over_H", scatter ? json(scatter->mean / H) : json(nullptr)}});
            worst = std::max(worst, e.mean / H);
            worstRunUp = std::max(worstRunUp, runUp.mean / H);
        }
        out["gauges"] = list;
        out["mean_abs_error_over_H_worst"] = worst;
        out["window"] = {tLo, tHi};
        out["mean_abs_error_over_H_worst_run_up"] = worstRunUp;
        out["run_up_window"] = {tLo, tRunUp};
        // When the water lands on the far gauge (first above recordH / 2), simulated and recorded.
        const std::size_t far = lobovskyFarGauge(gauges);
        const std::optional<double> lands = firstTimeAbove(run.top[far], 0.5 * recordH);
        out["far_gauge"] = gauges[far].name;
        out["far_gauge_landing_time"] = lands ? json(*lands) : json(nullptr);
        out["far_gauge_landing_time_record"] = landsRecord;
        // Null where the sensor's band holds no wall particle (a spacing above its height).
        out["far_wall_pressure"] =
            run.sensorParticles == 0
                ? json(nullptr)
                : farWallPressure(p1, run.sensorLow, run.sensorHigh, run.sensorParticles);
    }
    out["steps"] = run.totals.steps;
    out["ppe_iterations_mean"] = run.totals.ppeIterationsMean();
    out["solver_seconds"] = run.totals.seconds;
    out["us_per_particle_step"] =
        usPerParticleStep(run.totals.seconds, run.totals.steps, run.particles);
    return out;
}

json stillTank(const Scene& scene, double settle, long steps, long trace) {
    StillTankStep onStep;
    if (trace > 0) {
        // Called only once runStillTank has checked that the scene has a tank.
        onStep = [trace, &scene](const MpsSolver& solver, const StepStats& s) {
            if (s.step % trace != 0)
                return;
            const FastestParticle f =
                fastestWaterParticle(solver, *scene.geometry.tank, scene.geometry.particleSpacing);
            std::fprintf(
                stderr,
                "step %ld t %.3f max|u| %.4f (particle %zu at %.4f, %.4f n/n0 %.3f; before the "
                "shift %.4f) ppe %d surface %zu collisions %zu\n",
                s.step, s.time, std::hypot(f.u, f.v), f.index, f.x, f.y,
                solver.particles().n[f.index] / solver.densityConstants().n0, s.maxSpeed,
                s.ppeIterations, s.surfaceParticles, s.collisions);
        };
    }
    const StillTankReport r = runStillTank(scene, settle, steps, onStep);
    json out{{"scene", scene.name},
             {"H", scene.geometry.water.at(0).height()},
             {"l0", scene.geometry.particleSpacing},
             {"particles", r.particles},
             {"water", r.water},
             {"gauge_particles", r.gaugeParticles},
             {"outcome", r.outcome},
             {"steps", r.steps},
             {"time", r.time},
             {"bottom_pressure_mean", r.bottomPressureMean},
             {"rho_g_H", r.rhoGH},
             {"bottom_pressure_ratio", r.bottomPressureRatio},
             {"max_speed_after_settle", r.maxSpeed},
             {"max_speed_over_sqrt_gH", r.maxSpeedOverSqrtGH},
             {"max_speed_before_shift_over_sqrt_gH", r.maxSpeedBeforeShiftOverSqrtGH},
             {"mean_speed_over_sqrt_gH", r.meanSpeedOverSqrtGH},
             {"max_excursion_over_l0", r.maxExcursionOverL0},
             {"max_drift_speed_over_sqrt_gH", r.maxDriftSpeedOverSqrtGH},
             {"escaped", r.escaped},
             {"ppe_iterations_mean", r.ppeIterationsMean},
             {"solver_seconds", r.solverSeconds}};
    if (r.maxSpeed > 0.0) {
        const FastestParticle& f = r.fastest;
        out["fastest_after_settle"] = {{"particle", f.index},
                                       {"time", f.time},
                                       {"x", f.x},
                                       {"y", f.y},
                                       {"u", f.u},
                                       {"v", f.v},
                                       {"free_surface", f.freeSurface},
                                       {"depth_below_top_over_l0", f.depthOverL0},
                                       {"wall_distance_over_l0", f.wallDistanceOverL0}};
    }
    return out;
}

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

/// The regular-wave check (regular_wave.h) of a bake of `scene` (regularWaveRecord): each
/// gauge's height in its own window and the phases in the common one, or every figure in
/// [from, to] where --from / --to set it.
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

/// A standing wave (standing_wave.h, runStandingWave): the period at the two side walls
/// against linear theory's and the decay per period against none.
json standingWave(const Scene& scene, const std::string& csv) {
    const StandingWaveReport r = runStandingWave(scene);
    const CosineTop top = waterTop(scene.geometry, 0);
    json out{{"scene", scene.name},
             {"l0", scene.geometry.particleSpacing},
             {"depth", scene.geometry.water.front().height()},
             {"amplitude", top.amplitude},
             {"wavelength", top.wavelength},
             {"kh", r.theory.kh},
             {"period_theory", r.theory.period},
             {"gauges", r.gauges},
             {"particles", r.particles},
             {"water", r.water},
             {"outcome", r.outcome}};
    if (!csv.empty())
        writeGaugeSeries(csv, r, {"eta_left", "eta_right"});
    if (r.outcome == kStable) {
        json gauges = json::array();
        for (std::size_t g = 0; g < r.records.size(); ++g)
            gauges.push_back({{"x", r.gauges[g]},
                              {"period", r.records[g].period},
                              {"amplitudes", r.records[g].amplitudes},
                              {"decay_per_period", r.records[g].decayPerPeriod}});
        out["gauge_records"] = gauges;
        out["period"] = r.period;
        out["period_error"] = r.periodError;
        out["decay_per_period"] = r.decayPerPeriod;
        out["first_amplitude_over_theory"] = r.firstAmplitudeOverTheory;
    }
    addRunCost(out, r, r.particles);
    return out;
}

/// A solitary wave (solitary_wave.h, runSolitaryWave): its crest at each gauge, its celerity
/// against sqrt(g (h + A)), the height it loses and its width against Boussinesq's.
json solitaryWave(const Scene& scene, const std::string& csv) {
    const SolitaryWaveReport r = runSolitaryWave(scene);
    json out{{"scene", scene.name},
             {"l0", scene.geometry.particleSpacing},
             {"depth", r.depth},
             {"height", r.height},
             {"height_over_depth", r.height / r.depth},
             {"stroke", r.stroke},
             {"celerity_theory", r.theory.celerity},
             {"gauges", r.gauges},
             {"particles", r.particles},
             {"water", r.water},
             {"outcome", r.outcome}};
    if (!csv.empty())
        writeGaugeSeries(csv, r, "eta", r.gauges);
    if (r.outcome == kStable) {
        const SolitaryWaveCheck& c = r.check;
        json crests = json::array();
        for (const SolitaryCrest& k : c.crests)
            crests.push_back({{"x", k.x},
                              {"time", k.time},
                              {"amplitude", k.amplitude},
                              {"amplitude_over_height", k.amplitude / r.height},
                              {"still_level", k.stillLevel},
                              {"width_error", k.widthError}});
        out["crests"] = crests;
        out["celerity"] = c.celerity;
        out["celerity_error"] = c.celerityError;
        out["first_amplitude_over_height"] = c.firstAmplitudeOverHeight;
        out["decay_total"] = c.decayTotal;
        out["distance_over_depth"] = (c.crests.back().x - c.crests.front().x) / r.depth;
        out["mean_width_error"] = c.meanWidthError;
    }
    addRunCost(out, r, r.particles);
    return out;
}

/// A dam breaking onto a wet bed (wet_dam_break.h, runWetDamBreak): the depth at each gauge and
/// the bore's speed against Stoker's shallow-water solution.
json wetDamBreak(const Scene& scene, const std::string& csv) {
    const WetDamBreakReport r = runWetDamBreak(scene);
    const StokerDamBreak& t = r.theory;
    json out{{"scene", scene.name},
             {"l0", scene.geometry.particleSpacing},
             {"h0", t.h0},
             {"h1", t.h1},
             {"h1_over_h0", t.h1 / t.h0},
             {"gate", r.gate},
             {"theory",
              {{"bore_speed", t.boreSpeed},
               {"h2", t.h2},
               {"u2", t.u2},
               {"c0", t.c0},
               {"c2", t.c2},
               {"gravity", t.gravity}}},
             {"compared_from", t.comparedFrom()},
             {"gauges", r.gauges},
             {"particles", r.particles},
             {"water", r.water},
             {"outcome", r.outcome}};
    if (!csv.empty())
        writeGaugeSeries(csv, r, "h", r.gauges);
    if (r.outcome == kStable) {
        const WetDamBreakCheck& c = r.check;
        // NaN (no bore, or no plateau, at a gauge) as null.
        json gauges = json::array();
        for (const WetDamBreakGauge& g : c.gauges)
            gauges.push_back(
                {{"x", g.x},
                 {"from", g.from},
                 {"until", g.until},
                 {"mean_abs_error_over_h0", g.meanAbsErrorOverH0},
                 {"mean_signed_error_over_h0", g.meanSignedErrorOverH0},
                 {"bore_arrival", finiteOrNull(g.boreArrival)},
                 {"bore_arrival_theory", finiteOrNull(g.boreArrivalTheory)},
                 {"plateau_depth_over_theory", finiteOrNull(g.plateauDepthOverTheory)}});
        out["gauge_records"] = gauges;
        out["bore_speed"] = c.boreSpeed;
        out["bore_speed_error"] = c.boreSpeedError;
        out["bore_gauges"] = c.boreGauges;
        out["plateau_depth_error"] = finiteOrNull(c.plateauDepthError);
        out["mean_abs_error_over_h0_worst"] = c.meanAbsErrorOverH0Worst;
    }
    addRunCost(out, r, r.particles);
    return out;
}

/// A solitary wave shoaling up a beach (shoaling.h, runShoaling): the elevation at the six
/// gauges against Grilli et al. (1994)'s records, on the clock of g0's crest.
json shoaling(const Scene& scene, const std::string& csv) {
    const ShoalingReport r = runShoaling(scene);
    json out{{"scene", scene.name},
             {"l0", scene.geometry.particleSpacing},
             {"depth", r.depth},
             {"height", r.height},
             {"height_over_depth", r.height / r.depth},
             {"gravity", scene.physics.gravity},
             {"toe", r.toe},
             {"slope", r.slope},
             {"still_window", {r.stillFrom, r.stillTo}},
             {"gauges", r.gauges},
             {"particles", r.particles},
             {"water", r.water},
             {"outcome", r.outcome}};
    if (!csv.empty())
        writeGaugeSeries(csv, r, "eta", r.gauges);
    if (r.outcome == kStable) {
        const ShoalingCheck& c = r.check;
        json gauges = json::array();
        for (const ShoalingGaugeError& g : c.gauges)
            gauges.push_back({{"name", g.name},
                              {"x", g.x},
                              {"crest_over_h0", g.crest},
                              {"crest_record_over_h0", g.crestRecord},
                              {"crest_time", g.crestTime},
                              {"crest_time_record", g.crestTimeRecord},
                              {"amplification", g.amplification},
                              {"amplification_record", g.amplificationRecord},
                              {"mean_abs_error_over_h0", g.meanAbsError},
                              {"mean_signed_error_over_h0", g.meanSignedError},
                              {"rise", g.rise},
                              {"rise_record", g.riseRecord},
                              {"fall", g.fall},
                              {"fall_record", g.fallRecord},
                              {"energy_ratio", g.energyRatio},
                              {"from", g.from},
                              {"until", g.until},
                              {"still_level", g.stillLevel}});
        out["gauge_records"] = gauges;
        out["clock_offset"] = c.clockOffset;
        out["incident_crest_error"] = c.incidentCrestError;
        out["crest_error_worst"] = c.crestErrorWorst;
        out["amplification_error_worst"] = c.amplificationErrorWorst;
        out["mean_abs_error_over_h0_worst"] = c.meanAbsErrorWorst;
        out["travel_time_error"] = c.travelTimeError;
    }
    addRunCost(out, r, r.particles);
    return out;
}

json toJson(const Spread& s) {
    return {{"mean", s.mean}, {"sd", s.sd}, {"min", s.min}, {"max", s.max}, {"members", s.count}};
}

/// Named figures of one member's report, whose spread over the ensemble is reported.
using Figures = std::vector<std::pair<std::string, double>>;

/// A check as an ensemble: members with seeds 1..n and the water jittered (by the scene's
/// geometry.jitter, or 1e-6 l0), the same flow up to a perturbation far below the resolution.
/// Where the flow amplifies small differences (a breaking jet, a wave train over several
/// wavelengths) one record is one draw, and the spread of the members' figures is how far it can be
/// trusted. `run` runs one member; `figures` reads the figures of a stable member's report, the
/// same names in the same order for every member.
json ensemble(Scene scene, int n, const std::function<json(const Scene&)>& run,
              const std::function<Figures(const json&)>& figures) {
    if (!(scene.geometry.jitter > 0.0))
        scene.geometry.jitter = 1e-6;
    json members = json::array();
    std::vector<std::pair<std::string, std::vector<double>>> values;
    bool stable = true;
    for (int m = 1; m <= n; ++m) {
        scene.seed = static_cast<std::uint64_t>(m);
        json r = run(scene);
        r["seed"] = m;
        if (r["outcome"] != kStable) {
            stable = false;
        } else {
            const Figures f = figures(r);
            if (values.empty()) {
                for (const auto& [name, v] : f)
                    values.push_back({name, {}});
            }
            // A figure a member could not measure (NaN) stays out of the others' spread.
            for (std::size_t k = 0; k < f.size(); ++k) {
                if (std::isfinite(f[k].second))
                    values[k].second.push_back(f[k].second);
            }
        }
        std::fprintf(stderr, "swell-validate: ensemble member %d of %d: %s\n", m, n,
                     r["outcome"].get<std::string>().c_str());
        members.push_back(std::move(r));
    }
    json out{{"scene", scene.name},
             {"ensemble", n},
             {"jitter", scene.geometry.jitter},
             {"outcome", stable ? kStable : "stopped: a member stopped (see members)"},
             {"members", members}};
    // A figure no member measured reads null: an ensemble's other figures are never lost.
    for (const auto& [name, v] : values)
        out[name] = v.empty() ? json(nullptr) : toJson(spreadOf(v));
    return out;
}

Figures regularWaveFigures(const json& r) {
    const std::vector<double> e = r["height_errors"].get<std::vector<double>>();
    double worst = 0.0;
    for (double x : e)
        worst = std::max(worst, std::abs(x));
    // Each standard error's mean over the members is what one record predicts for the
    // members' spread of the figure above it.
    return {{"height_error_first_gauge", e.front()},
            {"height_error_first_gauge_standard_error",
             numberOrNaN(r["height_errors_standard_error"].front())},
            {"height_error_worst_gauge", worst},
            {"decay_total", r["decay_total"].get<double>()},
            {"decay_total_fit", r["decay_total_fit"].get<double>()},
            {"decay_total_fit_standard_error", numberOrNaN(r["decay_total_fit_standard_error"])},
            {"wavelength_fit_error", r["wavelength_fit_error"].get<double>()}};
}

Figures lobovskyFigures(const json& r) {
    Figures f;
    for (const json& g : r["gauges"]) {
        const std::string name = g["name"].get<std::string>();
        f.push_back({"mean_abs_error_over_H_" + name, g["mean_abs_error_over_H"].get<double>()});
        f.push_back(
            {"mean_signed_error_over_H_" + name, g["mean_signed_error_over_H"].get<double>()});
        // The same for every member; kept beside the errors it bounds (NaN: no second series).
        f.push_back(
            {"experiment_scatter_over_H_" + name, numberOrNaN(g["experiment_scatter_over_H"])});
    }
    f.push_back({"mean_abs_error_over_H_worst", r["mean_abs_error_over_H_worst"].get<double>()});
    for (const json& g : r["gauges"]) {
        f.push_back({"mean_abs_error_over_H_run_up_" + g["name"].get<std::string>(),
                     g["mean_abs_error_over_H_run_up"].get<double>()});
    }
    f.push_back({"mean_abs_error_over_H_worst_run_up",
                 r["mean_abs_error_over_H_worst_run_up"].get<double>()});
    f.push_back({"far_gauge_landing_time", numberOrNaN(r["far_gauge_landing_time"])});
    const json& p1 = r["far_wall_pressure"];
    // NaN for a figure that says nothing, and for all of them without a sensor.
    const auto value = [&p1](const char* record, const char* key) {
        if (p1.is_null())
            return std::nan("");
        return numberOrNaN(record ? p1[record][key] : p1[key]);
    };
    f.push_back({"far_wall_impact_time", value(nullptr, "impact_time")});
    f.push_back({"far_wall_second_peak_time", value(nullptr, "second_peak_time")});
    f.push_back({"far_wall_second_peak", value(nullptr, "second_peak")});
    f.push_back(
        {"far_wall_mean_abs_error_delta_sph_320", value("delta_sph_320", "mean_abs_error")});
    f.push_back({"far_wall_mean_abs_error_experiment", value("experiment", "mean_abs_error")});
    return f;
}

Figures stillTankFigures(const json& r) {
    return {{"bottom_pressure_ratio", r["bottom_pressure_ratio"].get<double>()},
            {"max_speed_over_sqrt_gH", r["max_speed_over_sqrt_gH"].get<double>()},
            {"max_speed_before_shift_over_sqrt_gH",
             r["max_speed_before_shift_over_sqrt_gH"].get<double>()},
            {"max_drift_speed_over_sqrt_gH", r["max_drift_speed_over_sqrt_gH"].get<double>()},
            {"mean_speed_over_sqrt_gH", r["mean_speed_over_sqrt_gH"].get<double>()},
            {"max_excursion_over_l0", r["max_excursion_over_l0"].get<double>()}};
}

Figures standingWaveFigures(const json& r) {
    return {{"period_error", r["period_error"].get<double>()},
            {"decay_per_period", r["decay_per_period"].get<double>()},
            {"first_amplitude_over_theory", r["first_amplitude_over_theory"].get<double>()}};
}

Figures solitaryWaveFigures(const json& r) {
    return {{"celerity_error", r["celerity_error"].get<double>()},
            {"first_amplitude_over_height", r["first_amplitude_over_height"].get<double>()},
            {"decay_total", r["decay_total"].get<double>()},
            {"mean_width_error", r["mean_width_error"].get<double>()}};
}

Figures wetDamBreakFigures(const json& r) {
    return {{"bore_speed_error", r["bore_speed_error"].get<double>()},
            {"plateau_depth_error", numberOrNaN(r["plateau_depth_error"])},
            {"mean_abs_error_over_h0_worst", r["mean_abs_error_over_h0_worst"].get<double>()}};
}

Figures shoalingFigures(const json& r) {
    Figures f{{"incident_crest_error", r["incident_crest_error"].get<double>()},
              {"crest_error_worst", r["crest_error_worst"].get<double>()},
              {"amplification_error_worst", r["amplification_error_worst"].get<double>()},
              {"mean_abs_error_over_h0_worst", r["mean_abs_error_over_h0_worst"].get<double>()},
              {"travel_time_error", r["travel_time_error"].get<double>()}};
    for (const json& g : r["gauge_records"]) {
        const std::string name = g["name"].get<std::string>();
        f.push_back({"crest_over_h0_" + name, g["crest_over_h0"].get<double>()});
        f.push_back({"mean_abs_error_over_h0_" + name, g["mean_abs_error_over_h0"].get<double>()});
        f.push_back({"energy_ratio_" + name, g["energy_ratio"].get<double>()});
        // A side whose half-height crossing the record's span does not hold reads null (NaN).
        for (const char* side : {"rise", "fall"})
            f.push_back({std::string(side) + "_" + name,
                         g[side].is_number() ? g[side].get<double>()
                                             : std::numeric_limits<double>::quiet_NaN()});
    }
    return f;
}

Figures damBreakFigures(const json& r) {
    return {{"front_error_mean", r["front_error_mean"].get<double>()},
            {"aligned_front_error_mean", r["aligned_front_error_mean"].get<double>()},
            {"aligned_front_error_max", r["aligned_front_error_max"].get<double>()}};
}

} // namespace

int main(int argc, char** argv) {
    ValidateCommandLine cl;
    if (const auto rc = parseValidateCommandLine(argc, argv, cl, std::cout, std::cerr))
        return *rc;
    if (cl.threads > 0)
        omp_set_num_threads(cl.threads);
    try {
        json out;
        const auto start = std::chrono::steady_clock::now();
        using Run = ValidateCommandLine::Run;
        const Scene scene = loadValidateScene(cl);
        if (!cl.records.empty()) // before the run: a bad path fails now, not after it
            writeTextFile(cl.records,
                          cl.run == Run::DamBreak   ? martinMoyceRecordsCsv()
                          : cl.run == Run::Shoaling ? grilli1994RecordsCsv()
                                                    : lobovskyRecordsCsv(),
                          "--records");
        if (!cl.pressureRecords.empty())
            writeTextFile(cl.pressureRecords, buchnerP1RecordsCsv(), "--pressure-records");
        // One check: run(scene, single) runs it once; a single run also writes the files its
        // options name (--csv, --keep), an ensemble member does not.
        std::function<json(const Scene&, bool)> run;
        std::function<Figures(const json&)> figures;
        if (cl.run == Run::DamBreak) {
            run = [&](const Scene& s, bool single) {
                return damBreak(s, cl.damUntil, single ? cl.csv : "");
            };
            figures = damBreakFigures;
        } else if (cl.run == Run::Lobovsky) {
            run = [&](const Scene& s, bool single) {
                return lobovsky(s, cl.lobovskyUntil, single ? cl.csv : "");
            };
            figures = lobovskyFigures;
        } else if (cl.run == Run::RegularWave) {
            run = [&](const Scene& s, bool single) {
                return regularWave(s, cl.waveFrom, cl.waveTo, single ? cl.keep : "", cl.probes);
            };
            figures = regularWaveFigures;
        } else if (cl.run == Run::StandingWave) {
            run = [&](const Scene& s, bool single) {
                return standingWave(s, single ? cl.csv : "");
            };
            figures = standingWaveFigures;
        } else if (cl.run == Run::SolitaryWave) {
            run = [&](const Scene& s, bool single) {
                return solitaryWave(s, single ? cl.csv : "");
            };
            figures = solitaryWaveFigures;
        } else if (cl.run == Run::WetDamBreak) {
            run = [&](const Scene& s, bool single) { return wetDamBreak(s, single ? cl.csv : ""); };
            figures = wetDamBreakFigures;
        } else if (cl.run == Run::Shoaling) {
            run = [&](const Scene& s, bool single) { return shoaling(s, single ? cl.csv : ""); };
            figures = shoalingFigures;
        } else {
            const long steps =
                cl.steps >= 0 ? cl.steps : std::lround(scene.run.endTime / scene.solver.time.dt);
            run = [&, steps](const Scene& s, bool) {
                return stillTank(s, cl.settle, steps, cl.trace);
            };
            figures = stillTankFigures;
        }
        out = cl.ensemble > 0
                  ? ensemble(
                        scene, cl.ensemble, [&](const Scene& s) { return run(s, false); }, figures)
                  : run(scene, true);
        out["wall_seconds"] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out["threads"] = omp_get_max_threads();
        out["overrides"] = cl.sets;
        if (cl.asJson) {
            std::printf("%s\n", out.dump().c_str());
        } else {
            for (const auto& [k, v] : out.items())
                std::printf("%-26s %s\n", k.c_str(), v.dump().c_str());
        }
        if (out["outcome"] == kStable)
            return 0;
        // A stopped run keeps its figures in the report (stdout) and says why on stderr.
        std::fprintf(stderr, "swell-validate: %s: %s\n", cl.scene.c_str(),
                     out["outcome"].get<std::string>().c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "swell-validate: %s\n", e.what());
        return 1;
    }
}
