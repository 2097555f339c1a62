#include "swell/cache/synthetic.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

namespace swell::cache {
namespace {

/// SplitMix64: a fixed, portable generator (same bits on every machine).
std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/// Uniform in [0, 1) from a hash of (seed, a, b).
double uniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    return static_cast<double>(splitmix(seed ^ splitmix(a * 0x100000001b3ULL + b)) >> 11) *
           0x1.0p-53;
}

} // namespace

Domain syntheticDomain(const SyntheticWave& w) {
    const float margin = 0.05f * w.length;
    return {-margin, 0.0f, w.length + margin, w.depth + 4.0f * w.amplitude + margin};
}

double syntheticHeight(const SyntheticWave& w, double x, double t) {
    const double k = 2.0 * std::numbers::pi / w.wavelength;
    const double om = 2.0 * std::numbers::pi / w.period;
    const double ph = k * x - om * t;
    // A Stokes-like second harmonic makes crests sharper than troughs.
    return w.depth + w.amplitude * (std::cos(ph) + 0.2 * std::cos(2.0 * ph));
}

Frame syntheticFrame(const SyntheticWave& w, std::size_t index) {
    Frame f;
    const double t = static_cast<double>(index) * w.frameTime;
    const double spacing = w.surfaceCount > 1 ? w.length / (w.surfaceCount - 1) : 0.0;
    f.surface.reserve(w.surfaceCount * 2);
    for (std::size_t i = 0; i < w.surfaceCount; ++i) {
        const double jitter = (uniform(w.seed, index, i) - 0.5) * 0.5 * spacing;
        const double x = std::clamp(i * spacing + jitter, 0.0, static_cast<double>(w.length));
        f.surface.push_back(static_cast<float>(x));
        f.surface.push_back(static_cast<float>(syntheticHeight(w, x, t)));
    }
    f.splash.reserve(w.splashCount * 4);
    for (std::size_t i = 0; i < w.splashCount; ++i) {
        const double x = uniform(w.seed ^ 0x5a5a, index, 2 * i) * w.length;
        const double lift = (0.5 + uniform(w.seed ^ 0x5a5a, index, 2 * i + 1)) * w.amplitude;
        f.splash.push_back(static_cast<float>(x));
        f.splash.push_back(static_cast<float>(syntheticHeight(w, x, t) + lift));
        f.splash.push_back(static_cast<float>(w.wavelength / w.period));
        f.splash.push_back(static_cast<float>(lift / w.period));
    }
    return f;
}

nlohmann::json syntheticReplayJson(const SyntheticWave& w) {
    // The surface particles' spacing; a wave of fewer than two particles has none, so it
    // records the whole length (the replay needs a positive l0 for its envelope bins).
    const double spacing = static_cast<double>(w.length) /
                           static_cast<double>(std::max<std::size_t>(w.surfaceCount, 2) - 1);
    return nlohmann::json{{"water_x_min", 0.0},
                          {"water_x_max", static_cast<double>(w.length)},
                          {"still_water_level", static_cast<double>(w.depth)},
                          {"particle_spacing", spacing},
                          {"steady_start_s", 0.0},
                          {"steady_reason", "synthetic travelling wave: steady from the start"}};
}

} // namespace swell::cache
