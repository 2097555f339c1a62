#pragma once
// Red noise for tests of estimators on noisy records: a first-order autoregressive series
// x_k = phi x_{k-1} + sqrt(1 - phi^2) sigma e_k (e_k standard normal), stationary from its
// first sample, with standard deviation sigma and correlation time -step / ln(phi).

#include <cmath>
#include <random>
#include <vector>

namespace swell::test {

class RedNoise {
public:
    /// `correlationTime` and `step` in the same units; a correlation time of 0 gives white
    /// noise. Seeded: the same seed gives the same series.
    RedNoise(double sigma, double correlationTime, double step, unsigned long long seed)
        : m_sigma(sigma), m_phi(correlationTime > 0.0 ? std::exp(-step / correlationTime) : 0.0),
          m_rng(seed) {}

    /// The next `n` samples of the series (continuing it).
    std::vector<double> next(std::size_t n) {
        std::vector<double> out(n);
        const double innovation = m_sigma * std::sqrt(1.0 - m_phi * m_phi);
        for (double& x : out) {
            m_x =
                m_started ? m_phi * m_x + innovation * m_normal(m_rng) : m_sigma * m_normal(m_rng);
            m_started = true;
            x = m_x;
        }
        return out;
    }

private:
    double m_sigma;
    double m_phi;
    std::mt19937_64 m_rng;
    std::normal_distribution<double> m_normal;
    double m_x = 0.0;
    bool m_started = false;
};

} // namespace swell::test
