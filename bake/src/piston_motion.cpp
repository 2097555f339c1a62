#include "swell/bake/piston_motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "swell/split_mix64.h"

namespace swell::bake {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

void require(bool ok, const char* field, const char* what) {
    if (!ok)
        throw std::invalid_argument(std::string("piston.") + field + ": " + what);
}

} // namespace

std::string_view toString(PistonKind kind) {
    switch (kind) {
    case PistonKind::Sinusoidal:
        return "sinusoidal";
    case PistonKind::Solitary:
        return "solitary";
    case PistonKind::Random:
        break;
    }
    return "random";
}

SolitaryWaveShape solitaryWaveShape(double height, double depth, double gravity) {
    if (!(height > 0.0) || !(depth > 0.0) || !(gravity > 0.0) || !std::isfinite(height) ||
        !std::isfinite(depth) || !std::isfinite(gravity)) {
        throw std::invalid_argument("solitaryWaveShape: height " + std::to_string(height) +
                                    " m, depth " + std::to_string(depth) + " m and gravity " +
                                    std::to_string(gravity) + " m/s^2 must be positive");
    }
    SolitaryWaveShape w;
    w.wavenumber = std::sqrt(3.0 * height / (4.0 * depth * depth * depth));
    w.celerity = std::sqrt(gravity * (depth + height));
    return w;
}

namespace {

/// Goring (1978): the piston's velocity at displacement x and time t, c eta / (h + eta).
struct GoringStroke {
    double H, h, k, c;
    double operator()(double t, double x) const {
        const double s = 1.0 / std::cosh(k * (c * t - x) - kSolitaryHalfWidth);
        const double eta = H * s * s;
        return c * eta / (h + eta);
    }
};

} // namespace

PistonMotion::PistonMotion(const PistonParams& p, double endTime) : m_params(p) {
    require(std::isfinite(p.rampTime) && p.rampTime >= 0.0, "ramp_time", "must be >= 0");
    if (p.kind == PistonKind::Solitary) {
        require(std::isfinite(p.depth) && p.depth > 0.0, "depth",
                "the still water must stand above the bed");
        require(std::isfinite(p.gravity) && p.gravity > 0.0, "gravity", "must be positive");
        require(std::isfinite(p.height) && p.height > 0.0, "height", "must be positive");
        require(p.height <= kSolitaryMaxHeightOverDepth * p.depth, "height",
                "must be at most 0.78 of the still-water depth: a higher solitary wave breaks "
                "(McCowan 1894)");
        const SolitaryWaveShape w = solitaryWaveShape(p.height, p.depth, p.gravity);
        const GoringStroke v{p.height, p.depth, w.wavenumber, w.celerity};
        // theta = k (c t - X) - 4 reaches 4 at t = (8 / k + S) / c; the span runs past it
        // (S is about sqrt(16 H h / 3) = 2.31 sqrt(H h)) and the loop stops where theta = 4.
        const double span =
            (2.0 * kSolitaryHalfWidth / w.wavenumber + 4.0 * std::sqrt(p.height * p.depth)) /
            w.celerity;
        constexpr int kSteps = 4000;
        const double dt = span / kSteps;
        double t = 0.0, x = 0.0;
        m_table.push_back({0.0, 0.0, v(0.0, 0.0)});
        for (int i = 0; i < kSteps; ++i) {
            const double k1 = m_table.back().velocity; // v(t, x), computed with the last row
            const double k2 = v(t + 0.5 * dt, x + 0.5 * dt * k1);
            const double k3 = v(t + 0.5 * dt, x + 0.5 * dt * k2);
            const double k4 = v(t + dt, x + dt * k3);
            x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            t += dt;
            m_table.push_back({t, x, v(t, x)});
            if (w.wavenumber * (w.celerity * t - x) >= 2.0 * kSolitaryHalfWidth)
                break;
        }
        return;
    }
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
    SplitMix64 rng(p.seed);
    for (double t = 0.0; t <= endTime;) {
        const double period = rng.uniform(p.periodMin, p.periodMax);
        const double stroke = rng.uniform(p.strokeMin, p.strokeMax);
        m_cycles.push_back({t, period, stroke});
        t += period;
    }
}

PistonState PistonMotion::at(double t) const {
    if (t <= 0.0)
        return {};
    if (m_params.kind == PistonKind::Solitary) {
        // No ramp: the stroke starts from 1.3e-3 of its largest velocity and ends at rest.
        if (t >= m_table.back().t)
            return {m_table.back().displacement, 0.0};
        const double dt = m_table[1].t - m_table[0].t;
        const auto i = std::min(static_cast<std::size_t>(t / dt), m_table.size() - 2);
        const Sample& a = m_table[i];
        const Sample& b = m_table[i + 1];
        // Cubic Hermite on the displacement, whose derivative is the tabulated velocity.
        const double u = (t - a.t) / dt;
        const double h00 = (1.0 + 2.0 * u) * (1.0 - u) * (1.0 - u), h10 = u * (1.0 - u) * (1.0 - u);
        const double h01 = u * u * (3.0 - 2.0 * u), h11 = u * u * (u - 1.0);
        const double x = h00 * a.displacement + h10 * dt * a.velocity + h01 * b.displacement +
                         h11 * dt * b.velocity;
        const double dh00 = 6.0 * u * (u - 1.0), dh10 = (1.0 - u) * (1.0 - 3.0 * u);
        const double dh01 = -dh00, dh11 = u * (3.0 * u - 2.0);
        const double vel = (dh00 * a.displacement + dh01 * b.displacement) / dt +
                           dh10 * a.velocity + dh11 * b.velocity;
        return {x, vel};
    }
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
