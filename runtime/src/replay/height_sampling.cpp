#include "swell/runtime/replay/height_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace swell::runtime {
namespace {

void checkSize(const HeightField& field, const Grid& grid) {
    if (!field.wellFormed() || field.cellsX != grid.cellsX || field.cellsZ != grid.cellsZ)
        throw std::invalid_argument("height sampling: the height field does not match the grid");
}

/// Cell-centre coordinate u (centre n at u = n) clamped to [0, cells - 1], split into the
/// lower centre and the weight of the upper one.
void split(double u, int cells, int& lo, double& t) {
    u = std::clamp(u, 0.0, static_cast<double>(cells - 1));
    lo = std::min(static_cast<int>(u), std::max(cells - 2, 0));
    t = cells > 1 ? u - lo : 0.0;
}

double sampleChecked(const HeightField& field, const Grid& grid, double x, double z) {
    const double u = (x - grid.x0) / grid.dx; // cell coordinates: edge 0 at 0, centre n at n + 1/2
    const double v = z / grid.dz;
    if (!(u >= 0.0 && u <= grid.cellsX && v >= 0.0 && v <= grid.cellsZ))
        return std::numeric_limits<double>::quiet_NaN(); // outside, or NaN coordinates
    int n = 0, m = 0;
    double tx = 0.0, tz = 0.0;
    split(u - 0.5, grid.cellsX, n, tx);
    split(v - 0.5, grid.cellsZ, m, tz);
    const int n1 = std::min(n + 1, grid.cellsX - 1);
    const int m1 = std::min(m + 1, grid.cellsZ - 1);
    const double a = field.at(n, m) + tx * (field.at(n1, m) - field.at(n, m));
    const double b = field.at(n, m1) + tx * (field.at(n1, m1) - field.at(n, m1));
    return a + tz * (b - a);
}

} // namespace

double sampleHeight(const HeightField& field, const Grid& grid, double x, double z) {
    checkSize(field, grid);
    return sampleChecked(field, grid, x, z);
}

void sampleHeights(const HeightField& field, const Grid& grid, std::span<const double> x,
                   std::span<const double> z, std::span<double> out) {
    if (x.size() != z.size() || x.size() != out.size())
        throw std::invalid_argument("height sampling: x, z and the output differ in length");
    checkSize(field, grid);
    for (std::size_t i = 0; i < x.size(); ++i)
        out[i] = sampleChecked(field, grid, x[i], z[i]);
}

} // namespace swell::runtime
