#pragma once
// The triangles of the water mesh (an N x M grid of vertices, vertex m * N + n at
// (x0 + n dx, z0 + m dz)) ordered front to back from an eye point: the quads sorted by the
// horizontal distance of their centre to the eye. A height field seen from above hides mostly
// what lies behind it, so drawn in this order the depth test rejects hidden pixels before they
// are shaded (early z) instead of shading them and painting over them.

#include "swell/runtime/render/camera.h"

#include <array>
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

/// Which of the block's four sides (walls from the mesh's edge rows down to the bed at `bedY`)
/// can be seen from `eye`: 0: z = z0 (row 0), 1: the last row, 2: x = x0 (column 0), 3: the last
/// column. A side is a plane: from above the bed the eye sees it only from outside, as the
/// others face away behind the water and the near sides (the block is closed but for its
/// bottom). From the bed or below, through the open bottom, all four may show.
std::array<bool, 4> visibleSides(const MeshLayout& mesh, double bedY, const Vec3& eye);

} // namespace swell::runtime
