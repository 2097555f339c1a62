#include "swell/bake/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "swell/bake/error.h"
#include "swell/split_mix64.h"

namespace swell::bake {
namespace {

/// Number of whole lattice cells of size l0 in `length`, tolerating rounding; at most 1e15 (a
/// count that high is refused by checkParticleCount before anything loops over it).
long cellsIn(double length, double l0) {
    return static_cast<long>(std::min(std::floor(length / l0 + 1e-6), 1e15));
}

/// Refuses a geometry of more than kMaxParticles particles before any is generated: counts
/// them in floating point (no overflow), as the generator below lays them out.
void checkParticleCount(const GeometryParams& g, int layers) {
    const double l0 = g.particleSpacing;
    const auto cells = [l0](double length) {
        return std::max(0.0, std::floor(length / l0 + 1e-6));
    };
    double count = 0.0;
    for (std::size_t w = 0; w < g.water.size(); ++w)
        count += cells(g.water[w].width()) *
                 cells(g.water[w].height() + std::abs(waterTop(g, w).amplitude));
    if (g.tank) {
        const double nIn = std::round(g.tank->width() / l0);
        const double nUp = std::round(g.tank->height() / l0);
        const double back = std::ceil(std::max(0.0, g.bedExtensionBack) / l0 - 1e-6);
        count += layers * (nIn + 2.0 * layers + back) + nUp * 2.0 * layers;
    }
    for (const Box& s : g.solids) {
        const double nx = cells(s.width()), ny = cells(s.height());
        count += nx * ny - std::max(0.0, nx - 2.0 * layers) * std::max(0.0, ny - 2.0 * layers);
    }
    if (!(count <= static_cast<double>(kMaxParticles))) {
        throw SceneError("geometry.particle_spacing",
                         fmt::format("{} m gives {:.4g} particles, more than the {} a scene may "
                                     "have: use a larger spacing or smaller rectangles",
                                     l0, count, kMaxParticles));
    }
}

bool isWholeMultiple(double length, double l0) {
    const double k = length / l0;
    return std::abs(k - std::round(k)) < 1e-6 && std::round(k) >= 1.0;
}

ParticleKind layerKind(long layer, int wallLayers) {
    return layer < wallLayers ? ParticleKind::Wall : ParticleKind::Dummy;
}

void checkBox(const Box& b, const std::string& key) {
    if (!std::isfinite(b.x0) || !std::isfinite(b.x1) || !std::isfinite(b.y0) ||
        !std::isfinite(b.y1)) {
        throw SceneError(key, "coordinates must be finite numbers");
    }
    if (!(b.x1 > b.x0) || !(b.y1 > b.y0)) {
        throw SceneError(
            key, fmt::format("empty rectangle: need x1 > x0 and y1 > y0 (got x0 = {}, x1 = {}, "
                             "y0 = {}, y1 = {})",
                             b.x0, b.x1, b.y0, b.y1));
    }
}

/// Refuses a bed profile that the generator cannot lay out: no tank, fewer than two points,
/// x not increasing, a point outside the tank, or a slope steeper than kMaxBedSlope.
void checkBed(const GeometryParams& g) {
    if (g.bed.empty())
        return;
    if (!g.tank)
        throw SceneError("geometry.bed", "needs geometry.tank: the profile is the tank's bed");
    if (g.bed.size() < 2)
        throw SceneError("geometry.bed", "needs at least two points [x, y] (m)");
    const Box& t = *g.tank;
    for (std::size_t k = 0; k < g.bed.size(); ++k) {
        const BedPoint& p = g.bed[k];
        const std::string key = fmt::format("geometry.bed[{}]", k);
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw SceneError(key, "coordinates must be finite numbers");
        if (p.x < t.x0 || p.x > t.x1)
            throw SceneError(
                key, fmt::format("x = {} m lies outside the tank [{}, {}] m", p.x, t.x0, t.x1));
        if (p.y < t.y0 || p.y >= t.y1)
            throw SceneError(key, fmt::format("y = {} m must be in [{}, {}) m, from the tank's "
                                              "bed to below the top of its walls",
                                              p.y, t.y0, t.y1));
        if (k == 0)
            continue;
        const BedPoint& q = g.bed[k - 1];
        if (!(p.x > q.x))
            throw SceneError(
                key, fmt::format("x = {} m must exceed the previous point's {} m", p.x, q.x));
        const double slope = std::abs(p.y - q.y) / (p.x - q.x);
        if (slope > kMaxBedSlope * (1.0 + 1e-9))
            throw SceneError(key, fmt::format("the slope from the previous point is {:.4g}, "
                                              "steeper than {:g} (the layers under the bed "
                                              "stand in vertical columns)",
                                              slope, kMaxBedSlope));
    }
}

/// Depth of a water site at height y under the level b, in spacings, snapped to a whole number
/// within 1e-6 so that a site on the level is not under it, whatever the rounding of b and y:
/// the site is under it where this is > 0.
double depthUnder(double b, double y, double l0) {
    const double d = (b - y) / l0;
    const double whole = std::round(d);
    return std::abs(d - whole) < 1e-6 ? whole : d;
}

/// A solid region (m) that water must not lie in, and the key that names it.
using SolidRegion = std::pair<Box, std::string>;

/// Refuses a spacing that is not a positive length, too few wall or dummy layers, or no water.
void checkLattice(const GeometryParams& g) {
    const double l0 = g.particleSpacing;
    if (!(l0 > 0.0) || !std::isfinite(l0)) {
        throw SceneError("geometry.particle_spacing",
                         fmt::format("must be a positive length in m, got {}", l0));
    }
    if (g.wallLayers < 1)
        throw SceneError("geometry.wall_layers", "must be at least 1");
    if (g.dummyLayers < 0)
        throw SceneError("geometry.dummy_layers", "must not be negative");
    if (g.water.empty())
        throw SceneError("geometry.water", "the scene has no water rectangle");
}

/// Checks the tank, the bed and the solid blocks, and returns the solid regions (m) used to
/// reject water placed inside walls: the tank's bed and side walls with their layers, and the
/// blocks.
std::vector<SolidRegion> solidRegionsOf(const GeometryParams& g, int layers) {
    const double l0 = g.particleSpacing;
    std::vector<SolidRegion> solidRegions;
    if (g.tank) {
        const Box& t = *g.tank;
        checkBox(t, "geometry.tank");
        if (!isWholeMultiple(t.width(), l0) || !isWholeMultiple(t.height(), l0)) {
            throw SceneError("geometry.tank",
                             fmt::format("width {} m and height {} m must be whole multiples of "
                                         "particle_spacing {} m",
                                         t.width(), t.height(), l0));
        }
        const double L = layers * l0;
        solidRegions.push_back({Box{t.x0 - L, t.y0 - L, t.x1 + L, t.y0}, "geometry.tank (bed)"});
        solidRegions.push_back({Box{t.x0 - L, t.y0, t.x0, t.y1}, "geometry.tank (back wall)"});
        solidRegions.push_back({Box{t.x1, t.y0, t.x1 + L, t.y1}, "geometry.tank (front wall)"});
    }
    checkBed(g);
    if (g.solids.size() > kMaxSolids) {
        throw SceneError("geometry.solids",
                         fmt::format("{} blocks, more than the {} a scene may have: join blocks "
                                     "that touch into larger ones",
                                     g.solids.size(), kMaxSolids));
    }
    for (std::size_t s = 0; s < g.solids.size(); ++s) {
        const std::string key = fmt::format("geometry.solids[{}]", s);
        const Box& b = g.solids[s];
        checkBox(b, key);
        if (cellsIn(b.width(), l0) < 1 || cellsIn(b.height(), l0) < 1) {
            throw SceneError(key, "solid block is thinner than one particle spacing");
        }
        // Each block lays its own wall particles: two that overlap would stack particles on
        // one another (a clump the solver refuses at its first step).
        for (std::size_t o = 0; o < s; ++o) {
            if (b.overlaps(g.solids[o])) {
                throw SceneError(key, fmt::format("overlaps geometry.solids[{}]: solid blocks "
                                                  "may touch, not overlap",
                                                  o));
            }
        }
        solidRegions.push_back({b, key});
    }
    return solidRegions;
}

/// Checks each water rectangle and its cosine top: an amplitude below the rectangle's height in
/// size, and a positive wavelength where the amplitude is not 0.
void checkWaterTops(const GeometryParams& g) {
    for (std::size_t w = 0; w < g.water.size(); ++w) {
        checkBox(g.water[w], fmt::format("geometry.water[{}]", w));
        const CosineTop top = waterTop(g, w);
        const std::string key = fmt::format("geometry.water[{}].surface", w);
        if (!std::isfinite(top.amplitude) || !(std::abs(top.amplitude) < g.water[w].height()))
            throw SceneError(key + ".amplitude",
                             fmt::format("must be below the rectangle's height {} m in size, "
                                         "got {} m",
                                         g.water[w].height(), top.amplitude));
        if (top.amplitude != 0.0 && !(std::isfinite(top.wavelength) && top.wavelength > 0.0))
            throw SceneError(key + ".wavelength",
                             fmt::format("must be positive, got {} m", top.wavelength));
    }
}

/// Refuses water rectangle w overlapping an earlier one (each with its cosine top's amplitude).
void checkWaterOverlap(const GeometryParams& g, std::size_t w, const std::string& key) {
    // Each rectangle reaches up to its cosine top's crest.
    const auto reach = [&g](std::size_t v) {
        Box b = g.water[v];
        b.y1 += std::abs(waterTop(g, v).amplitude);
        return b;
    };
    const Box b = reach(w);
    for (std::size_t v = 0; v < w; ++v) {
        if (b.overlaps(reach(v)))
            throw SceneError(key, fmt::format("overlaps geometry.water[{}]", v));
    }
}

/// Only the solids that reach into the rectangle b can hold one of its particles.
std::vector<SolidRegion> solidsNear(const Box& b, const std::vector<SolidRegion>& solidRegions) {
    std::vector<SolidRegion> near;
    for (const auto& region : solidRegions) {
        const Box& r = region.first;
        if (r.x1 > b.x0 && r.x0 < b.x1 && r.y1 > b.y0 && r.y0 < b.y1)
            near.push_back(region);
    }
    return near;
}

/// Water rectangle w: lattice sites (x0 + (i + 1/2) l0, y0 + (j + 1/2) l0) under its cosine
/// top and above the bed; refuses one that holds no particle, overlaps an earlier one or puts
/// water inside a solid.
void addWater(const GeometryParams& g, std::size_t w, const std::vector<SolidRegion>& solidRegions,
              Particles& P) {
    const double l0 = g.particleSpacing;
    const std::string key = fmt::format("geometry.water[{}]", w);
    const Box& b = g.water[w];
    checkBox(b, key);
    const CosineTop top = waterTop(g, w);
    const long nx = cellsIn(b.width(), l0);
    const long ny = cellsIn(b.height() + std::abs(top.amplitude), l0);
    if (nx < 1 || ny < 1) {
        throw SceneError(
            key, fmt::format("holds no particle: {} x {} m is smaller than particle_spacing {} m",
                             b.width(), b.height(), l0));
    }
    checkWaterOverlap(g, w, key);
    const std::vector<SolidRegion> near = solidsNear(b, solidRegions);
    std::size_t held = 0;
    for (long j = 0; j < ny; ++j) {
        for (long i = 0; i < nx; ++i) {
            const double x = b.x0 + (static_cast<double>(i) + 0.5) * l0;
            const double y = b.y0 + (static_cast<double>(j) + 0.5) * l0;
            if (top.amplitude != 0.0 &&
                !(y < b.y1 + top.amplitude *
                                 std::cos(2.0 * std::numbers::pi * (x - b.x0) / top.wavelength)))
                continue; // above the cosine top
            for (const auto& [box, name] : near) {
                const double m = 0.25 * l0; // a particle centre strictly inside a solid
                if (x > box.x0 + m && x < box.x1 - m && y > box.y0 + m && y < box.y1 - m) {
                    throw SceneError(
                        key, fmt::format("water at ({:.6g}, {:.6g}) m lies inside {}", x, y, name));
                }
            }
            // Water starts l0 / 2 above the profile, one spacing above the bed's first layer
            // at b - l0 / 2: as on the flat bed, no closer (a closer start is a pressure
            // spike the textbook scheme cannot take), at most two spacings.
            if (!g.bed.empty() && depthUnder(bedHeight(g, x) + 0.5 * l0, y, l0) > 0.0)
                continue;
            P.add(x, y, ParticleKind::Water);
            ++held;
        }
    }
    if (held == 0)
        throw SceneError(key, "holds no particle: it lies wholly under geometry.bed");
}

/// Tank: bed (with corners) and two side walls; layer 0 is the one touching the water.
/// backWall marks the back-wall particles (1) for the piston.
void addTank(const GeometryParams& g, int layers, Particles& P,
             std::vector<std::uint8_t>& backWall) {
    const double l0 = g.particleSpacing;
    const Box& t = *g.tank;
    const long nIn = std::lround(t.width() / l0);
    // Bed extension behind the back wall (piston travel), in whole spacings.
    const long back = bedExtensionCells(g);
    // Each column stands on the bed's height at its x (the profile's, clamped to the tank;
    // y0 on a flat bed): its bed layers k below it, its side-wall sites above it. So the
    // bed follows the profile smoothly, one column at a time, instead of in lattice steps.
    const auto base = [&](double x) { return bedHeight(g, std::clamp(x, t.x0, t.x1)); };
    for (long k = 0; k < layers; ++k) { // bed rows, corners included
        for (long i = -layers - back; i < nIn + layers; ++i) {
            const double x = t.x0 + (static_cast<double>(i) + 0.5) * l0;
            const long side = i < -back ? -i - 1 - back : (i >= nIn ? i - nIn : 0);
            P.add(x, base(x) - (static_cast<double>(k) + 0.5) * l0,
                  layerKind(std::max(k, side), g.wallLayers));
        }
    }
    // Side walls from each column's base to the top y1: nUp sites on a flat bed.
    const auto sites = [&](double b) { return cellsIn(t.y1 - b, l0); };
    std::vector<double> xBack(layers), xFront(layers);
    for (long k = 0; k < layers; ++k) {
        xBack[k] = t.x0 - (static_cast<double>(k) + 0.5) * l0;
        xFront[k] = t.x1 + (static_cast<double>(k) + 0.5) * l0;
    }
    const long nUp = std::max(sites(base(t.x0)), sites(base(t.x1)));
    for (long j = 0; j < nUp; ++j) {
        const double up = (static_cast<double>(j) + 0.5) * l0;
        for (long k = 0; k < layers; ++k) {
            if (j < sites(base(xBack[k]))) {
                backWall.resize(P.size(), 0);
                backWall.push_back(1);
                P.add(xBack[k], base(xBack[k]) + up, layerKind(k, g.wallLayers));
            }
            if (j < sites(base(xFront[k])))
                P.add(xFront[k], base(xFront[k]) + up, layerKind(k, g.wallLayers));
        }
    }
}

/// Solid block: outer wallLayers are wall, the next dummyLayers dummy, the core is left empty.
void addSolidBlock(const GeometryParams& g, const Box& s, int layers, Particles& P) {
    const double l0 = g.particleSpacing;
    const long nx = cellsIn(s.width(), l0);
    const long ny = cellsIn(s.height(), l0);
    for (long j = 0; j < ny; ++j) {
        // Rows through the empty core visit only their outer `layers` sites at each end.
        const bool core = j >= layers && j < ny - layers;
        for (long i = 0; i < nx; ++i) {
            if (core && i == layers && nx - layers > i)
                i = nx - layers;
            const long layer = std::min({i, j, nx - 1 - i, ny - 1 - j});
            if (layer >= layers)
                continue;
            P.add(s.x0 + (static_cast<double>(i) + 0.5) * l0,
                  s.y0 + (static_cast<double>(j) + 0.5) * l0, layerKind(layer, g.wallLayers));
        }
    }
}

/// Stable order: water, wall, dummy (keeps indices meaningful for users and tests); the
/// back-wall particles' new indices go to out.backWall.
void sortByKind(GeneratedGeometry& out, std::vector<std::uint8_t>& backWall) {
    const Particles& P = out.particles;
    backWall.resize(P.size(), 0);
    const auto isBackWall = [&](std::size_t i) { return backWall[i] != 0; };
    Particles sorted;
    sorted.reserve(P.size());
    for (ParticleKind k : {ParticleKind::Water, ParticleKind::Wall, ParticleKind::Dummy}) {
        for (std::size_t i = 0; i < P.size(); ++i) {
            if (P.kind[i] != k)
                continue;
            if (k != ParticleKind::Water && isBackWall(i))
                out.backWall.push_back(static_cast<std::uint32_t>(sorted.size()));
            sorted.add(P.x[i], P.y[i], k);
        }
    }
    out.particles = std::move(sorted);
}

/// The domain: geometry.domain, which must hold every particle with a margin of one spacing,
/// or else the particles' extent grown by half its width either side, a quarter of its height
/// below and its height above.
Box domainOf(const GeometryParams& g, const Particles& particles) {
    const double l0 = g.particleSpacing;
    double bx0 = std::numeric_limits<double>::max(), by0 = bx0;
    double bx1 = std::numeric_limits<double>::lowest(), by1 = bx1;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        bx0 = std::min(bx0, particles.x[i]);
        bx1 = std::max(bx1, particles.x[i]);
        by0 = std::min(by0, particles.y[i]);
        by1 = std::max(by1, particles.y[i]);
    }
    bx0 -= l0;
    bx1 += l0;
    by0 -= l0;
    by1 += l0;
    if (g.domain) {
        checkBox(*g.domain, "geometry.domain");
        const Box& d = *g.domain;
        if (bx0 < d.x0 || bx1 > d.x1 || by0 < d.y0 || by1 > d.y1) {
            throw SceneError(
                "geometry.domain",
                fmt::format("must contain every particle with a margin of one "
                            "spacing: particles span [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m",
                            bx0 + l0, bx1 - l0, by0 + l0, by1 - l0));
        }
        return d;
    }
    const double w = bx1 - bx0;
    const double h = by1 - by0;
    return Box{bx0 - 0.5 * w, by0 - 0.25 * h, bx1 + 0.5 * w, by1 + h};
}

/// The solver's neighbour grid covers the domain with cells of at least l0: bound them here,
/// naming the key, rather than fail later inside the solver (NeighborGrid allows 5e7).
void checkDomainCells(const GeometryParams& g, const Box& domain) {
    const double l0 = g.particleSpacing;
    const double cells = std::ceil(domain.width() / l0) * std::ceil(domain.height() / l0);
    if (!(cells <= kMaxDomainCells)) {
        throw SceneError(g.domain ? "geometry.domain" : "geometry",
                         fmt::format("the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m is {:.4g} "
                                     "particle spacings square, more than {:.0e}{}",
                                     domain.x0, domain.x1, domain.y0, domain.y1, cells,
                                     kMaxDomainCells,
                                     g.domain ? "" : " (it grows with the rectangles' extent)"));
    }
}

} // namespace

