#include "swell/bake/probes.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "swell/bake/classification.h"

namespace swell::bake {

ProbeSample sampleProbes(const Particles& P, double time, const ProbeParams& par) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    ProbeSample s;
    s.time = time;
    double front = -std::numeric_limits<double>::infinity();
    std::vector<double> top(par.gauges.size(), -std::numeric_limits<double>::infinity());
    const double half = par.spacing;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        if (P.n[i] < par.splashRatio * par.n0)
            continue; // splash (eq. (4)) is not part of the body
        front = std::max(front, P.x[i]);
        for (std::size_t g = 0; g < par.gauges.size(); ++g) {
            if (std::abs(P.x[i] - par.gauges[g]) <= half)
                top[g] = std::max(top[g], P.y[i]);
        }
    }
    s.frontX = std::isfinite(front) ? front : kNaN;
    s.elevations.resize(par.gauges.size());
    for (std::size_t g = 0; g < top.size(); ++g) {
        s.elevations[g] =
            std::isfinite(top[g]) ? top[g] + 0.5 * par.spacing - par.stillWaterLevel : kNaN;
    }
    return s;
}

std::string probeCsvHeader(std::span<const double> gauges) {
    std::string h = "time,front_x";
    for (double x : gauges)
        h += fmt::format(",gauge_{:g}", x);
    return h;
}

std::string probeCsvRow(const ProbeSample& s) {
    const auto num = [](double v) {
        return std::isnan(v) ? std::string("nan") : fmt::format("{:.9g}", v);
    };
    std::string r = num(s.time);
    r += ',';
    r += num(s.frontX);
    for (double e : s.elevations) {
        r += ',';
        r += num(e);
    }
    return r;
}

} // namespace swell::bake
