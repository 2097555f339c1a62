#pragma once
// SplitMix64 (Steele, Lea & Flood 2014), the bake's one random generator: a fixed sequence on
// every platform, so a seeded scene bakes the same everywhere (internal to swell_bake).
#include <cstdint>

namespace swell::bake {

/// One SplitMix64 step: advances `state` and returns the next 64 random bits.
inline std::uint64_t splitmix(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// A uniform double in [lo, hi) from the top 53 bits of the next step.
inline double uniform(std::uint64_t& state, double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(splitmix(state) >> 11) * 0x1.0p-53;
}

} // namespace swell::bake
