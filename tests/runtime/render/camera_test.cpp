// The render camera: view and projection matrices, the inverse, the default framing.
#include "swell/runtime/render/camera.h"

#include "render/render_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace swell::runtime {
namespace {

Grid testGrid() {
    return test::renderGrid();
}

const cache::Domain kDomain = test::kRenderDomain;

std::array<double, 4> transform(const Mat4& m, double x, double y, double z) {
    std::array<double, 4> r{};
    for (int row = 0; row < 4; ++row)
        r[row] = m[row] * x + m[4 + row] * y + m[8 + row] * z + m[12 + row];
    return r;
}

TEST(Camera, TargetProjectsToTheCentreAndInverseInverts) {
    Camera c;
    c.position = {1.0, 2.0, 5.0};
    c.target = {0.5, 0.3, -1.0};
    const Mat4 vp = multiply(projectionMatrix(c, 16.0 / 9.0), viewMatrix(c));
    const auto t = transform(vp, 0.5, 0.3, -1.0);
    EXPECT_NEAR(t[0] / t[3], 0.0, 1e-5);
    EXPECT_NEAR(t[1] / t[3], 0.0, 1e-5);
    EXPECT_GT(t[3], 0.0); // in front of the camera
    const auto e = transform(viewMatrix(c), 1.0, 2.0, 5.0);
    EXPECT_NEAR(e[0], 0.0, 1e-5); // the eye is the origin of view space
    EXPECT_NEAR(e[2], 0.0, 1e-5);
    const Mat4 id = multiply(inverse(vp), vp);
    for (int i = 0; i < 16; ++i)
        EXPECT_NEAR(id[i], i % 5 == 0 ? 1.0f : 0.0f, 1e-4) << i;
    EXPECT_THROW(inverse(Mat4{}), std::invalid_argument);
}

TEST(Camera, DefaultFramingShowsTheWholeMesh) {
    const Grid g = testGrid();
    for (double aspect : {16.0 / 9.0, 1.0, 0.6}) {
        for (double elevation : {28.0, 55.0}) {
            const Camera c = defaultCamera(g, kDomain, 0.5, aspect, 40.0, elevation);
            EXPECT_NO_THROW(c.validate());
            const Mat4 vp = multiply(projectionMatrix(c, aspect), viewMatrix(c));
            for (double x : {g.x0, g.x0 + g.cellsX * g.dx}) {
                for (double y : {0.0, 0.9}) {
                    for (double z : {0.0, g.extentZ}) {
                        const auto p = transform(vp, x, y, z);
                        ASSERT_GT(p[3], 0.0);
                        EXPECT_LE(std::abs(p[0] / p[3]), 1.0) << aspect << " " << x << " " << z;
                        EXPECT_LE(std::abs(p[1] / p[3]), 1.0) << aspect << " " << y;
                        EXPECT_GT(p[2] / p[3], -1.0); // not clipped by the near plane
                        EXPECT_LT(p[2] / p[3], 1.0);
                    }
                }
            }
        }
    }
    EXPECT_THROW(defaultCamera(g, kDomain, 0.5, 1.0, 40.0, 90.0), std::invalid_argument);
}

TEST(Camera, ValidateNamesTheProblem) {
    Camera c;
    c.fovYDegrees = 180.0;
    EXPECT_THROW(c.validate(), std::invalid_argument);
    c = Camera{};
    c.target = c.position;
    EXPECT_THROW(c.validate(), std::invalid_argument);
    c = Camera{};
    c.target = {c.position[0], c.position[1] - 3.0, c.position[2]}; // straight down
    EXPECT_THROW(c.validate(), std::invalid_argument);
    c = Camera{};
    c.nearPlane = 0.0;
    EXPECT_THROW(c.validate(), std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
