#pragma once
// The environment of the shaded water (Sec. 5: "environmental cube mapping ... with the
// surrounding illumination"): six cube-map faces, by default a procedural sky (gradient,
// sun glow, soft clouds), or six user images.

#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/io/image_io.h"
#include "swell/runtime/render/camera.h"

#include <array>
#include <cstdint>
#include <filesystem>

namespace swell::runtime {

struct SkyParams {
    double sunAzimuthDegrees = 300.0;     ///< sun direction around y: 0 = +x, 90 = +z, degrees
    double sunElevationDegrees = 32.0;    ///< sun height above the horizon, degrees (-90, 90)
    Vec3 zenithColour{0.09, 0.26, 0.62};  ///< sky straight up, linear RGB 0..1
    Vec3 horizonColour{0.80, 0.86, 0.93}; ///< sky at the horizon (haze), linear RGB 0..1
    Vec3 groundColour{0.07, 0.12, 0.16};  ///< below the horizon, linear RGB 0..1
    double sunRadiusDegrees = 1.2;        ///< angular radius of the sun disc, (0, 10] degrees
    double sunGlow = 1.0;                 ///< strength of the glow around the sun, 0..4
    double cloudCover = 0.45;             ///< 0: clear sky .. 1: overcast
    std::uint64_t cloudSeed = 3;          ///< seed of the cloud pattern
    int faceSize = 256;                   ///< cube-face edge in texels

    /// Throws std::invalid_argument naming the field.
    void validate() const;
};

/// Unit vector towards the sun.
Vec3 sunDirection(const SkyParams& sky);

/// Cube-map faces in OpenGL order +x, -x, +y, -y, +z, -z; each square, row 0 at the top
/// (t = -1 in the GL cube-map face convention).
using CubeFaces = std::array<Image, 6>;

/// The procedural sky of `sky` (deterministic: same parameters, same bytes).
CubeFaces proceduralSky(const SkyParams& sky);
/// Six user images DIR/{px,nx,py,ny,pz,nz}.png (square, all one size). Throws RuntimeError
/// naming the missing or bad file.
CubeFaces loadSkyImages(const std::filesystem::path& dir);
/// Direction of texel (x, y) of face `face` (0..5) of an edge-`size` cube map (not normalised).
Vec3 cubeDirection(int face, int x, int y, int size);

/// The linear RGB radiance straight up: what sampling the cube map of `faces` at (0, 1, 0)
/// gives (sRGB-decoded texels at the centre of the +y face, bilinear). The diffuse sky light of
/// splash drops and the block's sides, passed to their shaders as a constant instead of a
/// cube-map lookup per fragment.
Vec3 zenithRadiance(const CubeFaces& faces);

/// A GL cube-map texture (sRGB8, mipmapped, bilinear within a level; seamless filtering is
/// enabled by the renderer).
/// Needs a current context. Throws std::invalid_argument for faces that are not square or
/// not all one size.
GlTexture makeCubemapTexture(const CubeFaces& faces);

} // namespace swell::runtime
