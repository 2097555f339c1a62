#include "swell/runtime/io/height_sequence.h"

#include "swell/runtime/io/atomic_write.h"

#include <fmt/format.h>
#include <stdexcept>
#include <utility>

namespace swell::runtime {

using json = nlohmann::json;

const char* heightFormatName(HeightFormat format) {
    switch (format) {
    case HeightFormat::ExrHalf:
        return "exr-half";
    case HeightFormat::ExrFloat:
        return "exr-float";
    default:
        return "png16";
    }
}

HeightFormat parseHeightFormat(const std::string& value, const std::string& option) {
    for (HeightFormat f : {HeightFormat::Png16, HeightFormat::ExrHalf, HeightFormat::ExrFloat}) {
        if (value == heightFormatName(f))
            return f;
    }
    throw std::invalid_argument(
        fmt::format("{} takes {}; got '{}'", option, kHeightFormatNames, value));
}

std::string heightFileName(std::size_t i, HeightFormat format) {
    return fmt::format("height_{:05d}.{}", i, format == HeightFormat::Png16 ? "png" : "exr");
}

std::string normalFileName(std::size_t i) {
    return fmt::format("normal_{:05d}.exr", i);
}

std::string displacementFileName(std::size_t i) {
    return fmt::format("disp_{:04d}.exr", i + 1);
}

HeightSequence::HeightSequence(std::filesystem::path dir, const HeightSequenceParams& params,
                               const HeightScale& pngScale, const Grid& grid,
                               ReferenceLevel reference)
    : m_dir(std::move(dir)), m_params(params), m_pngScale(pngScale), m_grid(grid),
      m_reference(std::move(reference)) {}

const json& HeightSequence::write(std::size_t index, const HeightField& field, double tau,
                                  double seconds) {
    const ExrPixelType type = m_params.exrPixelType();
    json entry{{"file", heightFileName(index, m_params.format)}};
    const auto path = [&](const char* key) { return m_dir / entry[key].get<std::string>(); };
    if (m_params.format == HeightFormat::Png16)
        writeHeightPng(path("file"), field, m_pngScale);
    else
        writeHeightExr(path("file"), field, type);
    if (m_params.normals) {
        entry["normals"] = normalFileName(index);
        writeNormalExr(path("normals"), field, m_grid.dx, m_grid.dz, type);
    }
    if (m_params.displacement) {
        entry["disp"] = displacementFileName(index);
        writeDisplacementExr(path("disp"), field, m_reference.y, type);
    }
    entry["tau"] = tau;
    entry["seconds"] = seconds;
    m_frames.push_back(std::move(entry));
    return m_frames.back();
}

HeightScale HeightSequence::scale() const {
    return m_params.format == HeightFormat::Png16 ? m_pngScale : HeightScale{0.0, 1.0};
}

std::string HeightSequence::formatDescription() const {
    if (m_params.format == HeightFormat::Png16)
        return "16-bit greyscale PNG; height_m = offset + value * scale";
    return fmt::format("OpenEXR, one {} channel {} (ZIP); height_m = value (offset 0, scale 1)",
                       exrPixelTypeName(m_params.exrPixelType()), kHeightChannel);
}

json HeightSequence::sidecar(json params, const std::string& renderer) const {
    const HeightScale s = scale();
    const std::string pixel = exrPixelTypeName(m_params.exrPixelType());
    params.update({
        {"renderer", renderer},
        {"height_format", heightFormatName(m_params.format)},
        {"format", formatDescription()},
        {"scale", {{"offset", s.offset}, {"scale", s.scale}, {"units", "m"}}},
        {"layout", "column n = x cell (x = x0 + (n + 0.5) dx), row m = z cell (z = (m + 0.5) dz)"},
        {"orientation", "image row 0 (the top row, written first) is z cell m = 0; heights are "
                        "cache y, y up"},
        {"cells", {m_grid.cellsX, m_grid.cellsZ}},
        {"x0", m_grid.x0},
        {"dx", m_grid.dx},
        {"dz", m_grid.dz},
        {"count", m_frames.size()},
        {"frames", m_frames},
    });
    if (m_params.format != HeightFormat::Png16)
        params["exr"] = {
            {"channel", kHeightChannel}, {"pixel_type", pixel}, {"compression", "zip"}};
    if (m_params.normals) {
        params["normals"] = {
            {"files", "normal_NNNNN.exr (frame entries: normals)"},
            {"channels", {{"R", "normal x"}, {"G", "normal y (up)"}, {"B", "normal z"}}},
            {"meaning", "unit normal, world space, -1..1: normalize(-dh/dx, 1, -dh/dz), central "
                        "differences (one-sided at the edges)"},
            {"pixel_type", pixel},
            {"compression", "zip"}};
    }
    if (m_params.displacement) {
        params["displacement"] = {
            {"files", "disp_NNNN.exr (frame entries: disp)"},
            {"layout", "Blender Ocean modifier cache"},
            {"first_number", 1},
            {"numbering", "output frame i is disp_{i + 1:04}.exr (Blender frame i + 1)"},
            {"channels",
             {{"R", "x displacement (0)"},
              {"G", "y displacement (up) = height - reference_level_m"},
              {"B", "z displacement (0)"}}},
            {"units", "m"},
            {"reference_level_m", m_reference.y},
            {"reference", m_reference.source},
            {"pixel_type", pixel},
            {"compression", "zip"}};
    }
    return params;
}

std::filesystem::path HeightSequence::writeSidecar(json params, const std::string& renderer) const {
    const std::filesystem::path path = m_dir / "heights.json";
    writeTextAtomically(path, sidecar(std::move(params), renderer).dump(2) + "\n");
    return path;
}

} // namespace swell::runtime
