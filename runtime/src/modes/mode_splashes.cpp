#include "swell/runtime/modes/mode_splashes.h"

#include "swell/runtime/modes/whirlpool.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swell::runtime {

void placeSplashes(std::vector<SplashSprite>& sprites, const Grid& grid, const ModeParams& mode,
                   int direction, double tau) {
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    const double cx = grid.x0 + 0.5 * grid.cellsX * grid.dx, cz = 0.5 * grid.extentZ;
    const double x1 = grid.x0 + grid.cellsX * grid.dx;
    // Spray outside the slices' own x range (e.g. the wave maker's zone) is not shown: cut
    // before the mode moves it into the mesh.
    std::erase_if(sprites, [&](const SplashSprite& p) { return !(p.x >= grid.x0 && p.x <= x1); });
    switch (mode.mode) {
    case ReplayMode::Surging:
        break;
    case ReplayMode::Ripple: {
        const auto& angles = mode.ripple.anglesDegrees;
        if (direction < 0 || direction >= static_cast<int>(angles.size()))
            throw std::invalid_argument("placeSplashes: no such ripple direction");
        const double a = angles[static_cast<std::size_t>(direction)] * std::numbers::pi / 180.0;
        const double c = std::cos(a), s = std::sin(a);
        for (SplashSprite& p : sprites) {
            const double qx = p.x - cx, qz = p.z - cz;
            p.x = static_cast<float>(cx + c * qx - s * qz);
            p.z = static_cast<float>(cz + s * qx + c * qz);
        }
        break;
    }
    case ReplayMode::Whirlpool: {
        const SpiralGeometry spiral(grid, mode.whirlpool);
        const double J = spiral.sliceCount();
        const double spin = spiral.spinSlices(tau);
        const double a = spiral.innerRadius(), b = mode.whirlpool.growth;
        for (SplashSprite& p : sprites) {
            const double u = (p.x - grid.x0) / grid.dx;
            const double slice = p.z / grid.dz * (J + 1.0) / grid.cellsZ - 1.0;
            const double t = kTwoPi * u / grid.cellsX;
            const double r = a * std::exp(b * t);
            const double angle = kTwoPi * (slice + spin) / J + t;
            p.x = static_cast<float>(cx + r * std::cos(angle));
            p.z = static_cast<float>(cz + r * std::sin(angle));
        }
        break;
    }
    }
    std::erase_if(sprites, [&](const SplashSprite& p) {
        return !(p.x >= grid.x0 && p.x <= x1 && p.z >= 0.0 && p.z <= grid.extentZ);
    });
}

SplashParams keepSprayAwayFromTheWaveMaker(SplashParams params, const BakeRecord& record) {
    if (!std::isfinite(record.waveMakerXMax) || !(record.particleSpacing > 0.0))
        return params;
    const auto [x0, x1] = shownWaterX(record);
    const double band = kRecyclingSprayBand * record.particleSpacing;
    if (x1 - x0 > 2.0 * band) {
        params.keepX0 = std::max(params.keepX0, x0 + band);
        params.keepX1 = std::min(params.keepX1, x1 - band);
    }
    return params;
}

std::vector<SplashSystem> makeSplashSystems(const FrameSet& frames, const Grid& grid,
                                            const SplashParams& params, std::uint64_t seed,
                                            std::size_t sets) {
    std::vector<SplashSystem> systems;
    systems.reserve(sets);
    for (std::size_t d = 0; d < sets; ++d)
        systems.emplace_back(frames, grid, params,
                             sliceSetSeed(seed, static_cast<int>(d)) ^ 0x5b1a54e5ULL);
    return systems;
}

std::vector<SplashSprite> modeSplashes(std::span<const SplashSystem> systems,
                                       std::span<const SliceSampler> samplers, const Grid& grid,
                                       const ModeParams& mode, double tau, double seconds) {
    if (systems.size() != samplers.size())
        throw std::logic_error("modeSplashes: one splash system per slice sampler");
    std::vector<SplashSprite> sprites;
    if (systems.empty() || !systems.front().active())
        return sprites;
    for (std::size_t d = 0; d < systems.size(); ++d) {
        std::vector<SplashSprite> more = systems[d].sprites(samplers[d].frames(tau), seconds);
        placeSplashes(more, grid, mode, static_cast<int>(d), tau);
        sprites.insert(sprites.end(), more.begin(), more.end());
    }
    return sprites;
}

} // namespace swell::runtime
