#pragma once
// Per-frame exports for other tools (docs/render.md): the surface as a triangle mesh and the splash
// particles as a point cloud, both binary little-endian PLY (Blender, MeshLab, ParaView read
// it), with a reader for the same subset so every format is tested by a round trip. Height
// maps are written by height_png.h (16-bit PNG with a JSON scale) and height_exr.h (OpenEXR
// height, normal and displacement maps), a folder of them by height_sequence.h.

#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace swell::runtime {

struct SplashSprite; // render/splash_system.h: the exporters write what the renderer draws

/// The height field as a mesh: one vertex per cell centre (x = x0 + (n + 1/2) dx, y = h,
/// z = (m + 1/2) dz; vertex m * N + n, as drawn by the renderer), two triangles per quad,
/// counter-clockwise seen from above (+y).
struct SurfaceMesh {
    std::vector<float> positions;         ///< x, y, z per vertex, metres
    std::vector<std::uint32_t> triangles; ///< three vertex indices per triangle
};
/// Throws std::invalid_argument when the field and grid disagree or N, M < 2.
SurfaceMesh makeSurfaceMesh(const HeightField& field, const Grid& grid);

/// A PLY file as read back: vertex properties (all float32) and optional faces.
struct PlyData {
    std::vector<std::string> vertexProperties; ///< names in file order, e.g. x, y, z
    std::vector<float> vertices;               ///< vertexProperties.size() values per vertex
    std::vector<std::uint32_t> triangles;      ///< three indices per face (faces must be triangles)
    std::string comment;                       ///< the first comment line, if any
};

/// Binary little-endian PLY with vertex x y z and triangle faces. Throws RuntimeError naming
/// the file on I/O failure.
void writeSurfacePly(const std::filesystem::path& path, const SurfaceMesh& mesh,
                     const std::string& comment = "");
/// Binary little-endian PLY point cloud, vertex x y z alpha (opacity 0..1).
void writeSplashPly(const std::filesystem::path& path, std::span<const SplashSprite> sprites,
                    const std::string& comment = "");
/// Reads binary little-endian PLY files of float vertex properties and (uchar count,
/// int/uint indices) triangle faces: what the writers above produce. Throws RuntimeError naming
/// the file and the problem (not PLY, other format, truncated, a non-triangle face, an index
/// out of range).
PlyData readPly(const std::filesystem::path& path);

} // namespace swell::runtime
