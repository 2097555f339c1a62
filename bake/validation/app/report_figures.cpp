#include "report_figures.h"

#include <cmath>

using nlohmann::json;

namespace swell::bake {

json finiteOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

double usPerParticleStep(double seconds, long steps, std::size_t particles) {
    return steps > 0 ? 1e6 * seconds / (static_cast<double>(steps) * static_cast<double>(particles))
                     : 0.0;
}

void addRunCost(json& out, const GaugeRecords& r, std::size_t particles) {
    out["steps"] = r.steps;
    out["ppe_iterations_mean"] = r.ppeIterationsMean;
    out["solver_seconds"] = r.solverSeconds;
    out["us_per_particle_step"] = usPerParticleStep(r.solverSeconds, r.steps, particles);
}

json waveReportHead(const Scene& scene, double depth, double height) {
    return {{"scene", scene.name},
            {"l0", scene.geometry.particleSpacing},
            {"depth", depth},
            {"height", height},
            {"height_over_depth", height / depth}};
}

void addGaugeRun(nlohmann::json& out, const GaugeRecords& r, const std::vector<double>& gauges) {
    out["gauges"] = gauges;
    out["particles"] = r.particles;
    out["water"] = r.water;
    out["outcome"] = r.outcome;
}

} // namespace swell::bake
