#include "swell/runtime/replay/picture_measures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <vector>

namespace swell::runtime {
namespace {

void sameSize(const HeightField& a, const HeightField& b) {
    if (a.cellsX != b.cellsX || a.cellsZ != b.cellsZ || a.heights.size() != b.heights.size())
        throw std::invalid_argument("picture measures: the height fields differ in size");
}

double percentile99(std::vector<double>& v) {
    const std::size_t k = static_cast<std::size_t>(0.99 * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

} // namespace

SlopeRatios slopeRatios(const HeightField& h, double margin) {
    const int n0 = static_cast<int>(margin * h.cellsX), n1 = h.cellsX - n0;
    const int m0 = static_cast<int>(margin * h.cellsZ), m1 = h.cellsZ - m0;
    if (n1 - n0 < 2 || m1 - m0 < 2)
        throw std::invalid_argument("slope ratios: need at least 2 x 2 inner cells");
    std::vector<double> gx, gz;
    for (int m = m0; m < m1; ++m) {
        for (int n = n0; n < n1; ++n) {
            if (n + 1 < n1)
                gx.push_back(std::abs(h.at(n + 1, m) - h.at(n, m)));
            if (m + 1 < m1)
                gz.push_back(std::abs(h.at(n, m + 1) - h.at(n, m)));
        }
    }
    double sx = 0.0, sz = 0.0;
    for (double v : gx)
        sx += v;
    for (double v : gz)
        sz += v;
    if (!(sx > 0.0))
        throw std::invalid_argument("slope ratios: the field is flat along x");
    SlopeRatios r;
    r.mean = (sz / static_cast<double>(gz.size())) / (sx / static_cast<double>(gx.size()));
    const double px = percentile99(gx);
    r.p99 = px > 0.0 ? percentile99(gz) / px : INFINITY;
    return r;
}

double needleShare(const HeightField& h, double threshold) {
    if (h.cellsX < 3 || h.cellsZ < 3)
        return 0.0;
    std::size_t needles = 0, cells = 0;
    for (int m = 1; m + 1 < h.cellsZ; ++m) {
        for (int n = 1; n + 1 < h.cellsX; ++n) {
            const double c = h.at(n, m);
            const double nb[4] = {h.at(n - 1, m), h.at(n + 1, m), h.at(n, m - 1), h.at(n, m + 1)};
            bool above = true, below = true;
            for (double v : nb) {
                above = above && c - v > threshold;
                below = below && v - c > threshold;
            }
            needles += (above || below) ? 1 : 0;
            ++cells;
        }
    }
    return static_cast<double>(needles) / static_cast<double>(cells);
}

double shareDiffering(const HeightField& a, const HeightField& b, double threshold) {
    sameSize(a, b);
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.heights.size(); ++i)
        count += std::abs(a.heights[i] - b.heights[i]) > threshold ? 1 : 0;
    return a.heights.empty() ? 0.0
                             : static_cast<double>(count) / static_cast<double>(a.heights.size());
}

double meanChange(const HeightField& a, const HeightField& b) {
    sameSize(a, b);
    double sum = 0.0;
    for (std::size_t i = 0; i < a.heights.size(); ++i)
        sum += std::abs(a.heights[i] - b.heights[i]);
    return a.heights.empty() ? 0.0 : sum / static_cast<double>(a.heights.size());
}

double discMean(const HeightField& h, double cn, double cm, double radius) {
    double sum = 0.0;
    std::size_t count = 0;
    for (int m = 0; m < h.cellsZ; ++m) {
        for (int n = 0; n < h.cellsX; ++n) {
            if (std::hypot(n + 0.5 - cn, m + 0.5 - cm) <= radius) {
                sum += h.at(n, m);
                ++count;
            }
        }
    }
    if (count == 0)
        throw std::invalid_argument("disc mean: no cell centre lies within the disc");
    return sum / static_cast<double>(count);
}

double creaseRatio(const HeightField& h, double pn, double pm, double tn, double tm) {
    const double length = std::hypot(tn, tm);
    if (!(length > 0.0))
        throw std::invalid_argument("crease ratio: the line needs a direction");
    // Unit normal, and the second difference along the nearer grid axis to it.
    const double nn = -tm / length, nm = tn / length;
    const bool alongX = std::abs(nn) >= std::abs(nm);
    double onSum = 0.0, offSum = 0.0;
    std::size_t on = 0, off = 0;
    for (int m = 1; m + 1 < h.cellsZ; ++m) {
        for (int n = 1; n + 1 < h.cellsX; ++n) {
            const double c = h.at(n, m);
            const double d2 = alongX ? h.at(n + 1, m) - 2.0 * c + h.at(n - 1, m)
                                     : h.at(n, m + 1) - 2.0 * c + h.at(n, m - 1);
            const double distance = std::abs((n + 0.5 - pn) * nn + (m + 0.5 - pm) * nm);
            if (distance <= 1.5) {
                onSum += std::abs(d2);
                ++on;
            } else if (distance > 3.0 && distance <= 8.0) { // beside it, either side
                offSum += std::abs(d2);
                ++off;
            }
        }
    }
    if (on < 4 || off < 4 || !(offSum > 0.0))
        throw std::invalid_argument("crease ratio: the line does not cross the field");
    return (onSum / static_cast<double>(on)) / (offSum / static_cast<double>(off));
}

double lineCoverage(std::span<const double> xs, std::span<const double> zs, double halfWidth,
                    double span) {
    if (xs.size() != zs.size())
        throw std::invalid_argument("line coverage: as many x as z coordinates are needed");
    if (!(halfWidth > 0.0) || !(span > 0.0))
        throw std::invalid_argument("line coverage: the half-width and span must be > 0");
    std::size_t best = 0;
    for (int degrees = 0; degrees < 180; ++degrees) {
        const double a = degrees * std::numbers::pi / 180.0;
        const double tx = std::cos(a), tz = std::sin(a);
        // Offsets across the line in bins of the half-width (a line covers two neighbouring
        // ones), positions along it in bins of the width.
        std::map<long long, std::set<long long>> along;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const long long across =
                static_cast<long long>(std::floor((-xs[i] * tz + zs[i] * tx) / halfWidth));
            along[across].insert(
                static_cast<long long>(std::floor((xs[i] * tx + zs[i] * tz) / (2.0 * halfWidth))));
        }
        for (const auto& [bin, occupied] : along) {
            std::set<long long> both = occupied;
            if (const auto next = along.find(bin + 1); next != along.end())
                both.insert(next->second.begin(), next->second.end());
            best = std::max(best, both.size());
        }
    }
    return std::min(1.0, static_cast<double>(best) * 2.0 * halfWidth / span);
}

} // namespace swell::runtime
