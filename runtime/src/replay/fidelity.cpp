#include "swell/runtime/replay/fidelity.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace swell::runtime {

RowFidelity compareRow(std::span<const double> row, const Grid& grid,
                       const std::function<double(double)>& eta, double lo, double hi,
                       double step) {
    if (row.size() != static_cast<std::size_t>(grid.cellsX)) {
        throw std::invalid_argument(
            fmt::format("compareRow: {} heights for {} columns", row.size(), grid.cellsX));
    }
    if (!(step > 0.0) || !std::isfinite(step))
        throw std::invalid_argument(fmt::format("compareRow: step must be > 0, got {}", step));
    const double first = grid.x0 + 0.5 * grid.dx;
    const double last = grid.x0 + (grid.cellsX - 0.5) * grid.dx;
    lo = std::max(lo, first);
    hi = std::min(hi, last);
    RowFidelity r;
    double etaMax = -std::numeric_limits<double>::infinity(), etaMin = -etaMax;
    double rowMax = -std::numeric_limits<double>::infinity();
    const auto count = hi >= lo ? static_cast<long long>(std::floor((hi - lo) / step)) + 1 : 0;
    for (long long i = 0; i < count; ++i) {
        const double x = lo + static_cast<double>(i) * step;
        // The mesh between cell centres: linear in x.
        const double u =
            std::clamp((x - first) / grid.dx, 0.0, static_cast<double>(grid.cellsX - 1));
        const auto n = std::min(static_cast<std::size_t>(u), row.size() - 1);
        const std::size_t n1 = std::min(n + 1, row.size() - 1);
        const double t = u - static_cast<double>(n);
        const double h = (1.0 - t) * row[n] + t * row[n1];
        const double e = eta(x);
        const double d = h - e;
        r.sumSquares += d * d;
        r.maxAbs = std::max(r.maxAbs, std::abs(d));
        etaMax = std::max(etaMax, e);
        etaMin = std::min(etaMin, e);
        rowMax = std::max(rowMax, h);
        ++r.samples;
    }
    if (r.samples > 0 && etaMax > etaMin)
        r.crestLoss = (etaMax - rowMax) / (etaMax - etaMin);
    return r;
}

RowFidelity compareRow(std::span<const double> row, const Grid& grid, const SurfaceEnvelope& eta,
                       double step) {
    if (eta.empty())
        return {};
    return compareRow(
        row, grid, [&](double x) { return eta.at(x); }, eta.xFirst(), eta.xLast(), step);
}

double rowSpread(const HeightField& h, int m) {
    double s = 0.0, s2 = 0.0;
    for (int n = 0; n < h.cellsX; ++n) {
        const double v = h.at(n, m) - h.at(0, m); // shifted: no cancellation
        s += v;
        s2 += v * v;
    }
    const double mean = s / h.cellsX;
    return std::sqrt(std::max(0.0, s2 / h.cellsX - mean * mean));
}

double fieldSpread(const HeightField& h) {
    if (h.heights.empty())
        return 0.0;
    double s = 0.0, s2 = 0.0;
    for (double v : h.heights) {
        s += v - h.heights[0];
        s2 += (v - h.heights[0]) * (v - h.heights[0]);
    }
    const double n = static_cast<double>(h.heights.size());
    return std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)));
}

int flatRows(const HeightField& h) {
    int flat = 0;
    for (int m = 0; m < h.cellsZ; ++m)
        flat += rowSpread(h, m) < kFlatRowMetres ? 1 : 0;
    return flat;
}

void FidelityStats::add(const RowFidelity& r) {
    if (r.samples == 0)
        return;
    ++rows;
    samples += r.samples;
    sumSquares += r.sumSquares;
    maxAbs = std::max(maxAbs, r.maxAbs);
    sumRowMax += r.maxAbs;
    sumCrestLoss += r.crestLoss;
    maxCrestLoss = std::max(maxCrestLoss, r.crestLoss);
}

double FidelityStats::rms() const {
    return samples ? std::sqrt(sumSquares / static_cast<double>(samples)) : 0.0;
}

nlohmann::json toJson(const FidelityStats& s, double l0) {
    nlohmann::json j{{"rows", s.rows},
                     {"samples", s.samples},
                     {"rms_m", s.rms()},
                     {"max_m", s.maxAbs},
                     {"mean_row_max_m", s.meanRowMax()},
                     {"crest_loss_mean", s.meanCrestLoss()},
                     {"crest_loss_max", s.maxCrestLoss}};
    if (l0 > 0.0) {
        j["l0_m"] = l0;
        j["rms_l0"] = s.rms() / l0;
        j["max_l0"] = s.maxAbs / l0;
        j["mean_row_max_l0"] = s.meanRowMax() / l0;
    }
    return j;
}

} // namespace swell::runtime
