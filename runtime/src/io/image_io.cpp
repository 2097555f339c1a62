#include "swell/runtime/io/image_io.h"

#include "swell/runtime/error.h"
#include "swell/runtime/io/atomic_write.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_set>

namespace swell::runtime {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

// libpng reports through these; the error is turned into RuntimeError at the setjmp, so
// nothing is printed on stderr.
[[noreturn]] void pngError(png_structp png, png_const_charp) {
    png_longjmp(png, 1);
}
void pngWarning(png_structp, png_const_charp) {}
void appendPng(png_structp png, png_bytep data, png_size_t size) {
    static_cast<std::string*>(png_get_io_ptr(png))
        ->append(reinterpret_cast<const char*>(data), size);
}

} // namespace

void writePngRaw(const std::filesystem::path& path, int width, int height, PngLayout layout,
                 const std::uint8_t* samples, int compression) {
    if (width <= 0 || height <= 0 || samples == nullptr)
        throw std::logic_error("writePngRaw: malformed image");
    const bool rgb = layout == PngLayout::Rgb8;
    const std::size_t rowBytes = static_cast<std::size_t>(width) * (rgb ? 3 : 2);
    // Encoded in memory, then written atomically: a failed write leaves no PNG behind.
    std::string bytes;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) {
        png_destroy_write_struct(&png, &info);
        throw RuntimeError("libpng: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throw RuntimeError(fmt::format("cannot encode PNG {}", path.string()));
    }
    png_set_write_fn(png, &bytes, appendPng, nullptr);
    png_set_compression_level(png, std::clamp(compression, 0, 9));
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height),
                 rgb ? 8 : 16, rgb ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(samples + static_cast<std::size_t>(y) * rowBytes));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    writeBytesAtomically(path, bytes);
}

std::vector<std::uint8_t> readPngRaw(const std::filesystem::path& path, PngLayout layout,
                                     int& width, int& height) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw RuntimeError(fmt::format("cannot open {}", path.string()));
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError("libpng: out of memory");
    }
    std::vector<std::uint8_t> samples;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("{} is not a readable PNG", path.string()));
    }
    png_init_io(png, file.get());
    png_read_info(png, info);
    const bool rgb = layout == PngLayout::Rgb8;
    if (png_get_bit_depth(png, info) != (rgb ? 8 : 16) ||
        png_get_color_type(png, info) != (rgb ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY)) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("{} is not a {} PNG", path.string(),
                                       rgb ? "8-bit RGB" : "16-bit greyscale"));
    }
    width = static_cast<int>(png_get_image_width(png, info));
    height = static_cast<int>(png_get_image_height(png, info));
    const std::size_t rowBytes = static_cast<std::size_t>(width) * (rgb ? 3 : 2);
    samples.resize(rowBytes * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        png_read_row(png, &samples[static_cast<std::size_t>(y) * rowBytes], nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return samples;
}

void writePng(const std::filesystem::path& path, const Image& image, int compression) {
    if (image.width <= 0 || image.height <= 0 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
        throw std::logic_error("writePng: malformed image");
    }
    writePngRaw(path, image.width, image.height, PngLayout::Rgb8, image.rgb.data(), compression);
}

Image readPng(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw RuntimeError(fmt::format("cannot open {}", path.string()));
    png_byte signature[8] = {};
    if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
        throw RuntimeError(fmt::format("{} is not a PNG file", path.string()));
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (png == nullptr || info == nullptr) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError("libpng: out of memory");
    }
    // Everything that owns memory lives before setjmp: a libpng error longjmps back here and
    // the throw below then destroys it (objects made after setjmp would leak).
    Image image;
    std::vector<png_bytep> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("cannot read PNG {} (damaged)", path.string()));
    }
    png_init_io(png, file.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    // Normalise every colour type and depth to 8-bit RGB.
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_packing(png);
    png_set_palette_to_rgb(png);
    png_set_expand_gray_1_2_4_to_8(png);
    png_set_gray_to_rgb(png);
    png_read_update_info(png, info);
    const auto w = static_cast<int>(png_get_image_width(png, info));
    const auto h = static_cast<int>(png_get_image_height(png, info));
    if (png_get_rowbytes(png, info) != static_cast<std::size_t>(w) * 3) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw RuntimeError(fmt::format("{}: unsupported PNG layout", path.string()));
    }
    image = Image(w, h);
    rows.resize(static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
        rows[static_cast<std::size_t>(y)] = image.pixel(0, y);
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return image;
}

