#pragma once
// Synthetic cache frames for the runtime tests: analytic travelling waves sampled by jittered
// surface particles, with gaps, an empty frame and a few splash particles, so every code
// path (eq. 7 windows, fallbacks, clamp / loop) is exercised without a bake.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"
#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/split_mix64.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace swell::runtime::test {

/// `base` (ReplayParams or Grid) with an N x M grid and K real slices.
template <class T> T sized(int N, int M, int K, T base) {
    base.cellsX = N;
    base.cellsZ = M;
    base.slices = K;
    return base;
}

/// Domain x in [0, 4] m, y in [0, 1] m; dt 0.001 s, 10 steps per frame (A = 400 frames per
/// time unit with the paper's 4 s time unit).
inline cache::Header syntheticHeader() {
    cache::Header h;
    h.domain = {0.0f, 0.0f, 4.0f, 1.0f};
    h.dt = 0.001;
    h.frameInterval = 10;
    h.seed = 7;
    return h;
}

/// Mean water depth of the synthetic frames (m).
inline constexpr double kSyntheticDepth = 0.5;

/// Height of the analytic wave at x (m) and time t (s).
inline double syntheticWave(double x, double t) {
    using std::numbers::pi;
    return kSyntheticDepth + 0.06 * std::sin(2.0 * pi * (x / 1.3 - t / 1.7)) +
           0.025 * std::sin(2.0 * pi * (x / 0.37 + t / 0.9) + 1.0);
}

/// `count` frames with about `particles` surface particles each. Every 9th frame has a gap
/// x in [1.6, 2.4) with no surface particle, frame 5 (if present) is empty, and particles
/// past the moving front x > 3.2 + 0.6 sin(t) are missing (a dry region).
inline std::vector<cache::Frame> syntheticFrames(int count, int particles, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<cache::Frame> frames(static_cast<std::size_t>(count));
    for (int f = 0; f < count; ++f) {
        const double t = f * 0.01;
        cache::Frame& frame = frames[static_cast<std::size_t>(f)];
        if (f == 5)
            continue;
        const double front = 3.2 + 0.6 * std::sin(t);
        for (int p = 0; p < particles; ++p) {
            const double x = 4.0 * (p + rng.uniform()) / particles;
            if (x > front)
                continue;
            if (f % 9 == 0 && x >= 1.6 && x < 2.4)
                continue;
            frame.surface.push_back(static_cast<float>(x));
            frame.surface.push_back(
                static_cast<float>(syntheticWave(x, t) + 0.004 * (rng.uniform() - 0.5)));
        }
        for (int s = 0; s < 3; ++s) {
            for (float v : {static_cast<float>(front - 0.05 * s), 0.7f, 1.0f, 0.5f})
                frame.splash.push_back(v);
        }
    }
    return frames;
}

/// Every one of syntheticFrames(count, particles, seed) under syntheticHeader().
inline FrameSet syntheticSet(int count, int particles, std::uint64_t seed) {
    return FrameSet::whole(syntheticHeader(), syntheticFrames(count, particles, seed));
}

/// The sampler of `p` over every frame of `set`.
inline SliceSampler samplerOf(const FrameSet& set, const ReplayParams& p) {
    return SliceSampler(p, set.frameCount, framesPerTimeUnit(set.header, p));
}

} // namespace swell::runtime::test
