// swell-validate dam-break: the run's surge front against Martin & Moyce (1952).
#include "case_reports.h"

#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "report_files.h"

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/dam_break_run.h"
#include "swell/bake/validation/validation.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

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

} // namespace swell::bake
