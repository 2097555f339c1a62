#include "swell/bake/validation/standing_wave.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/bake/probes.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {

StandingWaveTheory standingWaveTheory(double wavelength, double depth, double gravity) {
    if (!(wavelength > 0.0) || !(depth > 0.0) || !(gravity > 0.0))
        throw std::invalid_argument(fmt::format(
            "standingWaveTheory: wavelength {} m, depth {} m and gravity {} m/s^2 must be "
            "positive",
            wavelength, depth, gravity));
    StandingWaveTheory t;
    t.wavenumber = 2.0 * std::numbers::pi / wavelength;
    t.kh = t.wavenumber * depth;
    t.omega = std::sqrt(gravity * t.wavenumber * std::tanh(t.kh)); // Lamb art. 228
    t.period = 2.0 * std::numbers::pi / t.omega;
    return t;
}

SloshRecord analyseSlosh(std::span<const double> t, std::span<const double> eta) {
    if (t.size() != eta.size())
        throw std::invalid_argument(
            fmt::format("analyseSlosh: {} times but {} elevations", t.size(), eta.size()));
    SloshRecord r;
    if (t.empty())
        throw std::invalid_argument("analyseSlosh: an empty record");
    const double mean =
        std::accumulate(eta.begin(), eta.end(), 0.0) / static_cast<double>(eta.size());
    std::vector<std::size_t> at; // sample index just after each crossing
    for (std::size_t k = 1; k < t.size(); ++k) {
        const double a = eta[k - 1] - mean, b = eta[k] - mean;
        if (a < 0.0 && b >= 0.0) {
            r.crossings.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-a) / (b - a));
            at.push_back(k);
        }
    }
    if (r.crossings.size() < 3)
        throw std::invalid_argument(fmt::format(
            "analyseSlosh: the record crosses its mean upwards {} times; two whole periods "
            "need 3",
            r.crossings.size()));
    r.period =
        (r.crossings.back() - r.crossings.front()) / static_cast<double>(r.crossings.size() - 1);
    for (std::size_t c = 0; c + 1 < at.size(); ++c) {
        const auto [lo, hi] = std::minmax_element(eta.begin() + static_cast<long>(at[c]),
                                                  eta.begin() + static_cast<long>(at[c + 1]));
        r.amplitudes.push_back(0.5 * (*hi - *lo));
    }
    // Least-squares slope of ln(amplitude) against the period's index (two or more periods).
    std::vector<double> index, logAmplitude;
    for (std::size_t k = 0; k < r.amplitudes.size(); ++k) {
        index.push_back(static_cast<double>(k));
        logAmplitude.push_back(std::log(std::max(r.amplitudes[k], 1e-300)));
    }
    r.decayPerPeriod = 1.0 - std::exp(lineSlope(index, logAmplitude, "analyseSlosh: one period"));
    return r;
}

StandingWaveReport runStandingWave(const Scene& scene) {
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the standing-wave check needs a tank");
    const Box tank = *scene.geometry.tank;
    const Box water = scene.geometry.water.at(0);
    const CosineTop top = waterTop(scene.geometry, 0);
    if (top.amplitude == 0.0)
        throw SceneError("geometry.water[0].surface",
                         "missing: the standing-wave check needs the water's cosine top");
    const double l0 = scene.geometry.particleSpacing;
    StandingWaveReport r;
    r.theory = standingWaveTheory(top.wavelength, water.height(), scene.physics.gravity);
    r.gauges = {tank.x0 + l0, tank.x1 - l0};
    static_cast<GaugeRecords&>(r) = recordGauges(scene, water.y1, r.gauges);
    if (r.outcome != kStable)
        return r;
    const double share = 1.0 / static_cast<double>(r.gauges.size());
    for (std::size_t g = 0; g < r.gauges.size(); ++g) {
        for (std::size_t k = 0; k < r.times.size(); ++k) {
            if (!std::isfinite(r.elevations[g][k]))
                throw std::runtime_error(
                    fmt::format("standing wave: the gauge at x = {} m ran dry at t = {} s",
                                r.gauges[g], r.times[k]));
        }
        try {
            r.records.push_back(analyseSlosh(r.times, r.elevations[g]));
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(
                fmt::format("standing wave: the gauge at x = {} m: {}", r.gauges[g], e.what()));
        }
        const SloshRecord& rec = r.records.back();
        r.period += share * rec.period;
        r.decayPerPeriod += share * rec.decayPerPeriod;
        r.firstAmplitudeOverTheory +=
            share * rec.amplitudes.front() /
            std::abs(top.amplitude * std::cos(r.theory.wavenumber * (r.gauges[g] - water.x0)));
    }
    r.periodError = r.period / r.theory.period - 1.0;
    return r;
}

} // namespace swell::bake::validation
