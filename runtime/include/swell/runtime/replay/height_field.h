#pragma once
// A reconstructed height field on the base mesh: h at every cell centre (eq. 7).

#include <cstddef>
#include <vector>

namespace swell::runtime {

struct HeightField {
    int cellsX = 0;              ///< N
    int cellsZ = 0;              ///< M
    std::vector<double> heights; ///< metres (cache y); cell (n, m) at [m * N + n]

    double at(int n, int m) const {
        return heights[static_cast<std::size_t>(m) * static_cast<std::size_t>(cellsX) +
                       static_cast<std::size_t>(n)];
    }
};

} // namespace swell::runtime
