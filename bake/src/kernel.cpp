#include "swell/bake/kernel.h"

#include <cmath>
#include <stdexcept>

namespace swell::bake {

LatticeConstants latticeConstants(double spacing, double re) {
    if (!(spacing > 0.0) || !(re > 0.0)) {
        throw std::invalid_argument("latticeConstants: spacing and re must be positive");
    }
    const int reach = static_cast<int>(std::ceil(re / spacing)) + 1;
    double sumW = 0.0;
    double sumR2W = 0.0;
    double halfSumY = 0.0; // sum of y w over the lower half lattice (y <= 0)
    for (int j = -reach; j <= reach; ++j) {
        for (int i = -reach; i <= reach; ++i) {
            if (i == 0 && j == 0)
                continue;
            const double r = spacing * std::hypot(static_cast<double>(i), static_cast<double>(j));
            const double w = mpsWeight(r, re);
            sumW += w;           // K&O 1996: n0 on the initial lattice
            sumR2W += r * r * w; // K&O 1996 Laplacian model: lambda = sum r^2 w / sum w
            if (j <= 0)
                halfSumY += spacing * j * w;
        }
    }
    if (!(sumW > 0.0))
        return {};
    return {sumW, sumR2W / sumW, std::abs(halfSumY) / (sumW * spacing)};
}

} // namespace swell::bake
