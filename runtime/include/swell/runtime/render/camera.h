#pragma once
// The render camera (Sec. 5 rendering; docs/render.md): a pinhole at `position` looking at
// `target`, y up, in the replay's world frame: x = propagation (cache x, metres), y = height (cache
// y), z = transverse (0 .. extentZ, the slices' axis).

#include "swell/cache/header.h"
#include "swell/runtime/replay/replay_params.h"

#include <array>

namespace swell::runtime {

using Vec3 = std::array<double, 3>;
/// A 4x4 matrix, column-major (OpenGL's layout): element (row r, column c) at [c * 4 + r].
using Mat4 = std::array<float, 16>;

struct Camera {
    Vec3 position{0.0, 1.0, 3.0}; ///< eye point, metres
    Vec3 target{0.0, 0.0, 0.0};   ///< point looked at, metres
    double fovYDegrees = 40.0;    ///< vertical field of view, degrees (0, 180)
    double nearPlane = 0.01;      ///< near clip distance, metres (> 0)
    double farPlane = 100.0;      ///< far clip distance, metres (> nearPlane)

    /// Throws std::invalid_argument naming the field (fov out of range, position == target,
    /// looking straight up or down, bad clip planes, non-finite values).
    void validate() const;
    /// Throws std::invalid_argument ("camera fov ...") unless `degrees` is in (0, 180): the part
    /// of validate() a field of view can be checked by before there is a camera.
    static void checkFov(double degrees);
};

/// The default camera's height above the horizon for the surging and ripple waves: low enough
/// that the horizon shows behind the block at the default 40 degree field of view.
inline constexpr double kDefaultCameraElevationDegrees = 16.0;

/// A three-quarter view of the whole base mesh: the eye looks across the propagation
/// direction (x) from the far z side, slightly against the waves, `elevationDegrees` above the
/// horizon (swell-play uses more for the whirlpool, whose spirals show best from above), at
/// the nearest distance where the box of the mesh (x and z extent, from the bed to halfway
/// between `waterLevel` and the domain's top) fills at most 92% of the picture at `aspect`
/// (width / height), with the box centred in the picture. Clip planes follow from the
/// distance.
Camera defaultCamera(const Grid& grid, const cache::Domain& domain, double waterLevel,
                     double aspect, double fovYDegrees = 40.0,
                     double elevationDegrees = kDefaultCameraElevationDegrees);

/// Right-handed view matrix (camera looks down -z, y up).
Mat4 viewMatrix(const Camera& camera);
/// OpenGL perspective projection (clip z in [-w, w]) for `aspect` = width / height.
Mat4 projectionMatrix(const Camera& camera, double aspect);
/// a * b.
Mat4 multiply(const Mat4& a, const Mat4& b);
/// Inverse of a general invertible 4x4 matrix; throws std::invalid_argument if singular.
Mat4 inverse(const Mat4& m);

} // namespace swell::runtime
