#include "swell/bake/validation/wet_dam_break.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/bake/probes.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Root of an increasing f on [lo, hi] with f(lo) < 0 <= f(hi), by bisection to round-off.
template <class F> double bisect(F f, double lo, double hi) {
    for (int k = 0; k < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Depth behind a bore of speed S running into still water of depth h1 (m): the conjugate
/// depth of the hydraulic jump, h1 (sqrt(1 + 8 S^2 / (g h1)) - 1) / 2 (mass and momentum
/// across it, Stoker 1957 Sec. 10.6).
double depthBehindBore(double s, double h1, double g) {
    return 0.5 * h1 * (std::sqrt(1.0 + 8.0 * s * s / (g * h1)) - 1.0);
}

/// Speed (m/s, positive, towards -x) of the bore that the far wall sends back when theory's
/// bore reaches it: it brings the state (h2, u2) to rest at depth h3, where mass and momentum
/// across it give u2 = (h3 - h2) sqrt(g (h3 + h2) / (2 h2 h3)), and it moves at
/// h2 u2 / (h3 - h2).
double reflectedBoreSpeed(const StokerDamBreak& t) {
    const auto inflow = [&](double h3) {
        return (h3 - t.h2) * std::sqrt(t.gravity * (h3 + t.h2) / (2.0 * t.h2 * h3)) - t.u2;
    };
    double hi = 2.0 * t.h2;
    while (inflow(hi) < 0.0)
        hi *= 2.0;
    const double h3 = bisect(inflow, t.h2, hi);
    return t.h2 * t.u2 / (h3 - t.h2);
}

} // namespace

StokerDamBreak stokerDamBreak(double h0, double h1, double gravity) {
    if (!std::isfinite(h0) || !std::isfinite(h1) || !std::isfinite(gravity) || !(h1 > 0.0) ||
        !(h1 < h0) || !(gravity > 0.0))
        throw std::invalid_argument(fmt::format(
            "stokerDamBreak: needs 0 < h1 < h0 and g > 0, got h0 = {} m, h1 = {} m, g = {} m/s^2",
            h0, h1, gravity));
    StokerDamBreak t;
    t.h0 = h0;
    t.h1 = h1;
    t.gravity = gravity;
    t.c0 = std::sqrt(gravity * h0);
    // The state behind the bore lies on the fan's Riemann invariant u + 2 c = 2 c0 and on the
    // bore's Rankine-Hugoniot curve u2 = S (1 - h1 / h2(S)); their difference grows with S from
    // 2 (c0 - c1) > 0 at S = c1 = sqrt(g h1) (no bore).
    const auto excess = [&](double s) {
        const double h2 = depthBehindBore(s, h1, gravity);
        return s * (1.0 - h1 / h2) + 2.0 * std::sqrt(gravity * h2) - 2.0 * t.c0;
    };
    double hi = 2.0 * t.c0;
    while (excess(hi) < 0.0)
        hi *= 2.0;
    t.boreSpeed = bisect(excess, std::sqrt(gravity * h1), hi);
    t.h2 = depthBehindBore(t.boreSpeed, h1, gravity);
    t.u2 = t.boreSpeed * (1.0 - h1 / t.h2);
    t.c2 = std::sqrt(gravity * t.h2);
    return t;
}

double StokerDamBreak::depth(double dx, double t) const {
    if (!(t > 0.0))
        return dx < 0.0 ? h0 : h1;
    const double xi = dx / t;
    if (xi <= -c0)
        return h0;
    if (xi <= u2 - c2) // the centred fan, u = 2 (c0 + xi) / 3, c = (2 c0 - xi) / 3
        return (2.0 * c0 - xi) * (2.0 * c0 - xi) / (9.0 * gravity);
    return xi <= boreSpeed ? h2 : h1;
}

bool StokerDamBreak::behindBore(double dx, double t) const {
    if (!(t > 0.0))
        return false;
    const double xi = dx / t;
    return xi > u2 - c2 && xi <= boreSpeed;
}

double StokerDamBreak::comparedFrom() const {
    return kStokerFromTimes * std::sqrt(h0 / gravity);
}

std::vector<std::pair<double, double>> stokerWindows(const StokerDamBreak& theory, double xb,
                                                     double x0, double x1, double tEnd,
                                                     std::span<const double> gauges) {
    const double from = theory.comparedFrom();
    const double back = (x0 - xb) / theory.c0; // the fan's head at the back wall
    const double forward = std::max(theory.c0, theory.u2 + theory.c2);
    const double far = (x1 - x0) / theory.boreSpeed; // the bore at the far wall
    const double returning = reflectedBoreSpeed(theory);
    std::vector<std::pair<double, double>> out;
    for (double x : gauges) {
        if (!(x > xb && x < x1))
            throw std::invalid_argument(fmt::format(
                "stokerWindows: gauge x = {} m is not inside the tank ({}, {}) m", x, xb, x1));
        const double until =
            std::min({tEnd, back + (x - xb) / forward, far + (x1 - x) / returning});
        if (!(until > from))
            throw std::invalid_argument(
                fmt::format("stokerWindows: gauge x = {} m has nothing to compare: its window "
                            "would close at {:.3g} s, before it opens at {:.3g} s",
                            x, until, from));
        out.emplace_back(from, until);
    }
    return out;
}

WetDamBreakCheck analyseWetDamBreak(const StokerDamBreak& theory, double x0,
                                    std::span<const double> gauges, std::span<const double> times,
                                    const std::vector<std::vector<double>>& depths,
                                    std::span<const std::pair<double, double>> windows) {
    if (depths.size() != gauges.size() || windows.size() != gauges.size())
        throw std::invalid_argument(
            fmt::format("analyseWetDamBreak: {} gauges, {} records and {} windows", gauges.size(),
                        depths.size(), windows.size()));
    const double settle = theory.comparedFrom();
    const double boreLevel = 0.5 * (theory.h1 + theory.h2);
    WetDamBreakCheck out;
    std::vector<double> arrivals, xs;
    double plateauSum = 0.0;
    std::size_t plateauGauges = 0;
    for (std::size_t g = 0; g < gauges.size(); ++g) {
        const std::vector<double>& h = depths[g];
        if (h.size() != times.size())
            throw std::invalid_argument(
                fmt::format("analyseWetDamBreak: gauge x = {} m has {} samples for {} times",
                            gauges[g], h.size(), times.size()));
        WetDamBreakGauge r;
        r.x = gauges[g];
        std::tie(r.from, r.until) = windows[g];
        const double dx = r.x - x0;
        r.boreArrivalTheory = dx >= 0.0 ? dx / theory.boreSpeed : kNaN;
        r.boreArrival = kNaN;
        double absSum = 0.0, signedSum = 0.0, plateau = 0.0;
        std::size_t n = 0, nPlateau = 0;
        for (std::size_t k = 0; k < times.size() && times[k] <= r.until; ++k) {
            const double t = times[k];
            if (dx > 0.0 && std::isnan(r.boreArrival) && k > 0 && h[k - 1] < boreLevel &&
                h[k] >= boreLevel)
                r.boreArrival =
                    times[k - 1] + (t - times[k - 1]) * (boreLevel - h[k - 1]) / (h[k] - h[k - 1]);
            if (t < r.from)
                continue;
            if (std::isnan(h[k]))
                throw std::invalid_argument(
                    fmt::format("analyseWetDamBreak: gauge x = {} m is dry at t = {} s", r.x, t));
            const double d = (h[k] - theory.depth(dx, t)) / theory.h0;
            absSum += std::abs(d);
            signedSum += d;
            ++n;
            if (theory.behindBore(dx, t) && t >= r.boreArrivalTheory + settle) {
                plateau += h[k];
                ++nPlateau;
            }
        }
        if (n == 0)
            throw std::invalid_argument(
                fmt::format("analyseWetDamBreak: gauge x = {} m has no sample in [{}, {}] s", r.x,
                            r.from, r.until));
        r.meanAbsErrorOverH0 = absSum / static_cast<double>(n);
        r.meanSignedErrorOverH0 = signedSum / static_cast<double>(n);
        r.plateauDepthOverTheory =
            nPlateau > 0 ? plateau / static_cast<double>(nPlateau) / theory.h2 : kNaN;
        if (nPlateau > 0) {
            plateauSum += r.plateauDepthOverTheory;
            ++plateauGauges;
        }
        // The bore speed is read where theory's bore passes inside the window, so the flow is
        // long against its depth there too.
        if (r.boreArrivalTheory >= r.from && r.boreArrivalTheory <= r.until &&
            !std::isnan(r.boreArrival)) {
            arrivals.push_back(r.boreArrival);
            xs.push_back(r.x);
        }
        out.meanAbsErrorOverH0Worst = std::max(out.meanAbsErrorOverH0Worst, r.meanAbsErrorOverH0);
        out.gauges.push_back(r);
    }
    if (arrivals.size() < 2)
        throw std::invalid_argument(fmt::format(
            "analyseWetDamBreak: {} gauge(s) saw the bore inside their window; its speed needs 2",
            arrivals.size()));
    out.boreGauges = arrivals.size();
    out.boreSpeed = lineSlope(arrivals, xs, "analyseWetDamBreak: the bore's arrival times");
    out.boreSpeedError = out.boreSpeed / theory.boreSpeed - 1.0;
    out.plateauDepthError =
        plateauGauges > 0 ? plateauSum / static_cast<double>(plateauGauges) - 1.0 : kNaN;
    return out;
}

WetDamBreakReport runWetDamBreak(const Scene& scene) {
    if (scene.piston)
        throw SceneError("piston", "the wet dam-break check runs still water, without a piston");
    if (scene.recycling)
        throw SceneError("recycling", "the wet dam-break check runs a closed tank");
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the wet dam-break check needs a tank");
    const Box tank = *scene.geometry.tank;
    const std::vector<Box>& water = scene.geometry.water;
    const double tol = 1e-9 * std::max(1.0, tank.width());
    const auto on = [&](double a, double b) { return std::abs(a - b) <= tol; };
    if (water.size() != 2 || !on(water[0].x0, tank.x0) || !on(water[0].y0, tank.y0) ||
        !on(water[1].x0, water[0].x1) || !on(water[1].x1, tank.x1) || !on(water[1].y0, tank.y0) ||
        !(water[1].y1 < water[0].y1) || waterTop(scene.geometry, 0).amplitude != 0.0 ||
        waterTop(scene.geometry, 1).amplitude != 0.0 || !scene.geometry.solids.empty())
        throw SceneError("geometry.water",
                         "the wet dam-break check needs two flat water rectangles on the tank's "
                         "bed and no solids: the reservoir from the back wall to the gate, then "
                         "a lower layer from the gate to the front wall");
    if (scene.output.gauges.size() < 2)
        throw SceneError("output.gauges", "the wet dam-break check needs two or more gauges");
    if (!(scene.physics.gravity > 0.0))
        throw SceneError("physics.gravity", "the wet dam-break check needs gravity");
    WetDamBreakReport r;
    r.gate = water[0].x1;
    r.theory = stokerDamBreak(water[0].height(), water[1].height(), scene.physics.gravity);
    try {
        r.windows = stokerWindows(r.theory, tank.x0, r.gate, tank.x1, scene.run.endTime,
                                  scene.output.gauges);
    } catch (const std::invalid_argument& e) {
        throw SceneError("output.gauges", e.what());
    }
    r.gauges = scene.output.gauges;
    // Elevations from the bed are depths.
    static_cast<GaugeRecords&>(r) = recordGauges(scene, tank.y0, r.gauges);
    if (r.outcome != kStable)
        return r;
    try {
        r.check = analyseWetDamBreak(r.theory, r.gate, r.gauges, r.times, r.elevations, r.windows);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(fmt::format("wet dam break: {}", e.what()));
    }
    return r;
}

} // namespace swell::bake::validation
