#include "swell/bake/validation/validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace swell::bake::validation {
namespace {

/// Mean, max and signed mean of sim - ref over the reference points whose time is in
/// [tLo, tHi], the simulated series (sorted by time) linearly interpolated at each of them;
/// `uncovered(t)` throws for a reference time outside the simulated series.
template <class Error, class Point, class Time, class Value, class Uncovered>
Error compareInterpolated(std::span<const Point> sim, std::span<const Point> ref, double tLo,
                          double tHi, Time time, Value value, Uncovered uncovered) {
    Error e;
    for (const Point& p : ref) {
        const double t = time(p);
        if (t < tLo || t > tHi)
            continue;
        if (t < time(sim.front()) || t > time(sim.back()))
            uncovered(t);
        const auto hi = std::lower_bound(sim.begin(), sim.end(), t,
                                         [&](const Point& a, double x) { return time(a) < x; });
        const auto lo = hi == sim.begin() ? hi : hi - 1;
        const double span = time(*hi) - time(*lo);
        const double v = span > 0.0
                             ? value(*lo) + (value(*hi) - value(*lo)) * (t - time(*lo)) / span
                             : value(*hi);
        const double d = v - value(p);
        e.mean += std::abs(d);
        e.meanSigned += d;
        e.max = std::max(e.max, std::abs(d));
        ++e.points;
    }
    if (e.points > 0) {
        e.mean /= e.points;
        e.meanSigned /= e.points;
    }
    return e;
}

} // namespace

double surgeFront(const Particles& particles, double n0, double splashRatio, double x0) {
    double front = x0;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        if (particles.kind[i] != ParticleKind::Water)
            continue;
        if (particles.n[i] < splashRatio * n0)
            continue; // splash, paper eq. (4)
        front = std::max(front, particles.x[i]);
    }
    return front - x0;
}

FrontError compareFront(std::span<const FrontPoint> sim, std::span<const FrontPoint> exp,
                        double tLo, double tHi) {
    if (sim.size() < 2)
        throw std::invalid_argument("compareFront: need at least two simulated points");
    return compareInterpolated<FrontError>(
        sim, exp, tLo, tHi, [](const FrontPoint& p) { return p.T; },
        [](const FrontPoint& p) { return p.Z; },
        [](double) {
            throw std::invalid_argument(
                "compareFront: the simulation does not cover the experimental times");
        });
}

FrontError pooled(const FrontError& a, const FrontError& b) {
    FrontError e;
    e.points = a.points + b.points;
    e.max = std::max(a.max, b.max);
    if (e.points > 0) {
        e.mean = (a.mean * a.points + b.mean * b.points) / e.points;
        e.meanSigned = (a.meanSigned * a.points + b.meanSigned * b.points) / e.points;
    }
    return e;
}

AlignedFront alignedFront(std::span<const FrontPoint> sim, std::span<const FrontPoint> exp,
                          double tLo, double tHi) {
    if (sim.size() < 2 || exp.size() < 2)
        throw std::invalid_argument(
            "alignedFront: need two or more simulated and experimental points");
    const FrontPoint anchor = exp.front(); // (T_1, Z_1): the experiment's first record
    if (sim.front().Z > anchor.Z) {
        throw std::invalid_argument(fmt::format(
            "alignedFront: the simulated front starts at Z = {} beyond the experiment's "
            "first position Z_1 = {}",
            sim.front().Z, anchor.Z));
    }
    double crossing = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < sim.size(); ++k) {
        if (sim[k].Z < anchor.Z)
            continue;
        if (k == 0) {
            crossing = sim[0].T; // starts exactly at Z_1
        } else {
            const FrontPoint& a = sim[k - 1];
            const FrontPoint& b = sim[k];
            crossing = a.T + (b.T - a.T) * (anchor.Z - a.Z) / (b.Z - a.Z);
        }
        break;
    }
    if (std::isnan(crossing)) {
        throw std::invalid_argument(fmt::format(
            "alignedFront: the simulated front never reaches the experiment's first position "
            "Z_1 = {} (largest Z {} up to T = {})",
            anchor.Z,
            std::max_element(sim.begin(), sim.end(),
                             [](const FrontPoint& a, const FrontPoint& b) { return a.Z < b.Z; })
                ->Z,
            sim.back().T));
    }
    AlignedFront out;
    out.shift = anchor.T - crossing;
    std::vector<FrontPoint> shifted(sim.begin(), sim.end());
    for (FrontPoint& p : shifted)
        p.T += out.shift;
    out.error = compareFront(shifted, exp.subspan(1), tLo, tHi);
    return out;
}

