#pragma once
// Splash particles for rendering (Sec. 5): every real slice shows the splash particles of the
// cache frame it samples (eq. 5), at its own z, and around each real splash a seeded cloud of
// artificial splashes: "random properties such as initial positions, velocities, and
// lifetimes, based on those of the actual splash particles", moving ballistically. Splash
// particles are never smoothed into the surface (Sec. 4.3). CPU side; the renderer draws the
// result as point sprites.

#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/replay_params.h"

#include <cstdint>
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <vector>

namespace swell::runtime {

struct SplashParams {
    bool enabled = true;       ///< draw splashes at all (a cache with none draws none anyway)
    int artificialPerReal = 6; ///< artificial splashes around each real one (Sec. 5)
    /// Radius of the sphere around a real splash where artificial ones start, metres.
    double spawnRadius = 0.04;
    double spriteRadius = 0.007; ///< rendered radius of a splash sprite, metres
    /// Random part of an artificial velocity, as a fraction of the real speed.
    double velocityJitter = 0.4;
    double minSpeed = 0.3;     ///< speed scale used when the real particle is slower, m/s
    double minLifetime = 0.15; ///< shortest lifetime, seconds
    double maxLifetime = 1.2;  ///< longest lifetime, seconds
    double gravity = 9.81;     ///< downward acceleration of the ballistic motion, m/s^2
    int sliceStride = 1;       ///< use every n-th real slice (1: all K)
    /// Real splashes are shown only with x in [keepX0, keepX1] (metres; default: all), e.g.
    /// not the spray a wave maker makes (keepSprayAwayFromTheWaveMaker).
    double keepX0 = -std::numeric_limits<double>::infinity();
    double keepX1 = std::numeric_limits<double>::infinity();
    /// Memory for the artificial splashes' random numbers, drawn once (72 bytes per artificial
    /// splash a frame can show); when they need more, they are drawn again every frame (the
    /// same numbers, more CPU). 0: always every frame.
    std::size_t drawTableBytes = std::size_t{64} << 20;

    /// Throws std::invalid_argument naming the field.
    void validate() const;
};

/// Reads the keys present ("enabled", "artificial_per_real", "spawn_radius", "sprite_radius",
/// "velocity_jitter", "min_speed", "min_lifetime", "max_lifetime", "gravity", "slice_stride")
/// over the defaults, then validate(); unknown keys and wrong types throw naming "splash.KEY".
SplashParams splashParamsFromJson(const nlohmann::json& j);

/// One point sprite: world position (metres) and opacity (0..1).
struct SplashSprite {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
    float alpha = 1.0f;
};

/// The random properties of one artificial splash (Sec. 5), for tests and exporters.
struct ArtificialSplash {
    /// Start relative to the real splash, |offset| <= spawnRadius.
    double offset[3] = {0.0, 0.0, 0.0};
    double velocity[3] = {0.0, 0.0, 0.0}; ///< initial velocity, m/s
    double lifetime = 0.0;                ///< seconds
    double phase = 0.0;                   ///< 0..1: where in its life it is at time 0
};

class SplashSystem {
public:
    /// Keeps a reference to `frames` (must outlive it). `seed` seeds the artificial splashes.
    /// Throws std::invalid_argument on bad parameters.
    SplashSystem(const FrameSet& frames, const Grid& grid, const SplashParams& params,
                 std::uint64_t seed);

    /// Whether any held frame has a splash particle and splashes are enabled: if not, the
    /// renderer runs no splash pass.
    bool active() const { return m_active; }

    /// The sprites at simulated time `seconds`, given the cache frame of every slice
    /// (SliceSampler::frames(tau), 2K - 1 entries; the K real slices, even j, are used).
    /// For real slice j showing frame s, each splash particle i of s gives one sprite at
    /// (x_i, y_i, z_j) plus artificialPerReal sprites at
    ///   p_i + offset + v t + (0, -g t^2 / 2, 0),  t = age = fract(seconds / L + phase) L,
    /// with opacity 1 - t / L (they respawn at the real particle when their life ends).
    /// Deterministic: the random properties depend on (seed, j, i, a) only.
    std::vector<SplashSprite> sprites(std::span<const std::uint32_t> sliceFrames,
                                      double seconds) const;

    /// The random properties of artificial splash `a` of splash particle `i` (position and
    /// velocity `realPosVel` = x, y, vx, vy) seen by slice j.
    ArtificialSplash artificial(const float* realPosVel, int j, std::size_t i, int a) const;

    const SplashParams& params() const { return m_params; }

private:
    /// The random numbers of one artificial splash, from its own generator keyed by
    /// (seed, j, i, a); artificial() combines them with the real particle's velocity.
    struct Draws {
        double ball[3] = {0.0, 0.0, 0.0};   ///< start offset, in the unit ball
        double jitter[3] = {0.0, 0.0, 0.0}; ///< random velocity part, in the unit ball
        double scale = 1.0;                 ///< factor on the real velocity, 0.7..1.3
        double life = 1.0;                  ///< factor on the lifetime, 0.5..1
        double phase = 0.0;                 ///< 0..1
    };
    Draws draws(int j, std::size_t i, int a) const;
    ArtificialSplash fromDraws(const Draws& d, const float* realPosVel) const;

    const FrameSet& m_frames;
    Grid m_grid;
    SplashParams m_params;
    std::uint64_t m_seed;
    bool m_active = false;
    /// Draws of every artificial splash a frame can show, [((j / 2) M + i) A + a] for real slice
    /// j, particle i < M (the most splash particles in a held frame) and a < A: they do not
    /// depend on the frame, so they are drawn once rather than per frame (when they fit in
    /// SplashParams::drawTableBytes; else per frame).
    std::vector<Draws> m_draws;
    std::size_t m_maxSplash = 0;
};

} // namespace swell::runtime
