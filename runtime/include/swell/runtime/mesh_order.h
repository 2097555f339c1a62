#pragma once
// The triangles of the water mesh (an N x M grid of vertices, vertex m * N + n at
// (x0 + n dx, z0 + m dz)) ordered front to back from an eye point: the quads sorted by the
// horizontal distance of their centre to the eye. A height field seen from above hides mostly
// what lies behind it, so drawn in this order the depth test rejects hidden pixels before they
// are shaded (early z) instead of shading them and painting over them.

#include "swell/runtime/camera.h"

#include <cstdint>
#include <vector>

namespace swell::runtime {

struct MeshLayout {
    int verticesX = 0; ///< N
    int verticesZ = 0; ///< M
    double x0 = 0.0;   ///< x of vertex column 0, metres
    double z0 = 0.0;   ///< z of vertex row 0, metres
    double dx = 1.0;   ///< spacing along x, metres
    double dz = 1.0;   ///< spacing along z, metres
};

/// Indices of the 2 (N - 1)(M - 1) triangles, six per quad: for the quad with corners
/// a = m N + n, b = a + 1, c = a + N, d = c + 1 the triangles (a, c, b) and (b, c, d) (the
/// winding of the unsorted mesh), quads in order of increasing horizontal distance of their
/// centre to `eye` (ties: lower index first). Throws std::invalid_argument for fewer than
/// 2 x 2 vertices.
std::vector<std::uint32_t> frontToBackIndices(const MeshLayout& mesh, const Vec3& eye);

} // namespace swell::runtime