AlignedFront martinMoyceScatter(double tLo, double tHi) {
    return alignedFront(martinMoyceA225(), martinMoyceA1125(), tLo, tHi);
}

LevelError compareLevel(std::span<const LevelPoint> sim, std::span<const LevelPoint> record,
                        double tLo, double tHi) {
    if (sim.size() < 2)
        throw std::invalid_argument("compareLevel: need at least two simulated points");
    return compareInterpolated<LevelError>(
        sim, record, tLo, tHi, [](const LevelPoint& p) { return p.t; },
        [](const LevelPoint& p) { return p.h; },
        [&](double t) {
            throw std::invalid_argument(fmt::format(
                "compareLevel: the simulation ({} to {} s) does not cover the record time {} s",
                sim.front().t, sim.back().t, t));
        });
}

std::optional<LevelError> lobovskyScatter(const LevelGauge& gauge, double tLo, double tHi) {
    if (gauge.repeat.empty())
        return std::nullopt;
    return compareLevel(gauge.repeat, gauge.series, tLo, tHi);
}

std::optional<double> firstTimeAbove(std::span<const LevelPoint> series, double level) {
    const auto above = std::find_if(series.begin(), series.end(),
                                    [level](const LevelPoint& p) { return p.h > level; });
    if (above == series.end())
        return std::nullopt;
    return above->t;
}

std::size_t lobovskyFarGauge(std::span<const LevelGauge> gauges) {
    if (gauges.empty())
        throw std::invalid_argument("lobovskyFarGauge: no gauges");
    const auto far =
        std::max_element(gauges.begin(), gauges.end(),
                         [](const LevelGauge& a, const LevelGauge& b) { return a.x < b.x; });
    return static_cast<std::size_t>(far - gauges.begin());
}

double lobovskyRunUpEnd(std::span<const LevelGauge> gauges, double H) {
    const LevelGauge& far = gauges[lobovskyFarGauge(gauges)];
    const std::optional<double> t = firstTimeAbove(far.series, 0.5 * H);
    if (!t) {
        throw std::invalid_argument(
            fmt::format("lobovskyRunUpEnd: the record at {} never rises above H / 2 = {} m",
                        far.name, 0.5 * H));
    }
    return *t;
}

std::pair<double, double> crossingsAround(std::span<const double> t, std::span<const double> y,
                                          double lo, double hi, double crestTime, double level) {
    // y[a] and y[b] lie on either side of `level` wherever this is called.
    const auto cross = [&](std::size_t a, std::size_t b) {
        return t[a] + (t[b] - t[a]) * (level - y[a]) / (y[b] - y[a]);
    };
    const std::size_t after = static_cast<std::size_t>(
        std::lower_bound(t.begin(), t.end(), crestTime) - t.begin()); // first t >= crestTime
    double front = std::numeric_limits<double>::quiet_NaN(), back = front;
    for (std::size_t k = after; k-- > 0 && t[k] >= lo;) {
        if (y[k] < level && k + 1 < t.size()) {
            front = cross(k, k + 1);
            break;
        }
    }
    for (std::size_t k = after; k < t.size() && t[k] <= hi; ++k) {
        if (y[k] < level && k > 0) {
            back = cross(k - 1, k);
            break;
        }
    }
    return {front, back};
}

