#include "swell/runtime/io/height_png.h"

#include "swell/runtime/io/atomic_write.h"
#include "swell/runtime/io/image_io.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace swell::runtime {

void writeHeightPng(const std::filesystem::path& path, const HeightField& field,
                    const HeightScale& scale) {
    std::vector<std::uint8_t> samples(field.heights.size() * 2);
    for (std::size_t i = 0; i < field.heights.size(); ++i) {
        const double v = std::round((field.heights[i] - scale.offset) / scale.scale);
        const auto q = static_cast<unsigned>(std::clamp(std::isfinite(v) ? v : 0.0, 0.0, 65535.0));
        samples[2 * i] = static_cast<std::uint8_t>(q >> 8); // PNG is big-endian
        samples[2 * i + 1] = static_cast<std::uint8_t>(q & 0xff);
    }
    writePngRaw(path, field.cellsX, field.cellsZ, PngLayout::Gray16, samples.data()); // atomic
}

HeightField readHeightPng(const std::filesystem::path& path, const HeightScale& scale) {
    HeightField out;
    const std::vector<std::uint8_t> samples =
        readPngRaw(path, PngLayout::Gray16, out.cellsX, out.cellsZ);
    out.heights.resize(samples.size() / 2);
    for (std::size_t i = 0; i < out.heights.size(); ++i) {
        const unsigned q = (static_cast<unsigned>(samples[2 * i]) << 8) | samples[2 * i + 1];
        out.heights[i] = scale.offset + q * scale.scale;
    }
    return out;
}

} // namespace swell::runtime
