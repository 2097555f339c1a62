#include "swell/runtime/replay/surface_envelope.h"

#include "swell/runtime/replay/bake_record.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <stdexcept>

namespace swell::runtime {

SurfaceEnvelope::SurfaceEnvelope(const cache::Frame& frame, double binWidth) {
    if (!(binWidth > 0.0) || !std::isfinite(binWidth)) {
        throw std::invalid_argument(
            fmt::format("envelope bin width must be > 0 m, got {}", binWidth));
    }
    std::map<long long, std::pair<double, double>> top; // bin -> (x, y) of its highest particle
    for (std::size_t p = 0; p + 1 < frame.surface.size(); p += 2) {
        const double x = frame.surface[p];
        const double y = frame.surface[p + 1];
        const auto b = static_cast<long long>(std::floor(x / binWidth));
        auto [it, inserted] = top.try_emplace(b, x, y);
        if (!inserted &&
            (y > it->second.second || (y == it->second.second && x < it->second.first)))
            it->second = {x, y};
    }
    m_x.reserve(top.size());
    m_y.reserve(top.size());
    for (const auto& [b, p] : top) {
        m_x.push_back(p.first);
        m_y.push_back(p.second);
    }
}

double SurfaceEnvelope::at(double x) const {
    if (m_x.empty())
        return std::numeric_limits<double>::quiet_NaN();
    if (x <= m_x.front())
        return m_y.front();
    if (x >= m_x.back())
        return m_y.back();
    const auto hi =
        static_cast<std::size_t>(std::upper_bound(m_x.begin(), m_x.end(), x) - m_x.begin());
    const std::size_t lo = hi - 1;
    const double t = (x - m_x[lo]) / (m_x[hi] - m_x[lo]);
    return m_y[lo] + t * (m_y[hi] - m_y[lo]);
}

double envelopeBinWidth(const cache::Header& header, const Grid& grid) {
    const BakeRecord record = bakeRecord(header);
    return record.particleSpacing > 0.0 ? record.particleSpacing : 0.5 * grid.dx;
}

std::vector<double> sampleEnvelope(const SurfaceEnvelope& envelope, double x0, double dx,
                                   int count) {
    if (envelope.empty())
        return {};
    std::vector<double> out(static_cast<std::size_t>(std::max(count, 0)));
    for (int i = 0; i < count; ++i)
        out[static_cast<std::size_t>(i)] = envelope.at(x0 + (i + 0.5) * dx);
    return out;
}

} // namespace swell::runtime