std::pair<double, double> parabolaTop(std::span<const double> t, std::span<const double> y,
                                      std::size_t lo, std::size_t hi, std::size_t peak) {
    const double t0 = t[peak];
    double s[5] = {0, 0, 0, 0, 0}, r[3] = {0, 0, 0};
    for (std::size_t k = lo; k <= hi; ++k) {
        const double d = t[k] - t0;
        double p = 1.0;
        for (int e = 0; e < 5; ++e) {
            s[e] += p;
            if (e < 3)
                r[e] += p * y[k];
            p *= d;
        }
    }
    // Normal equations [s0 s1 s2; s1 s2 s3; s2 s3 s4] (a b c) = r, by Cramer's rule.
    const auto det3 = [](double a, double b, double c, double d, double e, double f, double g,
                         double h, double i) {
        return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    };
    const double D = det3(s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4]);
    if (hi - lo < 2 || !(std::abs(D) > 0.0))
        return {t0, y[peak]};
    const double a = det3(r[0], s[1], s[2], r[1], s[2], s[3], r[2], s[3], s[4]) / D;
    const double b = det3(s[0], r[0], s[2], s[1], r[1], s[3], s[2], r[2], s[4]) / D;
    const double c = det3(s[0], s[1], r[0], s[1], s[2], r[1], s[2], s[3], r[2]) / D;
    const double vertex = -b / (2.0 * c);
    if (!(c < 0.0) || std::abs(vertex) > t[hi] - t[lo])
        return {t0, y[peak]};
    return {t0 + vertex, a + b * vertex + c * vertex * vertex};
}

double lineSlope(std::span<const double> x, std::span<const double> y, const char* what) {
    const double n = static_cast<double>(x.size());
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        mx += x[i] / n;
        my += y[i] / n;
    }
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    if (!(sxx > 0.0))
        throw std::invalid_argument(what);
    return sxy / sxx;
}

HarmonicFit fitHarmonic(std::span<const double> t, std::span<const double> v, double omega) {
    if (t.size() != v.size() || t.size() < 3)
        throw std::invalid_argument("fitHarmonic: need >= 3 samples of t and v");
    // Normal equations M x = r for x = (a, b, c).
    double M[3][4] = {};
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double basis[3] = {std::cos(omega * t[i]), std::sin(omega * t[i]), 1.0};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c)
                M[r][c] += basis[r] * basis[c];
            M[r][3] += basis[r] * v[i];
        }
    }
    for (int c = 0; c < 3; ++c) { // Gaussian elimination with partial pivoting
        int p = c;
        for (int r = c + 1; r < 3; ++r) {
            if (std::abs(M[r][c]) > std::abs(M[p][c]))
                p = r;
        }
        if (!(std::abs(M[p][c]) > 1e-12 * static_cast<double>(t.size()))) {
            throw std::invalid_argument(
                "fitHarmonic: singular fit (samples do not resolve the frequency)");
        }
        for (int k = 0; k < 4; ++k)
            std::swap(M[c][k], M[p][k]);
        for (int r = c + 1; r < 3; ++r) {
            const double f = M[r][c] / M[c][c];
            for (int k = c; k < 4; ++k)
                M[r][k] -= f * M[c][k];
        }
    }
    double x[3];
    for (int r = 2; r >= 0; --r) {
        double s = M[r][3];
        for (int k = r + 1; k < 3; ++k)
            s -= M[r][k] * x[k];
        x[r] = s / M[r][r];
    }
    return HarmonicFit{std::hypot(x[0], x[1]), std::atan2(x[1], x[0]), x[2]};
}

