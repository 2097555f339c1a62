#pragma once
// Height fields as 16-bit greyscale PNG: value v in 0..65535 means height offset + v * scale
// (metres). Row 0 of the image is z row m = 0; column n is x cell n.

#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace swell::runtime {

/// The linear map between PNG values and metres.
struct HeightScale {
    double offset = 0.0; ///< height (m) of value 0
    double scale = 1.0;  ///< metres per unit value
};

/// Writes `field` quantised by `scale` (values rounded to nearest, clamped to 0..65535).
/// Throws RuntimeError naming the file on I/O failure.
void writeHeightPng(const std::filesystem::path& path, const HeightField& field,
                    const HeightScale& scale);
/// Reads a file written by writeHeightPng back to metres. Throws RuntimeError.
HeightField readHeightPng(const std::filesystem::path& path, const HeightScale& scale);

/// The sidecar of a folder of height PNGs (heights.json): `params` (every replay parameter and
/// the seed, as the program records them) plus the renderer, the PNG format and scale, the
/// layout, the grid (x0, dx, dz) and `frames` (file, tau, seconds per frame).
nlohmann::json heightsSidecar(nlohmann::json params, const HeightScale& scale, const Grid& grid,
                              const std::string& renderer, nlohmann::json frames);

} // namespace swell::runtime
