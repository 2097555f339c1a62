#include "swell/runtime/render/mesh_order.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace swell::runtime {

std::vector<std::uint32_t> frontToBackIndices(const MeshLayout& mesh, const Vec3& eye) {
    const int N = mesh.verticesX, M = mesh.verticesZ;
    if (N < 2 || M < 2)
        throw std::invalid_argument("frontToBackIndices: the mesh needs at least 2 x 2 vertices");
    const int quadsX = N - 1;
    const std::size_t quads = static_cast<std::size_t>(quadsX) * static_cast<std::size_t>(M - 1);
    std::vector<double> distance(quads);
    for (std::size_t q = 0; q < quads; ++q) {
        const auto n = static_cast<double>(q % static_cast<std::size_t>(quadsX));
        const auto m = static_cast<double>(q / static_cast<std::size_t>(quadsX));
        const double ex = mesh.x0 + (n + 0.5) * mesh.dx - eye[0];
        const double ez = mesh.z0 + (m + 0.5) * mesh.dz - eye[2];
        distance[q] = ex * ex + ez * ez;
    }
    std::vector<std::uint32_t> order(quads);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return distance[a] < distance[b]; });
    std::vector<std::uint32_t> indices;
    indices.reserve(quads * 6);
    for (std::uint32_t q : order) {
        const std::uint32_t n = q % static_cast<std::uint32_t>(quadsX);
        const std::uint32_t m = q / static_cast<std::uint32_t>(quadsX);
        const std::uint32_t a = m * static_cast<std::uint32_t>(N) + n, b = a + 1;
        const std::uint32_t c = a + static_cast<std::uint32_t>(N), d = c + 1;
        for (std::uint32_t i : {a, c, b, b, c, d})
            indices.push_back(i);
    }
    return indices;
}

std::array<bool, 4> visibleSides(const MeshLayout& mesh, double bedY, const Vec3& eye) {
    if (!(eye[1] > bedY))
        return {true, true, true, true};
    const double x1 = mesh.x0 + (mesh.verticesX - 1) * mesh.dx;
    const double z1 = mesh.z0 + (mesh.verticesZ - 1) * mesh.dz;
    std::array<bool, 4> outside{};
    outside[0] = eye[2] < mesh.z0;
    outside[1] = eye[2] > z1;
    outside[2] = eye[0] < mesh.x0;
    outside[3] = eye[0] > x1;
    return outside;
}

} // namespace swell::runtime
