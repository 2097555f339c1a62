#include "swell/runtime/render/splash_system.h"

#include "../json_read.h"
#include "swell/runtime/parallel_chunks.h"
#include "swell/split_mix64.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {
namespace {

/// A point uniformly distributed in the unit ball (rejection sampling).
void unitBall(SplitMix64& rng, double out[3]) {
    for (;;) {
        for (int k = 0; k < 3; ++k)
            out[k] = 2.0 * rng.uniform() - 1.0;
        if (out[0] * out[0] + out[1] * out[1] + out[2] * out[2] <= 1.0)
            return;
    }
}

} // namespace

void SplashParams::validate() const {
    if (artificialPerReal < 0 || artificialPerReal > 1000) {
        throw std::invalid_argument(fmt::format(
            "splash count (artificial per real) must be in [0, 1000], got {}", artificialPerReal));
    }
    if (!(spawnRadius >= 0.0) || !std::isfinite(spawnRadius))
        throw std::invalid_argument("splash spawn radius must be >= 0");
    if (!(spriteRadius > 0.0) || !std::isfinite(spriteRadius))
        throw std::invalid_argument("splash sprite radius must be > 0");
    if (!(velocityJitter >= 0.0) || !std::isfinite(velocityJitter))
        throw std::invalid_argument("splash velocity jitter must be >= 0");
    if (!(minSpeed >= 0.0) || !std::isfinite(minSpeed))
        throw std::invalid_argument("splash min speed must be >= 0");
    if (!(minLifetime > 0.0) || !(maxLifetime >= minLifetime) || !std::isfinite(maxLifetime)) {
        throw std::invalid_argument("splash lifetimes need 0 < min <= max");
    }
    if (!(gravity >= 0.0) || !std::isfinite(gravity))
        throw std::invalid_argument("splash gravity must be >= 0");
    if (sliceStride < 1)
        throw std::invalid_argument("splash slice stride must be >= 1");
    if (std::isnan(keepX0) || std::isnan(keepX1) || !(keepX1 > keepX0))
        throw std::invalid_argument("splash keep range needs x0 < x1");
}

SplashParams splashParamsFromJson(const nlohmann::json& j) {
    using namespace json_read;
    rejectUnknown(j,
                  {"enabled", "artificial_per_real", "spawn_radius", "sprite_radius",
                   "velocity_jitter", "min_speed", "min_lifetime", "max_lifetime", "gravity",
                   "slice_stride"},
                  "splash.", "splash");
    SplashParams p;
    read(j, "enabled", "splash.", p.enabled);
    read(j, "artificial_per_real", "splash.", p.artificialPerReal);
    read(j, "spawn_radius", "splash.", p.spawnRadius);
    read(j, "sprite_radius", "splash.", p.spriteRadius);
    read(j, "velocity_jitter", "splash.", p.velocityJitter);
    read(j, "min_speed", "splash.", p.minSpeed);
    read(j, "min_lifetime", "splash.", p.minLifetime);
    read(j, "max_lifetime", "splash.", p.maxLifetime);
    read(j, "gravity", "splash.", p.gravity);
    read(j, "slice_stride", "splash.", p.sliceStride);
    p.validate();
    return p;
}

SplashSystem::SplashSystem(const FrameSet& frames, const Grid& grid, const SplashParams& params,
                           std::uint64_t seed)
    : m_frames(frames), m_grid(grid), m_params(params), m_seed(seed) {
    params.validate();
    if (params.enabled) {
        m_active = std::any_of(frames.frames.begin(), frames.frames.end(),
                               [](const cache::Frame& f) { return f.splashCount() > 0; });
    }
    if (!m_active)
        return;
    for (const cache::Frame& f : frames.frames)
        m_maxSplash = std::max(m_maxSplash, f.splashCount());
    const auto A = static_cast<std::size_t>(params.artificialPerReal);
    const auto realSlices = static_cast<std::size_t>(grid.sliceCount() + 1) / 2;
    const std::size_t count = realSlices * m_maxSplash * A;
    if (count == 0 || count > params.drawTableBytes / sizeof(Draws))
        return;
    m_draws.resize(count);
    forEachChunk(count, chunkCount(count, 4096), [&](std::size_t, std::size_t b, std::size_t e) {
        for (std::size_t n = b; n < e; ++n) {
            const std::size_t a = n % A, i = n / A % m_maxSplash, k = n / A / m_maxSplash;
            m_draws[n] = draws(static_cast<int>(2 * k), i, static_cast<int>(a));
        }
    });
}

SplashSystem::Draws SplashSystem::draws(int j, std::size_t i, int a) const {
    // One generator per artificial splash, keyed by (seed, slice, particle, index): the result
    // does not depend on the order or number of other splashes.
    SplitMix64 keyed(m_seed ^ 0x5e1a5bULL);
    std::uint64_t key = keyed.next();
    key ^= SplitMix64(static_cast<std::uint64_t>(j) * 0x9e3779b97f4a7c15ULL + 1).next();
    key ^= SplitMix64(static_cast<std::uint64_t>(i) * 0xc2b2ae3d27d4eb4fULL + 2).next();
    key ^= SplitMix64(static_cast<std::uint64_t>(a) * 0x165667b19e3779f9ULL + 3).next();
    SplitMix64 rng(key);
    Draws d;
    unitBall(rng, d.ball);
    unitBall(rng, d.jitter);
    d.scale = 0.7 + 0.6 * rng.uniform();
    d.life = 0.5 + 0.5 * rng.uniform();
    d.phase = rng.uniform();
    return d;
}

