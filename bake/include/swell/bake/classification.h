#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

#include "swell/bake/particles.h"
#include "swell/cache/frame.h"

namespace swell::bake {

/// Class of a water particle by its number density (paper eq. (4)).
enum class WaterClass : std::uint8_t { Splash, Surface, Deep };

/// Paper eq. (4): splash if n < d1 n0, surface if d1 n0 <= n <= d2 n0, deep if n > d2 n0.
inline WaterClass classifyWater(double n, double n0, double d1, double d2) {
    if (n < d1 * n0)
        return WaterClass::Splash;
    if (n <= d2 * n0)
        return WaterClass::Surface;
    return WaterClass::Deep;
}

/// The stored part of one simulation frame and the class counts behind it.
struct ClassifiedFrame {
    cache::Frame frame;   ///< surface (x, y) sorted by x, splash (x, y, vx, vy) in particle order
    std::size_t deep = 0; ///< water particles classified deep (never stored)
    std::size_t surface() const { return frame.surfaceCount(); }
    std::size_t splash() const { return frame.splashCount(); }
};

/// Classifies every water particle by eq. (4) from its number density `particles.n` and
/// keeps the surface and splash ones (Sec. 3.2: only they go to the animation step).
/// Surface particles are sorted by x (then y) so the cache's delta filter sees smooth
/// data; their order carries no meaning. Wall and dummy particles are skipped.
/// `layer` (one flag per particle, or empty) marks the solver's surface layer
/// (MpsSolver::surfaceLayer): a flagged particle with n >= d1 n0 is surface even above d2 n0,
/// so a compressed crest still counts; eq. (4)'s thresholds are unchanged.
ClassifiedFrame classifyParticles(const Particles& particles, double n0, double d1, double d2,
                                  std::span<const std::uint8_t> layer = {});

} // namespace swell::bake
