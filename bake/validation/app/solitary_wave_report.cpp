// swell-validate solitary-wave: the run's crests, celerity and width against theory.
#include "case_reports.h"

#include "report_figures.h"
#include "report_files.h"

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/solitary_wave.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

json solitaryWave(const Scene& scene, const std::string& csv) {
    const SolitaryWaveReport r = runSolitaryWave(scene);
    json out = waveReportHead(scene, r.depth, r.height);
    out.update({{"stroke", r.stroke}, {"celerity_theory", r.theory.celerity}});
    addGaugeRun(out, r, r.gauges, csv, "eta");
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

} // namespace swell::bake
