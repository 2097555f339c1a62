#include "swell/bake/validation/regular_wave.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/bake/validation/validation.h"

namespace swell::bake::validation {
namespace {

const PistonParams& sinusoidalPiston(const Scene& scene) {
    if (!scene.piston || scene.piston->kind != PistonKind::Sinusoidal) {
        throw SceneError("piston.kind", "the regular-wave check needs a sinusoidal piston");
    }
    if (!scene.geometry.tank)
        throw SceneError("geometry.tank", "the regular-wave check needs a tank");
    if (scene.output.gauges.size() < 2) {
        throw SceneError("output.gauges", "the regular-wave check needs at least two gauges");
    }
    return *scene.piston;
}

/// Phase lag (rad, in [0, 2 pi)) of a gauge with fit phase `to` behind one with `from`: the
/// wave reaches the farther gauge later.
double phaseLag(double from, double to) {
    const double twoPi = 2.0 * std::numbers::pi;
    return std::fmod(to - from + 2.0 * twoPi, twoPi);
}

constexpr const char* kDistinctGauges = "the regular-wave check needs gauges at distinct x";

LinearPistonWave theoryOf(const Scene& scene, double& depth) {
    const PistonParams& p = sinusoidalPiston(scene);
    depth = stillWaterLevel(scene) - scene.geometry.tank->y0;
    return linearPistonWave(p.stroke, p.period, depth, scene.physics.gravity);
}

/// The distance from the paddle's rest position to a gauge at x by way of the far wall: what
/// the wave reflected there has travelled when it reaches the gauge.
double mirrorDistance(const Box& tank, double x) {
    return 2.0 * (tank.x1 - tank.x0) - (x - tank.x0);
}

/// The window of a gauge at x (WaveWindow's rule for that one gauge).
WaveWindow gaugeWindow(const Scene& scene, double h, double x) {
    const PistonParams& p = *scene.piston;
    // Group velocity of linear theory: c_g = c / 2 (1 + 2kh / sinh 2kh), c = omega / k.
    const double cg = groupVelocity(2.0 * std::numbers::pi / p.period, h, scene.physics.gravity);
    const Box& tank = *scene.geometry.tank;
    WaveWindow win;
    win.start = p.rampTime + (x - tank.x0) / cg + p.period;
    const double reflected = mirrorDistance(tank, x) / cg;
    win.end = std::min(scene.run.endTime, reflected);
    return win;
}

/// 2 x harmonicAmplitudeStandardError, or NaN where a window does not allow one (too few or
/// unevenly spaced samples): the height is fitted all the same, and only its standard error is
/// missing.
double heightStandardError(std::span<const double> t, std::span<const double> v, double omega) {
    try {
        return 2.0 * harmonicAmplitudeStandardError(t, v, omega);
    } catch (const std::invalid_argument&) {
        return std::numeric_limits<double>::quiet_NaN();
    }
}

} // namespace

WaveWindow regularWaveWindow(const Scene& scene) {
    double h = 0.0;
    (void)theoryOf(scene, h); // validates the scene, sets the still-water depth h
    // The farthest gauge is the last the grown wave reaches and the first the reflection
    // (from the far wall) reaches: its window lies inside every other gauge's.
    const auto gMax = std::max_element(scene.output.gauges.begin(), scene.output.gauges.end());
    return gaugeWindow(scene, h, *gMax);
}

std::vector<WaveWindow> regularWaveGaugeWindows(const Scene& scene) {
    double h = 0.0;
    (void)theoryOf(scene, h); // validates the scene, sets the still-water depth h
    std::vector<WaveWindow> out;
    for (double x : scene.output.gauges)
        out.push_back(gaugeWindow(scene, h, x));
    return out;
}

RegularWaveCheck checkRegularWave(const Scene& scene, std::span<const ProbeSample> samples,
                                  const WaveWindow& window,
                                  std::span<const WaveWindow> gaugeWindows) {
    RegularWaveCheck out;
    out.theory = theoryOf(scene, out.depth);
    out.window = window;
    out.gauges = scene.output.gauges;
    const std::size_t nGauges = out.gauges.size();
    if (gaugeWindows.empty()) {
        out.gaugeWindows.assign(nGauges, window);
    } else if (gaugeWindows.size() == nGauges) {
        out.gaugeWindows.assign(gaugeWindows.begin(), gaugeWindows.end());
    } else {
        throw std::invalid_argument(
            fmt::format("{} gauge windows for {} gauges", gaugeWindows.size(), nGauges));
    }
    const auto inside = [](const WaveWindow& w, double t) { return t >= w.start && t <= w.end; };
    // Per gauge: the samples of its own window and of the common window (whose times are the
    // same for every gauge: a dry gauge throws before anything is kept).
    std::vector<std::vector<double>> tOwn(nGauges), vOwn(nGauges), vCommon(nGauges);
    std::vector<double> tCommon;
    for (const ProbeSample& s : samples) {
        const bool common = inside(window, s.time);
        for (std::size_t g = 0; g < nGauges; ++g) {
            const bool own = inside(out.gaugeWindows[g], s.time);
            if (!common && !own)
                continue;
            if (s.elevations.size() != nGauges) {
                throw std::invalid_argument(
                    fmt::format("probe sample at t = {} s has {} gauges, the scene {}", s.time,
                                s.elevations.size(), nGauges));
            }
            if (!std::isfinite(s.elevations[g])) {
                throw std::invalid_argument(
                    fmt::format("gauge at x = {} m is dry at t = {} s, inside the fit window",
                                out.gauges[g], s.time));
            }
            if (own) {
                tOwn[g].push_back(s.time);
                vOwn[g].push_back(s.elevations[g]);
            }
            if (common)
                vCommon[g].push_back(s.elevations[g]);
        }
        if (common)
            tCommon.push_back(s.time);
    }
    out.samples = tCommon.size();
    const double omega = 2.0 * std::numbers::pi / scene.piston->period;
    std::vector<HarmonicFit> fits; // in the common window: the phases
    for (std::size_t g = 0; g < nGauges; ++g) {
        fits.push_back(fitHarmonic(tCommon, vCommon[g], omega)); // throws below 3 samples
        out.heightsCommonWindow.push_back(2.0 * fits.back().amplitude);
        out.heights.push_back(2.0 * fitHarmonic(tOwn[g], vOwn[g], omega).amplitude);
        out.gaugeSamples.push_back(tOwn[g].size());
        out.heightStandardErrors.push_back(heightStandardError(tOwn[g], vOwn[g], omega));
    }
    // Phase lag between the first two gauges: the wave reaches the farther one later.
    const double twoPi = 2.0 * std::numbers::pi;
    const double dx = out.gauges[1] - out.gauges[0];
    const double lag = phaseLag(fits[0].phase, fits[1].phase);
    out.wavelength =
        lag > 0.0 ? twoPi * std::abs(dx) / lag : std::numeric_limits<double>::infinity();

    // All gauges in order of x: unwrapped phase and ln H against x, least-squares lines.
    std::vector<std::size_t> order(nGauges);
    for (std::size_t g = 0; g < nGauges; ++g)
        order[g] = g;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return out.gauges[a] < out.gauges[b]; });
    std::vector<double> xs, phase, logH;
    for (std::size_t i = 0; i < nGauges; ++i) {
        const std::size_t g = order[i];
        xs.push_back(out.gauges[g]);
        logH.push_back(std::log(out.heights[g]));
        if (i == 0) {
            phase.push_back(fits[g].phase);
        } else {
            phase.push_back(phase.back() + phaseLag(fits[order[i - 1]].phase, fits[g].phase));
        }
    }
    const double phaseSlope = lineSlope(xs, phase, kDistinctGauges);
    out.wavelengthFit =
        phaseSlope > 0.0 ? twoPi / phaseSlope : std::numeric_limits<double>::infinity();
    // The decay as H(x) = exp(a + b x): per wavelength and across the gauges' span.
    const double decaySlope = lineSlope(xs, logH, kDistinctGauges);
    out.decayPerWavelength = 1.0 - std::exp(decaySlope * out.theory.wavelength);
    out.decayOverSpan = 1.0 - std::exp(decaySlope * (xs.back() - xs.front()));
    out.decayTotal = 1.0 - out.heights[order.back()] / out.heights[order.front()];
    double meanX = 0.0;
    for (double x : xs)
        meanX += x / static_cast<double>(xs.size());
    double sxx = 0.0, slopeVariance = 0.0;
    for (std::size_t i = 0; i < nGauges; ++i) {
        const std::size_t g = order[i];
        const double d2 = (xs[i] - meanX) * (xs[i] - meanX);
        const double relative = out.heightStandardErrors[g] / out.heights[g];
        sxx += d2;
        slopeVariance += d2 * relative * relative;
    }
    const double span = xs.back() - xs.front();
    out.decayOverSpanStandardError =
        std::exp(decaySlope * span) * span * std::sqrt(slopeVariance) / sxx;
    return out;
}

