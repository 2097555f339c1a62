#include "swell/runtime/height_png.h"

#include "swell/runtime/error.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <memory>
#include <vector>

namespace swell::runtime {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

} // namespace

void writeHeightPng(const std::filesystem::path& path, const HeightField& field,
                    const HeightScale& scale) {
    const int W = field.cellsX;
    const int H = field.cellsZ;
    std::vector<png_byte> rows(static_cast<std::size_t>(W) * static_cast<std::size_t>(H) * 2);
    for (std::size_t i = 0; i < field.heights.size(); ++i) {
        const double v = std::round((field.heights[i] - scale.offset) / scale.scale);
        const auto q = static_cast<unsigned>(std::clamp(std::isfinite(v) ? v : 0.0, 0.0, 65535.0));
        rows[2 * i] = static_cast<png_byte>(q >> 8); // PNG is big-endian
        rows[2 * i + 1] = static_cast<png_byte>(q & 0xff);
    }
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
    if (!file)
        throw RuntimeError(fmt::format("cannot write {}", path.string()));
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) {
        png_destroy_write_struct(&png, &info);
        throw RuntimeError("libpng: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw RuntimeError(fmt::format("cannot write PNG {}", path.string()));
    }
    png_init_io(png, file.get());
    png_set_IHDR(png, info, static_cast<png_uint_32>(W), static_cast<png_uint_32>(H), 16,
                 PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < H; ++y)
        png_write_row(png, &rows[static_cast<std::size_t>(y) * W * 2]);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(file.get()) != 0)
        throw RuntimeError(fmt::format("cannot write {}", path.string()));
}

HeightField readHeightPng(const std::filesystem::path& path, const HeightScale& scale) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw RuntimeError(fmt::format("cannot open {}", path.string()));
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError("libpng: out of memory");
    }
    HeightField out;
    std::vector<png_byte> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("{} is not a readable PNG", path.string()));
    }
    png_init_io(png, file.get());
    png_read_info(png, info);
    if (png_get_bit_depth(png, info) != 16 ||
        png_get_color_type(png, info) != PNG_COLOR_TYPE_GRAY) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("{} is not a 16-bit greyscale height map", path.string()));
    }
    out.cellsX = static_cast<int>(png_get_image_width(png, info));
    out.cellsZ = static_cast<int>(png_get_image_height(png, info));
    rows.resize(static_cast<std::size_t>(out.cellsX) * static_cast<std::size_t>(out.cellsZ) * 2);
    for (int y = 0; y < out.cellsZ; ++y) {
        png_read_row(png, &rows[static_cast<std::size_t>(y) * out.cellsX * 2], nullptr);
    }
    png_destroy_read_struct(&png, &info, nullptr);
    out.heights.resize(rows.size() / 2);
    for (std::size_t i = 0; i < out.heights.size(); ++i) {
        const unsigned q = (static_cast<unsigned>(rows[2 * i]) << 8) | rows[2 * i + 1];
        out.heights[i] = scale.offset + q * scale.scale;
    }
    return out;
}

} // namespace swell::runtime