ImageDifference compareImages(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size()) {
        throw std::invalid_argument(fmt::format("images differ in size: {}x{} and {}x{}", a.width,
                                                a.height, b.width, b.height));
    }
    double sumSq = 0.0, sumAbs = 0.0;
    int maxAbs = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const int d = std::abs(static_cast<int>(a.rgb[i]) - static_cast<int>(b.rgb[i]));
        maxAbs = std::max(maxAbs, d);
        sumAbs += d;
        sumSq += static_cast<double>(d) * d;
    }
    const double n = static_cast<double>(std::max<std::size_t>(a.rgb.size(), 1));
    const double mse = sumSq / n;
    ImageDifference r;
    r.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                        : 10.0 * std::log10(255.0 * 255.0 / mse);
    r.maxAbs = maxAbs;
    r.meanAbs = sumAbs / n;
    return r;
}

ImageStats imageStats(const Image& image) {
    ImageStats s;
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
    if (n == 0)
        return s;
    double sum = 0.0, sumSq = 0.0;
    std::unordered_set<std::uint32_t> colours;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = &image.rgb[3 * i];
        const double luma = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += luma;
        sumSq += luma * luma;
        colours.insert(static_cast<std::uint32_t>(p[0]) << 16 |
                       static_cast<std::uint32_t>(p[1]) << 8 | p[2]);
    }
    s.meanLuma = sum / static_cast<double>(n);
    s.stddevLuma =
        std::sqrt(std::max(0.0, sumSq / static_cast<double>(n) - s.meanLuma * s.meanLuma));
    s.distinctColours = colours.size();
    return s;
}

Image downscale(const Image& image, int factor) {
    if (factor < 1)
        throw std::invalid_argument("downscale factor must be >= 1");
    if (factor == 1)
        return image;
    const int w = (image.width + factor - 1) / factor;
    const int h = (image.height + factor - 1) / factor;
    Image out(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            int sum[3] = {0, 0, 0};
            int count = 0;
            for (int yy = y * factor; yy < std::min(image.height, (y + 1) * factor); ++yy) {
                for (int xx = x * factor; xx < std::min(image.width, (x + 1) * factor); ++xx) {
                    const std::uint8_t* p = image.pixel(xx, yy);
                    for (int c = 0; c < 3; ++c)
                        sum[c] += p[c];
                    ++count;
                }
            }
            std::uint8_t* q = out.pixel(x, y);
            for (int c = 0; c < 3; ++c)
                q[c] = static_cast<std::uint8_t>((sum[c] + count / 2) / count);
        }
    }
    return out;
}

Image contactSheet(std::span<const Image> images, int columns, int gap) {
    if (images.empty())
        throw std::invalid_argument("contact sheet of no images");
    const int w = images[0].width, h = images[0].height;
    for (const Image& im : images) {
        if (im.width != w || im.height != h)
            throw std::invalid_argument("contact sheet images differ in size");
    }
    columns = std::clamp(columns, 1, static_cast<int>(images.size()));
    const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
    Image sheet(gap + columns * (w + gap), gap + rows * (h + gap));
    std::fill(sheet.rgb.begin(), sheet.rgb.end(), std::uint8_t{24});
    for (std::size_t i = 0; i < images.size(); ++i) {
        const int ox = gap + static_cast<int>(i) % columns * (w + gap);
        const int oy = gap + static_cast<int>(i) / columns * (h + gap);
        for (int y = 0; y < h; ++y) {
            std::copy_n(images[i].pixel(0, y), static_cast<std::size_t>(w) * 3,
                        sheet.pixel(ox, oy + y));
        }
    }
    return sheet;
}

} // namespace swell::runtime