std::vector<ProbeSample> linearTheoryRecord(const Scene& scene, std::span<const double> times,
                                            FarWall farWall) {
    double h = 0.0;
    (void)theoryOf(scene, h); // validates the scene, sets the still-water depth h
    const PistonParams& p = *scene.piston;
    const double g = scene.physics.gravity;
    const Box& tank = *scene.geometry.tank; // x0: the paddle's rest position; x1: the far wall
    double tEnd = 0.0;
    for (double t : times)
        tEnd = std::max(tEnd, t);
    // Piston velocity sampled 100 times per period up to the last time, then zero. The sampled
    // transform is periodic in its span: the wave that left the paddle at time s reaches a
    // gauge at distance D after D / c_g, so the span must exceed the last time plus the slowest
    // component's travel over the longest distance, or that component arrives wrapped around,
    // at the start of the record.
    const double twoPi = 2.0 * std::numbers::pi;
    const double dt = p.period / 100.0;
    const PistonMotion motion(p, tEnd);
    std::vector<double> v;
    for (double t = 0.0; t <= tEnd; t += dt)
        v.push_back(motion.at(t).velocity);
    // Frequencies up to 8 times the piston's: the ramp's spectrum is negligible beyond.
    const double omega = twoPi / p.period;
    // The longest distance is the nearest gauge's mirror distance, with or without the wall, so
    // that both records are made of the same components.
    double farthest = 0.0;
    for (double gx : scene.output.gauges)
        farthest = std::max(farthest, mirrorDistance(tank, gx));
    // A quarter more than that travel time, for a margin.
    const double slowest = groupVelocity(8.0 * omega, h, g);
    const double span =
        std::max(8.0 * std::max(tEnd, p.period), 1.25 * (tEnd + farthest / slowest));
    const double dw = twoPi / span;
    const int bins = static_cast<int>(std::ceil(8.0 * omega / dw));
    struct Component {
        double k, re, im; // wavenumber; B(kh) V(w) / w dw / pi, complex
    };
    std::vector<Component> comps;
    comps.reserve(static_cast<std::size_t>(bins));
    for (int m = 1; m <= bins; ++m) {
        const double w = m * dw;
        double re = 0.0, im = 0.0; // V(w) = sum V(t_n) e^{-i w t_n} dt
        for (std::size_t n = 0; n < v.size(); ++n) {
            const double ph = w * static_cast<double>(n) * dt;
            re += v[n] * std::cos(ph) * dt;
            im -= v[n] * std::sin(ph) * dt;
        }
        const double k = dispersionWavenumber(w, h, g);
        const double c = pistonHeightOverStroke(k * h) / w * dw / std::numbers::pi;
        comps.push_back({k, c * re, c * im});
    }
    // eta(x, t) = (1 / pi) Re sum B V(w) / w e^{i (w t - k x)} dw, x the distance travelled
    const auto train = [&](double distance, double t) {
        double eta = 0.0;
        for (std::size_t m = 0; m < comps.size(); ++m) {
            const double ph = static_cast<double>(m + 1) * dw * t - comps[m].k * distance;
            eta += comps[m].re * std::cos(ph) - comps[m].im * std::sin(ph);
        }
        return eta;
    };
    std::vector<ProbeSample> out;
    out.reserve(times.size());
    for (double t : times) {
        ProbeSample s;
        s.time = t;
        s.frontX = std::numeric_limits<double>::quiet_NaN();
        for (double gx : scene.output.gauges) {
            // The incident train at the gauge's distance from the paddle and, with a far wall,
            // its mirror image (a perfectly reflecting wall: the same train from 2 x_1 - x).
            double eta = train(gx - tank.x0, t);
            if (farWall == FarWall::Reflects)
                eta += train(mirrorDistance(tank, gx), t);
            s.elevations.push_back(eta);
        }
        out.push_back(std::move(s));
    }
    return out;
}

