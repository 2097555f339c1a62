#include "swell/bake/neighbor_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace swell::bake {

void NeighborGrid::configure(const Box& domain, double cellSize, std::size_t capacity,
                             int maxNeighbors) {
    if (!(cellSize > 0.0) || !(domain.width() > 0.0) || !(domain.height() > 0.0) ||
        maxNeighbors < 1) {
        throw std::invalid_argument(
            "NeighborGrid: need a non-empty domain, cellSize > 0, maxNeighbors >= 1");
    }
    const double nx = std::ceil(domain.width() / cellSize);
    const double ny = std::ceil(domain.height() / cellSize);
    if (nx * ny > 5e7) {
        throw std::invalid_argument("NeighborGrid: domain of " + std::to_string(nx * ny) +
                                    " cells is too large for the particle spacing");
    }
    m_domain = domain;
    m_cell = cellSize;
    m_nx = std::max(1, static_cast<int>(nx));
    m_ny = std::max(1, static_cast<int>(ny));
    m_stride = static_cast<std::size_t>(maxNeighbors);
    m_cellStart.assign(static_cast<std::size_t>(m_nx) * m_ny + 1, 0);
    m_cellOf.assign(capacity, 0);
    m_sorted.assign(capacity, 0);
    m_rank.assign(capacity, 0);
    m_list.assign(capacity * m_stride, 0);
    m_listCount.assign(capacity, 0);
    m_shortList.assign(capacity * m_stride, 0);
    m_shortCount.assign(capacity, 0);
    m_count = 0;
}

int NeighborGrid::cellOf(double x, double y) const {
    const int cx = std::min(m_nx - 1, static_cast<int>((x - m_domain.x0) / m_cell));
    const int cy = std::min(m_ny - 1, static_cast<int>((y - m_domain.y0) / m_cell));
    return cy * m_nx + cx;
}

bool NeighborGrid::build(std::span<const double> x, std::span<const double> y, double radius,
                         double shortRadius) {
    const std::size_t count = x.size();
    if (count > m_cellOf.size() || y.size() != count) {
        throw std::invalid_argument("NeighborGrid::build: more particles than configured");
    }
    if (radius > m_cell * (1.0 + 1e-12)) {
        throw std::invalid_argument("NeighborGrid::build: radius larger than the cell size");
    }
    if (shortRadius < 0.0 || shortRadius > radius) {
        throw std::invalid_argument("NeighborGrid::build: short radius outside [0, radius]");
    }
    m_count = count;
    // Counting sort: histogram, prefix sum, scatter (stable in particle index).
    std::fill(m_cellStart.begin(), m_cellStart.end(), 0u);
    for (std::size_t i = 0; i < count; ++i) {
        if (!m_domain.contains(x[i], y[i])) {
            throw std::out_of_range("NeighborGrid::build: particle " + std::to_string(i) +
                                    " is outside the domain");
        }
        const auto c = static_cast<std::uint32_t>(cellOf(x[i], y[i]));
        m_cellOf[i] = c;
        ++m_cellStart[c + 1];
    }
    for (std::size_t c = 1; c < m_cellStart.size(); ++c)
        m_cellStart[c] += m_cellStart[c - 1];
    // m_cellStart[c] is now the first slot of cell c; scatter, advancing it as a cursor.
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t c = m_cellOf[i];
        const std::uint32_t slot = m_cellStart[c]++;
        m_sorted[slot] = static_cast<std::uint32_t>(i);
    }
    // m_cellStart[c] now holds the end of cell c = start of c + 1: shift back.
    for (std::size_t c = m_cellStart.size() - 1; c > 0; --c)
        m_cellStart[c] = m_cellStart[c - 1];
    m_cellStart[0] = 0;
    for (std::size_t k = 0; k < count; ++k)
        m_rank[m_sorted[k]] = static_cast<std::uint32_t>(k);

    // Neighbour lists: each particle scans the 3x3 cells around it. Cells are visited in
    // increasing index and particles within a cell in increasing rank, so each list is
    // sorted by rank.
    const double r2max = radius * radius;
    const double r2short = shortRadius * shortRadius;
    std::size_t overflow = count;
#pragma omp parallel for schedule(static) reduction(min : overflow) if (count >= 4096)
    for (std::size_t i = 0; i < count; ++i) {
        const int c = static_cast<int>(m_cellOf[i]);
        const int cx = c % m_nx;
        const int cy = c / m_nx;
        std::uint32_t* out = m_list.data() + i * m_stride;
        std::uint32_t* outShort = m_shortList.data() + i * m_stride;
        std::size_t found = 0;
        std::size_t foundShort = 0;
        bool full = false;
        for (int jy = std::max(0, cy - 1); jy <= std::min(m_ny - 1, cy + 1); ++jy) {
            const int rowStart = jy * m_nx;
            const std::uint32_t begin =
                m_cellStart[static_cast<std::size_t>(rowStart + std::max(0, cx - 1))];
            const std::uint32_t end =
                m_cellStart[static_cast<std::size_t>(rowStart + std::min(m_nx - 1, cx + 1)) + 1];
            for (std::uint32_t k = begin; k < end; ++k) {
                const std::uint32_t j = m_sorted[k];
                if (j == i)
                    continue;
                const double dx = x[j] - x[i];
                const double dy = y[j] - y[i];
                const double r2 = dx * dx + dy * dy;
                if (r2 < r2max) {
                    if (found == m_stride) {
                        full = true;
                        break;
                    }
                    out[found++] = j;
                    if (r2 < r2short)
                        outShort[foundShort++] = j;
                }
            }
        }
        m_listCount[i] = static_cast<std::uint32_t>(found);
        m_shortCount[i] = static_cast<std::uint32_t>(foundShort);
        if (full)
            overflow = std::min(overflow, i);
    }
    m_overflow = overflow;
    return overflow == count;
}

} // namespace swell::bake
