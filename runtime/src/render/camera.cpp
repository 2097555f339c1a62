#include "swell/runtime/render/camera.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

namespace swell::runtime {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 normalized(const Vec3& a) {
    const double l = std::sqrt(dot(a, a));
    return {a[0] / l, a[1] / l, a[2] / l};
}
bool finite(const Vec3& a) {
    return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

} // namespace

void Camera::checkFov(double degrees) {
    if (!(degrees > 0.0 && degrees < 180.0))
        throw std::invalid_argument(
            fmt::format("camera fov must be in (0, 180) degrees, got {}", degrees));
}

void Camera::validate() const {
    if (!finite(position) || !finite(target))
        throw std::invalid_argument("camera position and target must be finite");
    checkFov(fovYDegrees);
    const Vec3 d = sub(target, position);
    const double len = std::sqrt(dot(d, d));
    if (!(len > 0.0))
        throw std::invalid_argument("camera position and target coincide");
    if (std::abs(d[1]) / len > 0.9999)
        throw std::invalid_argument("camera looks straight up or down (no up direction)");
    if (!(nearPlane > 0.0) || !(farPlane > nearPlane) || !std::isfinite(farPlane)) {
        throw std::invalid_argument(fmt::format(
            "camera clip planes need 0 < near < far, got {} and {}", nearPlane, farPlane));
    }
}

Camera defaultCamera(const Grid& grid, const cache::Domain& domain, double waterLevel,
                     double aspect, double fovYDegrees, double elevationDegrees) {
    using std::numbers::pi;
    const double sizeX = grid.cellsX * grid.dx;
    const double sizeZ = grid.extentZ;
    // The box to frame: the mesh's x and z extent, from the bed to halfway between the water
    // level and the top of the domain (splashes rarely fly higher).
    const double yLow = domain.yMin;
    const double yHigh =
        waterLevel + 0.5 * std::max(0.0, static_cast<double>(domain.yMax) - waterLevel);
    Camera c;
    c.fovYDegrees = fovYDegrees;
    c.target = {grid.x0 + 0.5 * sizeX, waterLevel, 0.5 * sizeZ};
    const double radius =
        0.5 * std::sqrt(sizeX * sizeX + sizeZ * sizeZ + (yHigh - yLow) * (yHigh - yLow));
    if (!(elevationDegrees > 0.0 && elevationDegrees < 90.0))
        throw std::invalid_argument("default camera elevation must be in (0, 90) degrees");
    const double elevation = elevationDegrees * pi / 180.0;
    const double azimuth = -35.0 * pi / 180.0; // from +z towards -x: the waves run to the right
    const Vec3 dir{std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                   std::cos(elevation) * std::cos(azimuth)};
    const double margin = 0.92; // the box fills at most 92% of the picture
    // NDC bounds (x0, x1, y0, y1) of the box's 8 corners seen from `target + distance dir`, or
    // false if a corner is behind the eye.
    auto bounds = [&](const Vec3& target, double distance, double out[4]) {
        Camera t = c;
        t.target = target;
        t.position = {target[0] + distance * dir[0], target[1] + distance * dir[1],
                      target[2] + distance * dir[2]};
        t.nearPlane = 1e-4 * distance;
        t.farPlane = 10.0 * distance;
        const Mat4 vp = multiply(projectionMatrix(t, aspect), viewMatrix(t));
        out[0] = out[2] = 1e300;
        out[1] = out[3] = -1e300;
        for (int k = 0; k < 8; ++k) {
            const double x = grid.x0 + ((k & 1) ? sizeX : 0.0);
            const double y = (k & 2) ? yHigh : yLow;
            const double z = (k & 4) ? sizeZ : 0.0;
            double p[4];
            for (int r = 0; r < 4; ++r)
                p[r] = vp[r] * x + vp[4 + r] * y + vp[8 + r] * z + vp[12 + r];
            if (p[3] <= 0.0)
                return false;
            out[0] = std::min(out[0], p[0] / p[3]);
            out[1] = std::max(out[1], p[0] / p[3]);
            out[2] = std::min(out[2], p[1] / p[3]);
            out[3] = std::max(out[3], p[1] / p[3]);
        }
        return true;
    };
    const Vec3 right = normalized(cross({-dir[0], -dir[1], -dir[2]}, {0.0, 1.0, 0.0}));
    const Vec3 up = cross(right, {-dir[0], -dir[1], -dir[2]});
    const double tanY = std::tan(0.5 * fovYDegrees * pi / 180.0);
    double distance = 0.0;
    for (int pass = 0; pass < 4; ++pass) {
        // The nearest distance where the box fits (bisection), then move the target sideways
        // and up or down so that the box's picture is centred.
        auto fits = [&](double d) {
            double b[4];
            return bounds(c.target, d, b) && std::max(-b[0], b[1]) <= margin &&
                   std::max(-b[2], b[3]) <= margin;
        };
        double lo = 0.0, hi = std::max(radius, 1e-6);
        while (!fits(hi))
            hi *= 2.0;
        for (int i = 0; i < 50; ++i) {
            const double mid = 0.5 * (lo + hi);
            (fits(mid) ? hi : lo) = mid;
        }
        distance = hi;
        double b[4];
        bounds(c.target, distance, b);
        const double sx = 0.5 * (b[0] + b[1]) * tanY * aspect * distance;
        const double sy = 0.5 * (b[2] + b[3]) * tanY * distance;
        for (int k = 0; k < 3; ++k)
            c.target[k] += sx * right[k] + sy * up[k];
    }
    c.position = {c.target[0] + distance * dir[0], c.target[1] + distance * dir[1],
                  c.target[2] + distance * dir[2]};
    c.nearPlane = std::max(distance - 2.0 * radius, distance * 0.02);
    c.farPlane = (distance + radius) * 50.0;
    return c;
}

Mat4 viewMatrix(const Camera& camera) {
    const Vec3 f = normalized(sub(camera.target, camera.position));
    const Vec3 s = normalized(cross(f, {0.0, 1.0, 0.0}));
    const Vec3 u = cross(s, f);
    const Vec3& e = camera.position;
    Mat4 m{};
    m[0] = static_cast<float>(s[0]);
    m[4] = static_cast<float>(s[1]);
    m[8] = static_cast<float>(s[2]);
    m[1] = static_cast<float>(u[0]);
    m[5] = static_cast<float>(u[1]);
    m[9] = static_cast<float>(u[2]);
    m[2] = static_cast<float>(-f[0]);
    m[6] = static_cast<float>(-f[1]);
    m[10] = static_cast<float>(-f[2]);
    m[12] = static_cast<float>(-dot(s, e));
    m[13] = static_cast<float>(-dot(u, e));
    m[14] = static_cast<float>(dot(f, e));
    m[15] = 1.0f;
    return m;
}

Mat4 projectionMatrix(const Camera& camera, double aspect) {
    const double t = 1.0 / std::tan(0.5 * camera.fovYDegrees * std::numbers::pi / 180.0);
    const double n = camera.nearPlane, f = camera.farPlane;
    Mat4 m{};
    m[0] = static_cast<float>(t / aspect);
    m[5] = static_cast<float>(t);
    m[10] = static_cast<float>((f + n) / (n - f));
    m[11] = -1.0f;
    m[14] = static_cast<float>(2.0 * f * n / (n - f));
    return m;
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (int c = 0; c < 4; ++c) {
        for (int row = 0; row < 4; ++row) {
            double s = 0.0;
            for (int k = 0; k < 4; ++k)
                s += static_cast<double>(a[k * 4 + row]) * b[c * 4 + k];
            r[c * 4 + row] = static_cast<float>(s);
        }
    }
    return r;
}

Mat4 inverse(const Mat4& m) {
    // Gauss-Jordan elimination with partial pivoting, in double precision.
    double a[4][8];
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            a[r][c] = m[c * 4 + r];
            a[r][c + 4] = r == c ? 1.0 : 0.0;
        }
    }
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int r = c + 1; r < 4; ++r) {
            if (std::abs(a[r][c]) > std::abs(a[p][c]))
                p = r;
        }
        if (std::abs(a[p][c]) < 1e-300)
            throw std::invalid_argument("singular matrix");
        if (p != c)
            std::swap(a[p], a[c]);
        const double inv = 1.0 / a[c][c];
        for (double& v : a[c])
            v *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c)
                continue;
            const double k = a[r][c];
            for (int j = 0; j < 8; ++j)
                a[r][j] -= k * a[c][j];
        }
    }
    Mat4 r{};
    for (int row = 0; row < 4; ++row) {
        for (int c = 0; c < 4; ++c)
            r[c * 4 + row] = static_cast<float>(a[row][c + 4]);
    }
    return r;
}

} // namespace swell::runtime