void requireRecordCoversWindows(std::span<const ProbeSample> samples,
                                std::span<const WaveWindow> windows, double tolerance,
                                const std::string& what) {
    double end = 0.0;
    for (const WaveWindow& w : windows)
        end = std::max(end, w.end);
    const double last = samples.empty() ? 0.0 : samples.back().time;
    if (samples.empty() || last < end - tolerance) {
        throw std::invalid_argument(
            fmt::format("{}: the record ends at t = {} s, before the fit windows close at {} s",
                        what, last, end));
    }
}

std::vector<ProbeSample> readProbeCsv(const std::filesystem::path& path,
                                      std::span<const double> gauges) {
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(fmt::format("{}: cannot open the probes file", path.string()));
    std::string line;
    if (!std::getline(in, line) || line.rfind("time,front_x", 0) != 0) {
        throw std::runtime_error(fmt::format(
            "{}:1: not a probes file (header must start with time,front_x)", path.string()));
    }
    if (!gauges.empty() && line != probeCsvHeader(gauges)) {
        throw std::runtime_error(
            fmt::format("{}:1: the header '{}' is not the scene's gauges ('{}')", path.string(),
                        line, probeCsvHeader(gauges)));
    }
    const auto columns = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    std::vector<ProbeSample> out;
    for (long lineNo = 2; std::getline(in, line); ++lineNo) {
        if (line.empty())
            continue;
        std::vector<double> values;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) {
            try {
                std::size_t used = 0;
                values.push_back(cell == "nan" ? std::numeric_limits<double>::quiet_NaN()
                                               : std::stod(cell, &used));
                if (cell != "nan" && used != cell.size())
                    throw std::invalid_argument(cell);
            } catch (const std::exception&) {
                throw std::runtime_error(
                    fmt::format("{}:{}: '{}' is not a number", path.string(), lineNo, cell));
            }
        }
        if (values.size() != columns) {
            throw std::runtime_error(fmt::format("{}:{}: {} values, the header has {} columns",
                                                 path.string(), lineNo, values.size(), columns));
        }
        ProbeSample s;
        s.time = values[0];
        s.frontX = values[1];
        s.elevations.assign(values.begin() + 2, values.end());
        out.push_back(std::move(s));
    }
    return out;
}

} // namespace swell::bake::validation
