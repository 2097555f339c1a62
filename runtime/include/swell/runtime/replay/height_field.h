#pragma once
// A reconstructed height field on the base mesh: h at every cell centre (eq. 7).

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace swell::runtime {

struct HeightField {
    int cellsX = 0;              ///< N
    int cellsZ = 0;              ///< M
    std::vector<double> heights; ///< metres (cache y); cell (n, m) at [m * N + n]

    /// At least one cell each way and one height per cell.
    bool wellFormed() const {
        return cellsX >= 1 && cellsZ >= 1 &&
               heights.size() ==
                   static_cast<std::size_t>(cellsX) * static_cast<std::size_t>(cellsZ);
    }

    double at(int n, int m) const {
        return heights[static_cast<std::size_t>(m) * static_cast<std::size_t>(cellsX) +
                       static_cast<std::size_t>(n)];
    }
};

/// How far one height field is from another (e.g. the GPU's from the CPU reference's), over
/// many fields; a non-finite height counts as an infinite difference.
struct HeightDifference {
    double maxAbs = 0.0;
    double sumSquares = 0.0;
    std::size_t cells = 0;

    /// Adds every cell of a against b (the same size).
    void add(const HeightField& a, const HeightField& b) {
        for (std::size_t i = 0; i < a.heights.size(); ++i) {
            const double d = std::isfinite(a.heights[i]) ? std::abs(a.heights[i] - b.heights[i])
                                                         : std::numeric_limits<double>::infinity();
            maxAbs = d > maxAbs ? d : maxAbs;
            sumSquares += d * d;
        }
        cells += a.heights.size();
    }
    double rms() const {
        return cells > 0 ? std::sqrt(sumSquares / static_cast<double>(cells)) : 0.0;
    }
};

} // namespace swell::runtime
