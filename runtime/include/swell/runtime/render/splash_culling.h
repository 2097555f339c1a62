#pragma once
// Splash sprites hidden under the water surface, dropped before drawing. The water is opaque,
// so a drop whose whole disc lies below the surface around it cannot be seen (the depth test
// would reject every one of its pixels); on llvmpipe each point still costs vertex processing
// and triangle set-up on one thread, so culling them on the CPU saves that work and changes no
// pixel. Order is kept (blending is order-dependent): the same sprites give the same picture.

#include "swell/runtime/render/camera.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/replay/replay_params.h"

#include <span>
#include <vector>

namespace swell::runtime {

/// How big a sprite is drawn: `radius` metres, but never under half a pixel's diagonal, and a
/// pixel at distance d from the eye spans d / pixelsPerMetre metres (pixelsPerMetre: pixels per
/// metre at unit distance, height / (2 tan(fov / 2))).
struct SpriteFootprint {
    double radius = 0.0;     ///< metres
    Vec3 eye{0.0, 0.0, 0.0}; ///< metres
    double pixelsPerMetre = 1.0;
};

/// Appends to `out` the sprites of `sprites` that may be visible above the height field
/// `heights` (N x M values, [m * N + n], vertex (n, m) at x = x0 + (n + 0.5) dx,
/// z = (m + 0.5) dz, as GpuReplay::heightBuffer), in their order. A sprite is dropped when it
/// lies over the mesh at least one cell in from its edge and its top (y + radius) is below the
/// lowest of the 4 x 4 vertices around it: every point within its drawn radius (the larger of
/// `footprint.radius` and 0.71 pixel at its distance; only when that is under a cell) is then below
/// the drawn surface (each triangle lies between its corner heights), inside the opaque water.
/// Sprites near the edge, outside the mesh or above it are kept. Returns the number dropped. Throws
/// std::invalid_argument if `heights` does not hold N x M values.
std::size_t cullSubmergedSplashes(std::span<const SplashSprite> sprites,
                                  std::span<const float> heights, const Grid& grid,
                                  const SpriteFootprint& footprint, std::vector<SplashSprite>& out);

} // namespace swell::runtime
