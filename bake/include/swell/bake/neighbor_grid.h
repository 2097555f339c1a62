#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "swell/bake/box.h"

namespace swell::bake {

/// Uniform cell grid over a fixed domain, rebuilt with a counting sort, and the
/// fixed-stride neighbour lists built from it. All memory is sized at configure():
/// build() allocates nothing.
class NeighborGrid {
public:
    /// Sizes the grid for `capacity` particles in `domain` with cells of side `cellSize`
    /// (m) and lists of up to `maxNeighbors` entries. Throws std::invalid_argument.
    void configure(const Box& domain, double cellSize, std::size_t capacity, int maxNeighbors);

    /// Counting sort of particles 0..count-1 into cells, then for each particle the list
    /// of others within `radius` (m), ordered by their position in the sorted order, and
    /// the sub-list of those within `shortRadius` (m, <= radius; 0: none) in the same order.
    /// Returns false (lists incomplete) if some particle has more than maxNeighbors
    /// neighbours; overflowParticle() names it. Throws std::out_of_range for a particle
    /// outside the domain (the solver checks the domain first, so that is a bug).
    bool build(std::span<const double> x, std::span<const double> y, double radius,
               double shortRadius = 0.0);

    std::size_t count() const { return m_count; }
    /// Particle indices in cell order (a space-filling order, good for locality).
    std::span<const std::uint32_t> sorted() const { return {m_sorted.data(), m_count}; }
    /// Position of particle i in sorted().
    std::uint32_t rank(std::size_t i) const { return m_rank[i]; }
    /// Neighbours of particle i (indices, excluding i), in increasing rank.
    std::span<const std::uint32_t> neighbors(std::size_t i) const {
        return {m_list.data() + i * m_stride, m_listCount[i]};
    }
    /// Neighbours of particle i within the short radius of the last build, in list order.
    std::span<const std::uint32_t> shortNeighbors(std::size_t i) const {
        return {m_shortList.data() + i * m_stride, m_shortCount[i]};
    }
    std::size_t overflowParticle() const { return m_overflow; }
    /// Cell of particle i at the last build.
    std::uint32_t cellIndex(std::size_t i) const { return m_cellOf[i]; }
    int cellsX() const { return m_nx; }
    int cellsY() const { return m_ny; }
    /// Cell index of a point inside the domain.
    int cellOf(double x, double y) const;

private:
    Box m_domain;
    double m_cell = 0.0;
    int m_nx = 0;
    int m_ny = 0;
    std::size_t m_stride = 0;
    std::size_t m_count = 0;
    std::size_t m_overflow = 0;
    std::vector<std::uint32_t> m_cellStart; // nCells + 1 prefix sums
    std::vector<std::uint32_t> m_cellOf;    // per particle
    std::vector<std::uint32_t> m_sorted;
    std::vector<std::uint32_t> m_rank;
    std::vector<std::uint32_t> m_list; // count x stride
    std::vector<std::uint32_t> m_listCount;
    std::vector<std::uint32_t> m_shortList; // count x stride: the sub-lists within shortRadius
    std::vector<std::uint32_t> m_shortCount;
};

} // namespace swell::bake
