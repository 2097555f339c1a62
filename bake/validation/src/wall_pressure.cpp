#include "swell/bake/validation/wall_pressure.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace swell::bake::validation {

std::vector<PressurePoint> movingAverage(std::span<const PressurePoint> series, double halfWidth) {
    std::vector<PressurePoint> out;
    out.reserve(series.size());
    // [lo, hi) holds the samples within halfWidth of sample i; both ends only move forward.
    std::size_t lo = 0, hi = 0;
    double sum = 0.0;
    for (std::size_t i = 0; i < series.size(); ++i) {
        while (hi < series.size() && series[hi].t <= series[i].t + halfWidth)
            sum += series[hi++].p;
        while (series[lo].t < series[i].t - halfWidth)
            sum -= series[lo++].p;
        out.push_back({series[i].t, sum / static_cast<double>(hi - lo)});
    }
    return out;
}

PressureFigures pressureFigures(std::span<const PressurePoint> series) {
    const std::vector<PressurePoint> s = movingAverage(series, kPressureSmoothing);
    PressureFigures f;
    const auto impact =
        std::find_if(s.begin(), s.end(), [](const PressurePoint& q) { return q.p > kImpactLevel; });
    if (impact != s.end())
        f.impactTime = impact->t;
    for (const PressurePoint& q : s) {
        if (q.t < kSecondPeakFrom || q.t > kSecondPeakTo)
            continue;
        if (!f.peakTime || q.p > f.peak) {
            f.peakTime = q.t;
            f.peak = q.p;
        }
    }
    return f;
}

std::optional<double> meanAbsPressureError(std::span<const PressurePoint> simulated,
                                           std::span<const PressurePoint> reference) {
    if (reference.size() < 2)
        return std::nullopt;
    const std::vector<PressurePoint> sim = movingAverage(simulated, kPressureSmoothing);
    const std::vector<PressurePoint> ref = movingAverage(reference, kPressureSmoothing);
    double sum = 0.0;
    std::size_t n = 0;
    std::size_t k = 1; // ref[k - 1].t <= q.t <= ref[k].t for the sample at hand
    for (const PressurePoint& q : sim) {
        if (q.t < ref.front().t || q.t > ref.back().t)
            continue;
        while (ref[k].t < q.t)
            ++k;
        const PressurePoint& a = ref[k - 1];
        const PressurePoint& b = ref[k];
        const double w = b.t > a.t ? (q.t - a.t) / (b.t - a.t) : 0.0;
        sum += std::abs(q.p - (a.p + w * (b.p - a.p)));
        ++n;
    }
    if (n == 0)
        return std::nullopt;
    return sum / static_cast<double>(n);
}

std::span<const PressureRecordColumn> buchnerP1Columns() {
    static constexpr PressureRecordColumn kColumns[] = {
        {"experiment", &FarWallPressureSample::experiment},
        {"delta_sph_40", &FarWallPressureSample::deltaSph40},
        {"delta_sph_80", &FarWallPressureSample::deltaSph80},
        {"delta_sph_320", &FarWallPressureSample::deltaSph320}};
    return kColumns;
}

std::vector<PressurePoint> buchnerP1Series(double FarWallPressureSample::*column) {
    std::vector<PressurePoint> out;
    for (const FarWallPressureSample& s : buchnerP1Records())
        out.push_back({s.t, s.*column});
    return out;
}

std::string buchnerP1RecordsCsv() {
    std::string text = "series,t,p\n";
    for (const auto& [name, column] : buchnerP1Columns())
        for (const FarWallPressureSample& s : buchnerP1Records())
            text += fmt::format("{},{},{}\n", name, s.t, s.*column);
    return text;
}

} // namespace swell::bake::validation