ArtificialSplash SplashSystem::fromDraws(const Draws& d, const float* p) const {
    ArtificialSplash s;
    const SplashParams& q = m_params;
    // Sec. 5: initial position random in a sphere around the real splash.
    for (int k = 0; k < 3; ++k)
        s.offset[k] = d.ball[k] * q.spawnRadius;
    // Velocity from the real particle's (in the slice plane, z = 0) plus a random part in
    // every direction, proportional to its speed.
    const double vx = p[2], vy = p[3];
    const double speed = std::max(std::sqrt(vx * vx + vy * vy), q.minSpeed);
    s.velocity[0] = vx * d.scale + d.jitter[0] * q.velocityJitter * speed;
    s.velocity[1] = vy * d.scale + d.jitter[1] * q.velocityJitter * speed;
    s.velocity[2] = d.jitter[2] * q.velocityJitter * speed;
    // Lifetime from the real particle: the flight time of a drop thrown up at its speed,
    // 2 |v| / g, clamped, times a random factor in [0.5, 1].
    const double flight = q.gravity > 0.0 ? 2.0 * speed / q.gravity : q.maxLifetime;
    s.lifetime = std::clamp(flight, q.minLifetime, q.maxLifetime) * d.life;
    s.lifetime = std::max(s.lifetime, q.minLifetime);
    s.phase = d.phase;
    return s;
}

ArtificialSplash SplashSystem::artificial(const float* p, int j, std::size_t i, int a) const {
    return fromDraws(draws(j, i, a), p);
}

std::vector<SplashSprite> SplashSystem::sprites(std::span<const std::uint32_t> sliceFrames,
                                                double seconds) const {
    std::vector<SplashSprite> out;
    if (!m_active)
        return out;
    if (static_cast<int>(sliceFrames.size()) != m_grid.sliceCount()) {
        throw std::logic_error("SplashSystem::sprites: one frame per slice expected");
    }
    const SplashParams& q = m_params;
    // The real splashes in order (slice, particle); each gives 1 + artificialPerReal sprites at
    // a fixed place in `out`, so the chunks below fill it in parallel, deterministically.
    struct Real {
        const float* p; // x, y, vx, vy
        int j;          // slice
        std::size_t i;  // particle in its frame
        double z;       // the slice's z, metres
    };
    std::vector<Real> reals;
    for (int j = 0; j < m_grid.sliceCount(); j += 2 * q.sliceStride) {
        const cache::Frame* frame = m_frames.find(sliceFrames[static_cast<std::size_t>(j)]);
        if (frame == nullptr)
            continue; // not held: nothing to show (like the replay's yMin)
        const double z = m_grid.sliceZCells(j) * m_grid.dz;
        for (std::size_t i = 0; i < frame->splashCount(); ++i) {
            const float x = frame->splash[4 * i];
            if (x >= q.keepX0 && x <= q.keepX1)
                reals.push_back({&frame->splash[4 * i], j, i, z});
        }
    }
    const auto per = static_cast<std::size_t>(1 + q.artificialPerReal);
    out.resize(reals.size() * per);
    const auto fill = [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            const Real& real = reals[r];
            const float* p = real.p;
            const double z = real.z;
            SplashSprite* o = &out[r * per];
            *o++ = {p[0], p[1], static_cast<float>(z), 1.0f};
            const Draws* table =
                m_draws.empty()
                    ? nullptr
                    : &m_draws[(static_cast<std::size_t>(real.j / 2) * m_maxSplash + real.i) *
                               static_cast<std::size_t>(q.artificialPerReal)];
            for (int a = 0; a < q.artificialPerReal; ++a) {
                const ArtificialSplash s =
                    fromDraws(table != nullptr ? table[a] : draws(real.j, real.i, a), p);
                // Ballistic motion from the start point; age cycles through the lifetime.
                double life = seconds / s.lifetime + s.phase;
                life -= std::floor(life);
                const double t = life * s.lifetime;
                *o++ = {static_cast<float>(p[0] + s.offset[0] + s.velocity[0] * t),
                        static_cast<float>(p[1] + s.offset[1] + s.velocity[1] * t -
                                           0.5 * q.gravity * t * t),
                        static_cast<float>(z + s.offset[2] + s.velocity[2] * t),
                        static_cast<float>(1.0 - life)};
            }
        }
    };
    // At least a few thousand sprites per thread: below that a thread costs more than it saves.
    forEachChunk(reals.size(), chunkCount(out.size(), 4096), fill);
    return out;
}

} // namespace swell::runtime
