#include "swell/runtime/render/splash_culling.h"

#include "swell/runtime/parallel_chunks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace swell::runtime {

namespace {

std::size_t cullRange(std::span<const SplashSprite> sprites, std::span<const float> heights,
                      const Grid& grid, const SpriteFootprint& footprint,
                      std::vector<SplashSprite>& out) {
    const int N = grid.cellsX, M = grid.cellsZ;
    const double cell = std::min(grid.dx, grid.dz);
    const double pixelRadius = 0.71 / footprint.pixelsPerMetre; // per metre of distance
    const double ox = grid.x0 + 0.5 * grid.dx, oz = 0.5 * grid.dz;
    std::size_t dropped = 0;
    for (const SplashSprite& s : sprites) {
        // The cell (between vertices n..n+1, m..m+1) holding the sprite, and one more around.
        const double fx = (s.x - ox) / grid.dx, fz = (s.z - oz) / grid.dz;
        bool hidden = false;
        const double ex = s.x - footprint.eye[0], ey = s.y - footprint.eye[1],
                     ez = s.z - footprint.eye[2];
        // The drawn radius; a disc under a cell reaches at most one cell beyond its own.
        const double radius =
            std::max(footprint.radius, pixelRadius * std::sqrt(ex * ex + ey * ey + ez * ez));
        if (radius < cell && fx >= 1.0 && fz >= 1.0 && fx < N - 2.0 && fz < M - 2.0) {
            const int n = static_cast<int>(fx), m = static_cast<int>(fz);
            float lowest = heights[static_cast<std::size_t>(m - 1) * N + (n - 1)];
            for (int dm = -1; dm <= 2; ++dm) {
                const float* row = &heights[static_cast<std::size_t>(m + dm) * N];
                for (int dn = -1; dn <= 2; ++dn)
                    lowest = std::min(lowest, row[n + dn]);
            }
            hidden = s.y + radius < lowest;
        }
        if (hidden)
            ++dropped;
        else
            out.push_back(s);
    }
    return dropped;
}

} // namespace

std::size_t cullSubmergedSplashes(std::span<const SplashSprite> sprites,
                                  std::span<const float> heights, const Grid& grid,
                                  const SpriteFootprint& footprint,
                                  std::vector<SplashSprite>& out) {
    const int N = grid.cellsX, M = grid.cellsZ;
    if (N < 4 || M < 4 ||
        heights.size() != static_cast<std::size_t>(N) * static_cast<std::size_t>(M))
        throw std::invalid_argument(
            "cullSubmergedSplashes: heights must hold N x M >= 4 x 4 values");
    // Consecutive ranges culled in parallel, each into its own list, joined in order.
    const std::size_t chunks = chunkCount(sprites.size(), 8192);
    std::vector<std::vector<SplashSprite>> kept(chunks);
    std::vector<std::size_t> dropped(chunks, 0);
    forEachChunk(sprites.size(), chunks, [&](std::size_t c, std::size_t begin, std::size_t end) {
        kept[c].reserve(end - begin);
        dropped[c] =
            cullRange(sprites.subspan(begin, end - begin), heights, grid, footprint, kept[c]);
    });
    std::size_t total = 0;
    for (std::size_t c = 0; c < chunks; ++c) {
        out.insert(out.end(), kept[c].begin(), kept[c].end());
        total += dropped[c];
    }
    return total;
}

} // namespace swell::runtime
