// swell-validate lobovsky: the run's gauge heights and far-wall pressure against the records.
#include "case_reports.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include <fmt/format.h>

#include "report_figures.h"
#include "report_files.h"

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/lobovsky2014.h"
#include "swell/bake/validation/lobovsky_run.h"
#include "swell/bake/validation/validation.h"
#include "swell/bake/validation/wall_pressure.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {
namespace {

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

} // namespace

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

} // namespace swell::bake