double bedHeight(const GeometryParams& g, double x) {
    if (g.bed.empty())
        return g.tank ? g.tank->y0 : 0.0;
    if (x <= g.bed.front().x)
        return g.bed.front().y;
    if (x >= g.bed.back().x)
        return g.bed.back().y;
    const auto next = std::upper_bound(g.bed.begin(), g.bed.end(), x,
                                       [](double v, const BedPoint& p) { return v < p.x; });
    const BedPoint& b = *next;
    const BedPoint& a = *(next - 1);
    return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
}

GeneratedGeometry generateGeometry(const GeometryParams& g) {
    checkLattice(g);
    const int layers = g.wallLayers + g.dummyLayers;
    const std::vector<SolidRegion> solidRegions = solidRegionsOf(g, layers);
    checkWaterTops(g);
    checkParticleCount(g, layers);

    GeneratedGeometry out;
    std::vector<std::uint8_t> backWall; // 1 for the tank's back-wall particles (piston)
    for (std::size_t w = 0; w < g.water.size(); ++w)
        addWater(g, w, solidRegions, out.particles);
    if (g.tank)
        addTank(g, layers, out.particles, backWall);
    for (const Box& s : g.solids)
        addSolidBlock(g, s, layers, out.particles);
    sortByKind(out, backWall);
    out.domain = domainOf(g, out.particles);
    checkDomainCells(g, out.domain);
    return out;
}

long bedExtensionCells(const GeometryParams& g) {
    return static_cast<long>(
        std::ceil(std::max(0.0, g.bedExtensionBack) / g.particleSpacing - 1e-6));
}

void jitterWater(Particles& particles, double amplitude, std::uint64_t seed) {
    SplitMix64 rng(seed);
    for (std::size_t i = 0; i < particles.size(); ++i) {
        if (particles.kind[i] != ParticleKind::Water)
            continue;
        particles.x[i] += rng.uniform(-amplitude, amplitude);
        particles.y[i] += rng.uniform(-amplitude, amplitude);
    }
}

} // namespace swell::bake
