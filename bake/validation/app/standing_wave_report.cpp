// swell-validate standing-wave: the run's period and decay at the side walls.
#include "case_reports.h"

#include <cstddef>

#include "report_figures.h"
#include "report_files.h"

#include "swell/bake/geometry.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/standing_wave.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {

json standingWave(const Scene& scene, const std::string& csv) {
    const StandingWaveReport r = runStandingWave(scene);
    const CosineTop top = waterTop(scene.geometry, 0);
    json out{{"scene", scene.name},
             {"l0", scene.geometry.particleSpacing},
             {"depth", scene.geometry.water.front().height()},
             {"amplitude", top.amplitude},
             {"wavelength", top.wavelength},
             {"kh", r.theory.kh},
             {"period_theory", r.theory.period}};
    addGaugeRun(out, r, r.gauges);
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

} // namespace swell::bake
