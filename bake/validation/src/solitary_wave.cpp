#include "swell/bake/validation/solitary_wave.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/bake/probes.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {
namespace {

/// eta / A = sech^2(3) = 0.99 % at the front the windows use.
constexpr double kFrontTheta = 3.0;

/// The time a record of Boussinesq's wave of crest A stays above A / 2 (s):
/// sech^2(theta) = 1/2 at theta = acosh(sqrt 2), so 2 acosh(sqrt 2) / (k c).
double halfHeightDuration(double amplitude, double depth, double gravity) {
    const SolitaryWaveShape w = solitaryWaveShape(amplitude, depth, gravity);
    return 2.0 * std::acosh(std::sqrt(2.0)) / (w.wavenumber * w.celerity);
}

} // namespace

std::vector<CrestWindow> solitaryCrestWindows(const PistonParams& piston, double x0, double x1,
                                              std::span<const double> gauges) {
    const SolitaryWaveShape w = solitaryWaveShape(piston.height, piston.depth, piston.gravity);
    const double lead = kSolitaryHalfWidth / w.wavenumber;          // crest at x0 + c t - lead
    const double front = kFrontTheta / (w.wavenumber * w.celerity); // front ahead of the crest
    std::vector<CrestWindow> out;
    for (double x : gauges) {
        if (!(x > x0 && x < x1))
            throw std::invalid_argument(fmt::format(
                "gauge x = {} m is not between the piston ({} m) and the far wall ({} m)", x, x0,
                x1));
        CrestWindow c;
        c.stillTo = (x - x0 + lead) / w.celerity - front;
        c.stillFrom = 0.5 * c.stillTo;
        if (!(c.stillTo > 0.0))
            throw std::invalid_argument(fmt::format(
                "gauge x = {} m is too near the piston: the wave's front is there from the start",
                x));
        c.until = (2.0 * (x1 - x0) - (x - x0) + lead) / w.celerity - front;
        out.push_back(c);
    }
    return out;
}

