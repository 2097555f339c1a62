// The water mesh's triangles ordered front to back from the eye (for early depth rejection).
#include "swell/runtime/render/mesh_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>
#include <stdexcept>

namespace swell::runtime {
namespace {

const MeshLayout kMesh{5, 4, 1.0, 2.0, 0.5, 0.25}; // 4 x 3 quads

double quadDistance(const MeshLayout& mesh, const Vec3& eye, std::uint32_t a) {
    const double n = a % static_cast<std::uint32_t>(mesh.verticesX);
    const double m = a / static_cast<std::uint32_t>(mesh.verticesX);
    const double ex = mesh.x0 + (n + 0.5) * mesh.dx - eye[0];
    const double ez = mesh.z0 + (m + 0.5) * mesh.dz - eye[2];
    return ex * ex + ez * ez;
}

TEST(MeshOrder, EveryQuadOnceWithTheGridsWinding) {
    const std::vector<std::uint32_t> idx = frontToBackIndices(kMesh, {0.0, 3.0, 0.0});
    ASSERT_EQ(idx.size(), 4u * 3u * 6u);
    std::set<std::uint32_t> corners;
    for (std::size_t t = 0; t < idx.size(); t += 6) {
        const std::uint32_t a = idx[t], N = 5;
        const std::array<std::uint32_t, 6> expected{a, a + N, a + 1, a + 1, a + N, a + N + 1};
        for (std::size_t k = 0; k < 6; ++k)
            EXPECT_EQ(idx[t + k], expected[k]);
        EXPECT_LT(a % N, N - 1); // a is a quad's first corner
        EXPECT_TRUE(corners.insert(a).second) << "quad " << a << " twice";
    }
    EXPECT_EQ(corners.size(), 12u);
}

TEST(MeshOrder, QuadsGoFromNearToFar) {
    for (const Vec3& eye : {Vec3{0.0, 3.0, 0.0}, Vec3{4.0, 1.0, 9.0}, Vec3{2.0, 5.0, 2.4}}) {
        const std::vector<std::uint32_t> idx = frontToBackIndices(kMesh, eye);
        for (std::size_t t = 6; t < idx.size(); t += 6) {
            EXPECT_LE(quadDistance(kMesh, eye, idx[t - 6]), quadDistance(kMesh, eye, idx[t]));
        }
    }
    // Seen from far +z, the last row (m = 2) comes first and row 0 last.
    const std::vector<std::uint32_t> idx = frontToBackIndices(kMesh, {2.0, 1.0, 50.0});
    EXPECT_EQ(idx.front() / 5, 2u);
    EXPECT_EQ(idx[idx.size() - 6] / 5, 0u); // the last quad's first corner
}

TEST(MeshOrder, TooSmallMeshThrows) {
    EXPECT_THROW(frontToBackIndices({1, 4, 0.0, 0.0, 1.0, 1.0}, {0.0, 1.0, 0.0}),
                 std::invalid_argument);
    EXPECT_THROW(frontToBackIndices({4, 1, 0.0, 0.0, 1.0, 1.0}, {0.0, 1.0, 0.0}),
                 std::invalid_argument);
}

TEST(MeshOrder, OnlyTheSidesTheEyeIsOutsideOfShow) {
    // kMesh spans x in [x0, x1], z in [z0, z1]; sides: 0 z = z0, 1 z = z1, 2 x = x0, 3 x = x1.
    const double x1 = kMesh.x0 + (kMesh.verticesX - 1) * kMesh.dx;
    const double z1 = kMesh.z0 + (kMesh.verticesZ - 1) * kMesh.dz;
    const double xm = 0.5 * (kMesh.x0 + x1), zm = 0.5 * (kMesh.z0 + z1);
    const double bed = -1.0;
    using Sides = std::array<bool, 4>;
    EXPECT_EQ(visibleSides(kMesh, bed, {xm, 2.0, z1 + 3.0}), (Sides{false, true, false, false}));
    EXPECT_EQ(visibleSides(kMesh, bed, {kMesh.x0 - 1.0, 2.0, kMesh.z0 - 1.0}),
              (Sides{true, false, true, false}));
    EXPECT_EQ(visibleSides(kMesh, bed, {x1 + 2.0, 0.5, zm}), (Sides{false, false, false, true}));
    // Straight above the water: none; from below the bed, through the open bottom: all four.
    EXPECT_EQ(visibleSides(kMesh, bed, {xm, 2.0, zm}), (Sides{false, false, false, false}));
    EXPECT_EQ(visibleSides(kMesh, bed, {xm, -3.0, z1 + 3.0}), (Sides{true, true, true, true}));
}

} // namespace
} // namespace swell::runtime
