#include "swell/runtime/slice_sampler.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

SliceSampler::SliceSampler(const ReplayParams& params, std::size_t frameCount, double A)
    : m_K(params.slices), m_frameCount(frameCount), m_A(A), m_F(params.fluctuation),
      m_policy(params.policy) {
    params.validate();
    if (frameCount == 0 || frameCount > 0x7fffffffu) {
        throw std::invalid_argument(
            fmt::format("cache has {} frames; need 1 .. 2^31 - 1", frameCount));
    }
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

std::uint32_t SliceSampler::frame(double tau, int j) const {
    if (j < 0 || j >= sliceCount()) {
        throw std::logic_error(fmt::format("slice {} outside 0 .. {}", j, sliceCount() - 1));
    }
    if (!std::isfinite(tau) || (std::abs(tau) + 1.0) * m_A > 1.0e9) {
        throw std::invalid_argument(
            fmt::format("animation time tau = {} is out of range for A = {}", tau, m_A));
    }
    const double x = m_F != 0.0 ? tau + m_F * noiseAt(tau, j) : tau;
    const long long s = static_cast<long long>(std::floor(x * m_A + 0.5)); // eq. (5)
    const long long n = static_cast<long long>(m_frameCount);
    if (m_policy == FramePolicy::Loop)
        return static_cast<std::uint32_t>(((s % n) + n) % n);
    return static_cast<std::uint32_t>(std::clamp(s, 0LL, n - 1));
}

std::vector<std::uint32_t> SliceSampler::frames(double tau) const {
    std::vector<std::uint32_t> out(static_cast<std::size_t>(sliceCount()));
    for (int j = 0; j < sliceCount(); ++j)
        out[static_cast<std::size_t>(j)] = frame(tau, j);
    return out;
}

std::vector<std::uint32_t> SliceSampler::framesUsed(std::span<const double> taus) const {
    std::vector<bool> used(m_frameCount, false);
    for (double tau : taus) {
        for (int j = 0; j < sliceCount(); ++j)
            used[frame(tau, j)] = true;
    }
    std::vector<std::uint32_t> out;
    for (std::size_t f = 0; f < m_frameCount; ++f) {
        if (used[f])
            out.push_back(static_cast<std::uint32_t>(f));
    }
    return out;
}

} // namespace swell::runtime
