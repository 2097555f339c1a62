#pragma once
// Height fields as 16-bit greyscale PNG: value v in 0..65535 means height offset + v * scale
// (metres). Row 0 of the image is z row m = 0; column n is x cell n. A folder of them and its
// sidecar: height_sequence.h.

#include "swell/runtime/replay/height_field.h"

#include <filesystem>

namespace swell::runtime {

/// The linear map between PNG values and metres.
struct HeightScale {
    double offset = 0.0; ///< height (m) of value 0
    double scale = 1.0;  ///< metres per unit value
};

/// Writes `field` quantised by `scale` (values rounded to nearest, clamped to 0..65535), under a
/// temporary name renamed when complete (atomic_write.h). Throws RuntimeError naming the file
/// on I/O failure.
void writeHeightPng(const std::filesystem::path& path, const HeightField& field,
                    const HeightScale& scale);
/// Reads a file written by writeHeightPng back to metres. Throws RuntimeError.
HeightField readHeightPng(const std::filesystem::path& path, const HeightScale& scale);

} // namespace swell::runtime