SolitaryWaveCheck analyseSolitaryWave(const PistonParams& piston, std::span<const double> gauges,
                                      std::span<const double> times,
                                      const std::vector<std::vector<double>>& elevations,
                                      std::span<const CrestWindow> windows) {
    if (gauges.size() < 2 || elevations.size() != gauges.size() || windows.size() != gauges.size())
        throw std::invalid_argument(fmt::format(
            "analyseSolitaryWave: {} gauges, {} records and {} windows: need two or more, one "
            "record and window each",
            gauges.size(), elevations.size(), windows.size()));
    SolitaryWaveCheck out;
    std::vector<double> crestTimes, xs;
    double amplitudeSum = 0.0;
    for (std::size_t g = 0; g < gauges.size(); ++g) {
        const std::vector<double>& eta = elevations[g];
        const CrestWindow& win = windows[g];
        if (eta.size() != times.size())
            throw std::invalid_argument(
                fmt::format("analyseSolitaryWave: gauge x = {} m: {} samples for {} times",
                            gauges[g], eta.size(), times.size()));
        SolitaryCrest c;
        c.x = gauges[g];
        double still = 0.0;
        std::size_t stillCount = 0, peak = times.size(), last = 0;
        for (std::size_t k = 0; k < times.size() && times[k] <= win.until; ++k) {
            if (!std::isfinite(eta[k]))
                throw std::invalid_argument(fmt::format(
                    "analyseSolitaryWave: gauge x = {} m is dry at t = {} s", c.x, times[k]));
            if (times[k] >= win.stillFrom && times[k] <= win.stillTo) {
                still += eta[k];
                ++stillCount;
            }
            if (peak == times.size() || eta[k] > eta[peak])
                peak = k;
            last = k;
        }
        if (stillCount == 0)
            throw std::invalid_argument(fmt::format(
                "analyseSolitaryWave: gauge x = {} m has no sample in its still window [{}, {}] s",
                c.x, win.stillFrom, win.stillTo));
        c.stillLevel = still / static_cast<double>(stillCount);
        if (peak == 0 || peak >= last)
            throw std::invalid_argument(fmt::format(
                "analyseSolitaryWave: gauge x = {} m: no crest passed before t = {} s (the record "
                "is highest at {} s)",
                c.x, win.until, peak < times.size() ? times[peak] : 0.0));
        const double raw = eta[peak] - c.stillLevel;
        if (!(raw > 0.0))
            throw std::invalid_argument(fmt::format(
                "analyseSolitaryWave: gauge x = {} m never rises above its still level", c.x));
        const double eighth = halfHeightDuration(raw, piston.depth, piston.gravity) / 8.0;
        std::size_t lo = peak, hi = peak;
        while (lo > 0 && times[lo - 1] >= times[peak] - eighth)
            --lo;
        while (hi < last && times[hi + 1] <= times[peak] + eighth)
            ++hi;
        const auto [tc, top] = parabolaTop(times, eta, lo, hi, peak);
        c.time = tc;
        c.amplitude = top - c.stillLevel;
        // The A / 2 crossings on either side, interpolated.
        const double half = c.stillLevel + 0.5 * c.amplitude;
        const auto [front, back] =
            crossingsAround(times, eta, times.front(), times[last], tc, half);
        if (std::isnan(front) || std::isnan(back))
            throw std::invalid_argument(fmt::format(
                "analyseSolitaryWave: gauge x = {} m stays above half its crest on one side "
                "inside [0, {}] s",
                c.x, win.until));
        const double width = back - front;
        c.widthError = width / halfHeightDuration(c.amplitude, piston.depth, piston.gravity) - 1.0;
        crestTimes.push_back(c.time);
        xs.push_back(c.x);
        amplitudeSum += c.amplitude;
        out.meanWidthError += c.widthError / static_cast<double>(gauges.size());
        out.crests.push_back(c);
    }
    std::sort(out.crests.begin(), out.crests.end(),
              [](const SolitaryCrest& p, const SolitaryCrest& q) { return p.x < q.x; });
    out.celerity = lineSlope(crestTimes, xs, "analyseSolitaryWave: the crest times");
    const double meanAmplitude = amplitudeSum / static_cast<double>(gauges.size());
    out.celerityError =
        out.celerity / std::sqrt(piston.gravity * (piston.depth + meanAmplitude)) - 1.0;
    out.firstAmplitudeOverHeight = out.crests.front().amplitude / piston.height;
    out.decayTotal = 1.0 - out.crests.back().amplitude / out.crests.front().amplitude;
    return out;
}

SolitaryWaveReport runSolitaryWave(const Scene& scene) {
    if (!scene.piston || scene.piston->kind != PistonKind::Solitary)
        throw SceneError("piston.kind", "the solitary-wave check needs a solitary piston");
    if (scene.output.gauges.size() < 2)
        throw SceneError("output.gauges", "the solitary-wave check needs two or more gauges");
    const Box tank = *scene.geometry.tank; // a piston needs a tank (loadScene)
    const PistonParams& piston = *scene.piston;
    SolitaryWaveReport r;
    r.height = piston.height;
    r.depth = piston.depth;
    r.theory = solitaryWaveShape(piston.height, piston.depth, piston.gravity);
    r.stroke = PistonMotion(piston, scene.run.endTime).at(scene.run.endTime + 1e9).displacement;
    r.gauges = scene.output.gauges;
    try {
        r.windows = solitaryCrestWindows(piston, tank.x0, tank.x1, r.gauges);
    } catch (const std::invalid_argument& e) {
        throw SceneError("output.gauges", e.what());
    }
    static_cast<GaugeRecords&>(r) = recordGauges(scene, stillWaterLevel(scene), r.gauges);
    if (r.outcome != kStable)
        return r;
    try {
        r.check = analyseSolitaryWave(piston, r.gauges, r.times, r.elevations, r.windows);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(fmt::format("solitary wave: {}", e.what()));
    }
    return r;
}

} // namespace swell::bake::validation
