#include "swell/bake/piston_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "split_mix64.h"

namespace swell::bake {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

void require(bool ok, const char* field, const char* what) {
    if (!ok)
        throw std::invalid_argument(std::string("piston.") + field + ": " + what);
}

} // namespace

std::string_view toString(PistonKind kind) {
    return kind == PistonKind::Sinusoidal ? "sinusoidal" : "random";
}

PistonMotion::PistonMotion(const PistonParams& p, double endTime) : m_params(p) {
    require(std::isfinite(p.rampTime) && p.rampTime >= 0.0, "ramp_time", "must be >= 0");
    if (p.kind == PistonKind::Sinusoidal) {
        require(std::isfinite(p.period) && p.period > 0.0, "period", "must be positive");
        require(std::isfinite(p.stroke) && p.stroke >= 0.0, "stroke", "must be >= 0");
        return;
    }
    require(std::isfinite(p.periodMin) && p.periodMin > 0.0, "period_min", "must be positive");
    require(std::isfinite(p.periodMax) && p.periodMax >= p.periodMin, "period_max",
            "must be >= period_min");
    require(std::isfinite(p.strokeMin) && p.strokeMin >= 0.0, "stroke_min", "must be >= 0");
    require(std::isfinite(p.strokeMax) && p.strokeMax >= p.strokeMin, "stroke_max",
            "must be >= stroke_min");
    // Every cycle is drawn up front: a bounded count (the shortest period over the run).
    require(endTime / p.periodMin <= static_cast<double>(kMaxPistonCycles), "period_min",
            "too short for the run: end_time / period_min exceeds 1,000,000 cycles");
    std::uint64_t state = p.seed;
    for (double t = 0.0; t <= endTime;) {
        const double period = uniform(state, p.periodMin, p.periodMax);
        const double stroke = uniform(state, p.strokeMin, p.strokeMax);
        m_cycles.push_back({t, period, stroke});
        t += period;
    }
}

PistonState PistonMotion::at(double t) const {
    if (t <= 0.0)
        return {};
    PistonState s;
    if (m_params.kind == PistonKind::Sinusoidal) {
        const double w = kTwoPi / m_params.period;
        s.displacement = 0.5 * m_params.stroke * std::sin(w * t);
        s.velocity = 0.5 * m_params.stroke * w * std::cos(w * t);
    } else if (!m_cycles.empty()) {
        // Last cycle starting at or before t (cycles are sorted by start).
        auto it = std::upper_bound(m_cycles.begin(), m_cycles.end(), t,
                                   [](double v, const Cycle& c) { return v < c.start; });
        const Cycle& c = *std::prev(it);
        const double w = kTwoPi / c.period;
        const double tau = t - c.start;
        if (tau < c.period) { // beyond the drawn cycles the piston rests
            s.displacement = 0.5 * c.stroke * (1.0 - std::cos(w * tau));
            s.velocity = 0.5 * c.stroke * w * std::sin(w * tau);
        }
    }
    if (m_params.rampTime > 0.0 && t < m_params.rampTime) {
        const double a = std::numbers::pi / m_params.rampTime;
        const double r = 0.5 * (1.0 - std::cos(a * t));
        const double dr = 0.5 * a * std::sin(a * t);
        s.velocity = r * s.velocity + dr * s.displacement; // product rule
        s.displacement *= r;
    }
    return s;
}

} // namespace swell::bake
