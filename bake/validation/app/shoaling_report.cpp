// swell-validate shoaling: the run's elevations up the beach against Grilli et al. (1994).
#include "case_reports.h"

#include "report_figures.h"
#include "report_files.h"

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/shoaling.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

json shoaling(const Scene& scene, const std::string& csv) {
    const ShoalingReport r = runShoaling(scene);
    json out = waveReportHead(scene, r.depth, r.height);
    out["gravity"] = scene.physics.gravity;
    out["toe"] = r.toe;
    out["slope"] = r.slope;
    out["still_window"] = {r.stillFrom, r.stillTo};
    addGaugeRun(out, r, r.gauges, csv, "eta");
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
        out.update({{"gauge_records", gauges},
                    {"clock_offset", c.clockOffset},
                    {"incident_crest_error", c.incidentCrestError},
                    {"crest_error_worst", c.crestErrorWorst},
                    {"amplification_error_worst", c.amplificationErrorWorst},
                    {"mean_abs_error_over_h0_worst", c.meanAbsErrorWorst},
                    {"travel_time_error", c.travelTimeError}});
    }
    addRunCost(out, r, r.particles);
    return out;
}

} // namespace swell::bake
