#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "swell/bake/box.h"
#include "swell/bake/particles.h"

namespace swell::bake {

/// A water rectangle's top as a cosine instead of its edge y1: the lattice sites with
/// y < y1 + amplitude cos(2 pi (x - x0) / wavelength) hold water, so y1 is the mean level. A
/// closed tank's first sloshing mode starts from rest with wavelength twice the tank's length
/// (swell-validate standing-wave). amplitude 0 keeps the flat top.
struct CosineTop {
    double amplitude = 0.0;  ///< A (m): |A| below the rectangle's height
    double wavelength = 0.0; ///< (m), > 0 where amplitude is not 0
};

/// A point of the tank's bed profile (geometry.bed), in m.
struct BedPoint {
    double x = 0.0;
    double y = 0.0;
};

/// Steepest bed slope |dy / dx| a profile may have: its wall and dummy layers stand in
/// vertical columns, so a slope of 1 keeps cos 45° = 0.71 of their thickness normal to the bed.
inline constexpr double kMaxBedSlope = 1.0;

/// Scene geometry: rectangles of water and solid, turned into particles on a
/// square lattice of spacing `particle_spacing`.
struct GeometryParams {
    double particleSpacing = 0.01; ///< l0 (m): lattice spacing of all particles; sets resolution
    /// Open-topped tank given by its inner faces (m): back wall inner face at x0, front
    /// wall inner face at x1, bed at y0, side walls up to y1. Walls are generated outside.
    std::optional<Box> tank;
    std::vector<Box> water; ///< water rectangles (m); each holds at least one particle
    /// Tops of the water rectangles, in their order (geometry.water[i].surface); empty, or
    /// shorter than `water`, for flat tops.
    std::vector<CosineTop> waterTops;
    std::vector<Box> solids; ///< extra solid blocks (m), filled with wall + dummy particles
    /// The tank's bed as a profile (m): its height is linear between the points (x increasing,
    /// inside the tank, y from the tank's y0 to below its y1, slopes at most kMaxBedSlope), the
    /// first point's y before them and the last's after. Empty: the flat bed at tank.y0. Each
    /// column of the tank's walls stands on the profile's height b at its x: its wall and dummy
    /// layers at b - (k + 1/2) l0, its side-wall sites above b; so a beach, a step or a shoal
    /// is smooth, not a staircase of lattice steps. Water lattice sites less than l0 / 2 above
    /// the profile are left out, so that water starts at least one spacing above the bed's
    /// first layer (as on a flat bed) and at most two.
    std::vector<BedPoint> bed;
    int wallLayers = 2;  ///< layers of pressure-solved wall particles (textbook code: 2)
    int dummyLayers = 2; ///< dummy layers behind them, completing wall density (textbook: 2)
    /// Simulation domain (m); a particle leaving it stops the run. Default: the bounding box B
    /// of all particles (plus one spacing) grown by B's width/2 left and right, B's height/4
    /// down and B's height up.
    std::optional<Box> domain;
    /// Extra bed (m) behind the tank's back wall, room for a piston back wall moving back
    /// (set by the scene from the piston's motion, not a scene key). Rounded up to l0.
    double bedExtensionBack = 0.0;
    /// Initial jitter of the water (l0): each water particle starts moved by a uniform random
    /// offset in [-jitter, jitter] l0 along x and y, drawn from the scene's seed (jitterWater);
    /// 0 keeps the lattice. A tiny jitter (1e-6) gives ensemble members of one flow whose
    /// spread is the record's sensitivity to round-off (swell-validate regular-wave --ensemble).
    double jitter = 0.0;
};

/// Water rectangle w's top: its entry in waterTops, flat (amplitude 0) where it has none.
inline CosineTop waterTop(const GeometryParams& g, std::size_t w) {
    return w < g.waterTops.size() ? g.waterTops[w] : CosineTop{};
}

/// The bed's height (m) at x: g.bed's profile, or the tank's y0 where it has none (0 without
/// a tank).
double bedHeight(const GeometryParams& g, double x);

/// Most particles a geometry may generate (water, wall and dummy together): 4 million, some
/// 40 times the largest shipped scene. A scene past it is refused before any particle is made,
/// naming geometry.particle_spacing and the count, instead of allocating without bound.
inline constexpr std::size_t kMaxParticles = 4'000'000;
/// Most solid blocks (geometry.solids) a scene may have.
inline constexpr std::size_t kMaxSolids = 10'000;

/// Largest domain, in particle spacings squared (the solver's neighbour grid holds at most 5e7
/// cells of at least one spacing): a geometry whose domain is larger is refused.
inline constexpr double kMaxDomainCells = 5e7;

/// The particles and domain a geometry describes.
struct GeneratedGeometry {
    Particles particles;
    Box domain;
    /// Indices of the tank's back-wall particles (wall and dummy layers above the bed, bed
    /// corners excluded): the particles a piston wavemaker moves (paper Sec. 3.3.1).
    std::vector<std::uint32_t> backWall;
};

/// Generates water, wall and dummy particles (water first, then walls, then dummies).
/// Water rectangles hold the lattice sites (x0 + (i + 1/2) l0, y0 + (j + 1/2) l0) inside
/// them; tank walls and solid blocks put their innermost `wallLayers` as Wall particles
/// and the next `dummyLayers` as Dummy; with a bed profile the tank's columns stand on it
/// (GeometryParams::bed). Throws SceneError naming the key for an empty
/// water rectangle (or one wholly under the bed), water overlapping a solid, a bed profile
/// without a tank, out of order, outside the tank or too steep, particles outside the domain, more
/// than kMaxParticles particles or a domain larger than kMaxDomainCells.
GeneratedGeometry generateGeometry(const GeometryParams& geometry);

/// Spacings of bed behind the tank's back wall: bedExtensionBack rounded up to whole l0.
long bedExtensionCells(const GeometryParams& geometry);

/// Moves each water particle by a uniform random offset in [-amplitude, amplitude] (m) along x
/// and y, from a SplitMix64 stream seeded with `seed`, in particle order (the same offsets on
/// every platform). Fixed particles stay.
void jitterWater(Particles& particles, double amplitude, std::uint64_t seed);

} // namespace swell::bake
