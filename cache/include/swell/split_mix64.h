#pragma once
// swell's one random generator: SplitMix64 (Steele, Lea & Flood 2014), whose output is defined
// by integer arithmetic alone, so a seed gives the same numbers on every machine and compiler
// (std::normal_distribution does not). The bake draws its jitter and random piston from it, the
// runtime its noise, splash and sky.
#include <cstdint>

namespace swell {

class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}

    /// Next 64 random bits.
    std::uint64_t next() {
        std::uint64_t z = (m_state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1), 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    /// Uniform in [lo, hi), from the same 53 bits.
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Standard normal, approximately: the sum of 12 uniforms minus 6 (Irwin-Hall). Mean 0,
    /// variance 1, tails cut at +-6. Chosen over Box-Muller because it needs no libm call,
    /// so the bits do not depend on the C library's log/cos.
    double gaussian() {
        double sum = 0.0;
        for (int i = 0; i < 12; ++i)
            sum += uniform();
        return sum - 6.0;
    }

private:
    std::uint64_t m_state;
};

} // namespace swell
