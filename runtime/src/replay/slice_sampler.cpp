#include "swell/runtime/replay/slice_sampler.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

SliceSampler::SliceSampler(const ReplayParams& params, std::size_t frameCount, double A)
    : SliceSampler(params, Timeline::whole(frameCount, params.policy), A) {}

SliceSampler::SliceSampler(const ReplayParams& params, Timeline timeline, double A)
    : m_K(params.slices), m_timeline(std::move(timeline)), m_A(A), m_F(params.fluctuation),
      m_sampling(params.timeSampling) {
    params.validate();
    if (m_timeline.size() == 0)
        throw std::invalid_argument("the replay's timeline has no frames");
    if (!std::isfinite(A) || A <= 0.0 || A > 1e8) {
        throw std::invalid_argument(
            fmt::format("A = {} cache frames per time unit is out of range", A));
    }
    if (m_F != 0.0)
        m_noise.emplace(params.noise, params.slices, params.seed);
}

double SliceSampler::noiseAt(double tau, int j) const {
    if (!m_noise)
        return 0.0;
    // Same operations, in the same order, as shaders/slice_lookup.comp.
    const int T = m_noise->timeSamples();
    const double Td = static_cast<double>(T);
    const double tw = tau - Td * std::floor(tau / Td); // tau wrapped into [0, T)
    int i0 = static_cast<int>(std::floor(tw));
    if (i0 >= T)
        i0 -= T; // rounding at the period end
    const double a = tw - static_cast<double>(i0);
    const int i1 = (i0 + 1) % T;
    auto along = [&](int k) { return (1.0 - a) * m_noise->at(i0, k) + a * m_noise->at(i1, k); };
    const int k0 = j / 2;
    double n = along(k0);
    if ((j & 1) == 1)
        n = 0.5 * (n + along(k0 + 1)); // inserted slice: N at k + 1/2
    return n;
}

std::size_t SliceSampler::entry(double tau, int j) const {
    if (j < 0 || j >= sliceCount()) {
        throw std::logic_error(fmt::format("slice {} outside 0 .. {}", j, sliceCount() - 1));
    }
    if (!std::isfinite(tau) || (std::abs(tau) + 1.0) * m_A > 1.0e9) {
        throw std::invalid_argument(
            fmt::format("animation time tau = {} is out of range for A = {}", tau, m_A));
    }
    const double x = m_F != 0.0 ? tau + m_F * noiseAt(tau, j) : tau;
    const long long s = static_cast<long long>(std::floor(x * m_A + 0.5)); // eq. (5)
    return m_timeline.index(s);
}

SliceBlend SliceSampler::blend(double tau, int j) const {
    const std::size_t nearest = entry(tau, j); // checks j and tau
    if (m_sampling == TimeSampling::Nearest)
        return {nearest, nearest, 0.0};
    // Same operations, in the same order, as shaders/slice_lookup.comp.
    const double x = m_F != 0.0 ? tau + m_F * noiseAt(tau, j) : tau;
    const double scaled = x * m_A;
    double base = std::floor(scaled);
    double w = scaled - base;
    if (w > 1.0 - 1e-9) { // on a stored frame, up to rounding
        base += 1.0;
        w = 0.0;
    } else if (w < 1e-9) {
        w = 0.0;
    }
    const auto s = static_cast<long long>(base);
    const std::size_t first = m_timeline.index(s);
    return {first, w == 0.0 ? first : m_timeline.index(s + 1), w};
}

std::uint32_t SliceSampler::frame(double tau, int j) const {
    return m_timeline[entry(tau, j)].shown();
}

std::vector<std::size_t> SliceSampler::entries(double tau) const {
    std::vector<std::size_t> out(static_cast<std::size_t>(sliceCount()));
    for (int j = 0; j < sliceCount(); ++j)
        out[static_cast<std::size_t>(j)] = entry(tau, j);
    return out;
}

std::vector<std::uint32_t> SliceSampler::frames(double tau) const {
    std::vector<std::uint32_t> out(static_cast<std::size_t>(sliceCount()));
    for (int j = 0; j < sliceCount(); ++j)
        out[static_cast<std::size_t>(j)] = frame(tau, j);
    return out;
}

std::vector<std::uint32_t> SliceSampler::framesUsed(std::span<const double> taus) const {
    std::vector<bool> used(static_cast<std::size_t>(m_timeline.maxFrame()) + 1, false);
    for (double tau : taus) {
        for (int j = 0; j < sliceCount(); ++j) {
            const SliceBlend b = blend(tau, j);
            for (const std::size_t i : {b.first, b.second}) {
                const TimelineEntry& e = m_timeline[i];
                used[e.a] = true;
                if (e.blended())
                    used[e.b] = true;
            }
        }
    }
    std::vector<std::uint32_t> out;
    for (std::size_t f = 0; f < used.size(); ++f) {
        if (used[f])
            out.push_back(static_cast<std::uint32_t>(f));
    }
    return out;
}

} // namespace swell::runtime
