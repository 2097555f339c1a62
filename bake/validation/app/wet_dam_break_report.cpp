// swell-validate wet-dam-break: the run's depths and bore against Stoker's solution.
#include "case_reports.h"

#include "report_figures.h"
#include "report_files.h"

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/wet_dam_break.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

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
             {"compared_from", t.comparedFrom()}};
    addGaugeRun(out, r, r.gauges, csv, "h");
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

} // namespace swell::bake
