#pragma once
// A folder of per-frame height maps, as `swell-play heights` writes it and `swell-play render
// --export heights` writes into heights/ (docs/runtime.md, docs/render.md): for output frame i
//  - height_{i:05}.png (16-bit greyscale, height_png.h) or height_{i:05}.exr (one channel "Y",
//    half or float metres, height_exr.h),
//  - optionally normal_{i:05}.exr (unit normals, y up) and disp_{i+1:04}.exr (Blender's
//    Ocean-cache displacement: numbered from 1, Blender's first frame, 4 digits as Blender's
//    bake names them),
// and heights.json, the sidecar naming the frames, the format, the scale and the grid. Every
// file is written under a temporary name and renamed when complete (atomic_write.h).

#include "swell/runtime/io/height_exr.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace swell::runtime {

/// The file format of the height maps.
enum class HeightFormat {
    Png16,    ///< 16-bit greyscale PNG, quantised by the domain's HeightScale
    ExrHalf,  ///< one-channel EXR, 16-bit float metres
    ExrFloat, ///< one-channel EXR, 32-bit float metres (the GPU's values exactly)
};
/// The option values of the formats, in the order above.
inline constexpr const char* kHeightFormatNames = "png16, exr-half or exr-float";
/// "png16", "exr-half" or "exr-float".
const char* heightFormatName(HeightFormat format);
/// Parses one of kHeightFormatNames; throws std::invalid_argument naming `option`, the value
/// and the valid values.
HeightFormat parseHeightFormat(const std::string& value, const std::string& option);

/// What is written per frame.
struct HeightSequenceParams {
    HeightFormat format = HeightFormat::Png16;
    bool normals = false;      ///< normal_NNNNN.exr too
    bool displacement = false; ///< disp_NNNN.exr too (Blender's Ocean-cache layout)

    /// The sample type of the EXR files: half with ExrHalf, float otherwise.
    ExrPixelType exrPixelType() const {
        return format == HeightFormat::ExrHalf ? ExrPixelType::Half : ExrPixelType::Float;
    }
};

/// The level the displacement is measured from: the still water when the bake recorded it.
struct ReferenceLevel {
    double y = 0.0;     ///< m (cache y)
    std::string source; ///< how it was chosen, for the sidecar
};

/// File names of output frame i.
std::string heightFileName(std::size_t i, HeightFormat format);
std::string normalFileName(std::size_t i);
/// disp_{i + 1:04}.exr: Blender frame i + 1.
std::string displacementFileName(std::size_t i);

/// Writes the frames of one sequence into a folder (which must exist) and then its sidecar.
class HeightSequence {
public:
    /// `pngScale`: the 16-bit PNG's scale (the domain's); `grid`: the replay's mesh.
    HeightSequence(std::filesystem::path dir, const HeightSequenceParams& params,
                   const HeightScale& pngScale, const Grid& grid, ReferenceLevel reference);

    /// Writes output frame `index` (files named by the functions above) and returns its
    /// sidecar entry: file (the height map), normals and disp when written, tau, seconds.
    /// Throws RuntimeError naming the file on I/O failure.
    const nlohmann::json& write(std::size_t index, const HeightField& field, double tau,
                                double seconds);

    /// The map from stored values to metres: height_m = offset + value * scale; the PNG's
    /// scale, or {0, 1} for EXR (metres as they are).
    HeightScale scale() const;
    /// One line on the height maps' format, e.g. "16-bit greyscale PNG; height_m = offset +
    /// value * scale".
    std::string formatDescription() const;
    /// The sidecar: `params` (every replay parameter and the seed, as the program records them)
    /// plus the renderer, height_format, format, scale, exr (channel, pixel type, compression),
    /// layout and orientation, the grid (cells, x0, dx, dz), normals and displacement (files,
    /// channels, reference level) when written, count and frames (the entries of write()).
    nlohmann::json sidecar(nlohmann::json params, const std::string& renderer) const;
    /// Writes sidecar(params, renderer) to DIR/heights.json; returns its path. Throws
    /// RuntimeError naming the file on I/O failure.
    std::filesystem::path writeSidecar(nlohmann::json params, const std::string& renderer) const;

    const HeightSequenceParams& params() const { return m_params; }

private:
    std::filesystem::path m_dir;
    HeightSequenceParams m_params;
    HeightScale m_pngScale;
    Grid m_grid;
    ReferenceLevel m_reference;
    nlohmann::json m_frames = nlohmann::json::array();
};

} // namespace swell::runtime