double harmonicAmplitudeStandardError(std::span<const double> t, std::span<const double> v,
                                      double omega) {
    const std::size_t n = t.size();
    // The mean and its drift, harmonics 1..kStandardErrorHarmonics, and the first harmonic's
    // drift (an amplitude that grows or shrinks across the window, as a wave front's does).
    constexpr int kCols = 4 + 2 * kStandardErrorHarmonics;
    static_assert(kStandardErrorMinSamples == 2 * kCols);
    if (v.size() != n || n < kStandardErrorMinSamples)
        throw std::invalid_argument(
            fmt::format("harmonicAmplitudeStandardError: need >= {} samples of t and v",
                        kStandardErrorMinSamples));
    const double step = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
    for (std::size_t i = 1; i < n; ++i) {
        if (!(std::abs(t[i] - t[i - 1] - step) <= 0.01 * step))
            throw std::invalid_argument(fmt::format(
                "harmonicAmplitudeStandardError: samples not evenly spaced at t = {} s", t[i]));
    }
    // The wave's part of the record, least squares.
    const double middle = 0.5 * (t[0] + t[n - 1]);
    Eigen::MatrixXd A(static_cast<Eigen::Index>(n), kCols);
    Eigen::VectorXd y(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
        const auto r = static_cast<Eigen::Index>(i);
        const double drift = t[i] - middle;
        A(r, 0) = 1.0;
        for (int h = 1; h <= kStandardErrorHarmonics; ++h) {
            A(r, 2 * h - 1) = std::cos(h * omega * t[i]);
            A(r, 2 * h) = std::sin(h * omega * t[i]);
        }
        A(r, kCols - 3) = drift;
        A(r, kCols - 2) = drift * std::cos(omega * t[i]);
        A(r, kCols - 1) = drift * std::sin(omega * t[i]);
        y(r) = v[i];
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    if (qr.rank() < kCols)
        throw std::invalid_argument(
            "harmonicAmplitudeStandardError: singular fit (samples do not resolve the harmonics)");
    const Eigen::VectorXd residual = y - A * qr.solve(y);
    // The fit's projection P = Q Q^T (Q: an orthonormal basis of A's columns). The residual of
    // white noise of variance s^2 has the covariance s^2 (I - P), so the estimate below reads
    // s^2 B for it, B from (I - P)'s diagonals; dividing by B makes it exact for white noise
    // and puts back the band around omega that the fit took out (B = 0.53 at N = 300, K = 77:
    // without it the standard error reads a quarter low).
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(A.rows(), kCols);
    // Its spectral density at omega: autocovariance over lags up to one period, Bartlett window.
    const double period = 2.0 * std::numbers::pi / omega;
    const auto lags = std::min<std::size_t>(n - 1, static_cast<std::size_t>(period / step));
    double density = 0.0;
    double white = 0.0; // B
    for (std::size_t k = 0; k <= lags; ++k) {
        double c = 0.0;
        double projected = 0.0;
        for (std::size_t i = 0; i + k < n; ++i) {
            const auto a = static_cast<Eigen::Index>(i);
            const auto b = static_cast<Eigen::Index>(i + k);
            c += residual(a) * residual(b);
            projected += Q.row(a).dot(Q.row(b));
        }
        const double taper = 1.0 - static_cast<double>(k) / static_cast<double>(lags + 1);
        const double weight =
            k == 0 ? 1.0 : 2.0 * taper * std::cos(omega * static_cast<double>(k) * step);
        density += weight * c / static_cast<double>(n);
        white +=
            weight * ((k == 0 ? static_cast<double>(n) : 0.0) - projected) / static_cast<double>(n);
    }
    if (!(white > 0.0))
        throw std::invalid_argument(
            "harmonicAmplitudeStandardError: the window is too short to estimate the noise");
    density /= white;
    return std::sqrt(2.0 * std::max(density, 0.0) / static_cast<double>(n));
}

std::string martinMoyceRecordsCsv() {
    std::string out = "series,T,Z\n";
    for (const auto& [name, series] :
         {std::pair{"a2.25in", martinMoyceA225()}, std::pair{"a1.125in", martinMoyceA1125()}}) {
        for (const FrontPoint& p : series)
            out += fmt::format("{},{},{}\n", name, p.T, p.Z);
    }
    return out;
}

std::string lobovskyRecordsCsv() {
    std::string out = "gauge,series,x,t,h\n";
    for (const LevelGauge& g : lobovskyH300Gauges()) {
        for (const LevelPoint& p : g.series)
            out += fmt::format("{},record,{},{},{}\n", g.name, g.x, p.t, p.h);
        for (const LevelPoint& p : g.repeat)
            out += fmt::format("{},repeat,{},{},{}\n", g.name, g.x, p.t, p.h);
    }
    return out;
}

Spread spreadOf(std::span<const double> values) {
    if (values.empty())
        throw std::invalid_argument("spreadOf: no values");
    Spread s;
    s.count = values.size();
    s.min = s.max = values.front();
    double sum = 0.0;
    for (double v : values) {
        if (!std::isfinite(v))
            throw std::invalid_argument(fmt::format("spreadOf: a value is not finite ({})", v));
        sum += v;
        s.min = std::min(s.min, v);
        s.max = std::max(s.max, v);
    }
    s.mean = sum / static_cast<double>(s.count);
    double ss = 0.0;
    for (double v : values)
        ss += (v - s.mean) * (v - s.mean);
    s.sd = s.count > 1 ? std::sqrt(ss / static_cast<double>(s.count - 1)) : 0.0;
    return s;
}

} // namespace swell::bake::validation
