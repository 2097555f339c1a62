#pragma once
// Heights at arbitrary points of the base mesh (gameplay queries such as buoyancy, as engine
// water APIs offer them): bilinear interpolation between the cell centres of a height field.

#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"

#include <span>

namespace swell::runtime {

/// Height (metres) at (x, z) on `grid`'s mesh: bilinear between the four nearest cell centres
/// (x_n = x0 + (n + 1/2) dx, z_m = (m + 1/2) dz); within half a cell of the mesh's edge, the
/// edge centres' values (clamped). NaN for a point outside [x0, x0 + N dx] x [0, extentZ] (no
/// water there) or a non-finite coordinate. Throws std::invalid_argument if the field and grid
/// disagree in size.
double sampleHeight(const HeightField& field, const Grid& grid, double x, double z);

/// sampleHeight for every (x[i], z[i]) into out[i]; the three spans have one length
/// (std::invalid_argument otherwise).
void sampleHeights(const HeightField& field, const Grid& grid, std::span<const double> x,
                   std::span<const double> z, std::span<double> out);

} // namespace swell::runtime
