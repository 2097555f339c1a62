#pragma once
// Height fields as OpenEXR images (libopenexr, scan lines, ZIP compression), for compositing
// and DCC tools that read linear floating-point data (docs/render.md, "OpenEXR outputs"):
//  - the height map: one channel "Y", the height in metres (cache y, not offset or scaled);
//  - the normal map: R, G, B = the unit surface normal (x, y, z), world space, y up;
//  - the displacement frame in the layout of Blender's Ocean-modifier bake (disp_####.exr):
//    R, G, B = the (x, y, z) displacement in metres, y up; a height field moves only
//    vertically, so R = B = 0 and G = height - reference level.
// Orientation as the 16-bit PNG (height_png.h): image row 0 (the top row, OpenEXR's y = 0,
// written first) is z cell m = 0 (z = (m + 1/2) dz), column n is x cell n
// (x = x0 + (n + 1/2) dx). Every writer writes a temporary file and renames it
// (atomic_write.h). Readers for the round trips.

#include "swell/runtime/replay/height_field.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace swell::runtime {

/// The sample type stored in the file (values are computed in double, converted once).
enum class ExrPixelType {
    Half,  ///< 16-bit float: 11 significant bits, relative error <= 2^-11 (0.5 mm at 1 m)
    Float, ///< 32-bit float: the GPU's own precision, the field read back exactly
};
/// "half" or "float".
const char* exrPixelTypeName(ExrPixelType type);

/// An EXR file as read back, every channel converted to float.
struct ExrImage {
    int width = 0;
    int height = 0;
    std::vector<std::string> channels; ///< names in the file's order (OpenEXR sorts them)
    std::vector<std::string> types;    ///< per channel: "half", "float" or "uint"
    std::string compression;           ///< "zip", "none", "piz", ...
    std::string comments;              ///< the standard "comments" attribute, if any
    std::vector<float> samples;        ///< rows top to bottom, channels interleaved

    /// Index of channel `name`; throws std::out_of_range naming it when absent.
    std::size_t channel(const std::string& name) const;
    /// Sample of channel `c` at column x, row y.
    float at(int x, int y, std::size_t c) const {
        return samples[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(x)) *
                           channels.size() +
                       c];
    }
};

/// The single channel of a greyscale height map. "Y" is OpenEXR's luminance channel: a file
/// with only "Y" is a greyscale image to OpenEXR's RGBA interface, Blender (which copies Y into
/// R, G and B), Nuke and OpenImageIO, so every viewer shows the heights as grey levels.
inline constexpr const char* kHeightChannel = "Y";

/// Writes `field` as a one-channel ("Y") EXR, metres. Throws std::invalid_argument for a
/// malformed field and RuntimeError naming the file on I/O failure.
void writeHeightExr(const std::filesystem::path& path, const HeightField& field, ExrPixelType type);
/// Reads a height map written by writeHeightExr (exactly one channel "Y"). Throws RuntimeError
/// naming the file (missing, not EXR, damaged or truncated, other channels).
HeightField readHeightExr(const std::filesystem::path& path);

/// Unit surface normals at every cell centre, y up: normalize(-dh/dx, 1, -dh/dz) with central
/// differences of the neighbouring heights, one-sided at the edges: the normal the renderer
/// shades with (shaders/surface_vertices.comp). Three values (x, y, z) per cell, cell (n, m)
/// at [3 (m N + n)]. Throws std::invalid_argument for a malformed field or dx, dz <= 0.
std::vector<double> surfaceNormals(const HeightField& field, double dx, double dz);
/// Writes surfaceNormals(field, dx, dz) as R, G, B = x, y, z in [-1, 1] (world space, y up;
/// not the 0..1 encoding of tangent-space normal maps). Throws as writeHeightExr.
void writeNormalExr(const std::filesystem::path& path, const HeightField& field, double dx,
                    double dz, ExrPixelType type);

/// Writes the displacement of each cell from a flat surface at `referenceLevel` (m) as
/// Blender's Ocean modifier bakes it: R, G, B = x, y, z displacement (metres, y up), so
/// R = 0, G = height - referenceLevel, B = 0. Throws as writeHeightExr.
void writeDisplacementExr(const std::filesystem::path& path, const HeightField& field,
                          double referenceLevel, ExrPixelType type);

/// Reads any scan-line EXR of half, float or uint channels. Throws RuntimeError naming the
/// file (missing, not EXR, damaged or truncated).
ExrImage readExr(const std::filesystem::path& path);

} // namespace swell::runtime
