#pragma once
// 8-bit RGB images: PNG I/O (libpng), image differences for the golden test (PSNR, max error),
// box downscaling and the contact sheet of a render (docs/render.md).

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace swell::runtime {

/// An 8-bit RGB image, rows top to bottom, pixels interleaved R, G, B.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb; ///< width * height * 3 bytes

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
    std::uint8_t* pixel(int x, int y) {
        return rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
    }
    const std::uint8_t* pixel(int x, int y) const {
        return rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
    }
};

/// Sample layouts of the raw PNG I/O below.
enum class PngLayout {
    Rgb8,   ///< 3 bytes per pixel
    Gray16, ///< 2 bytes per pixel, big-endian (as PNG stores them)
};
/// Writes `height` rows of `width` pixels of raw samples in `layout`. Throws RuntimeError
/// naming the file.
void writePngRaw(const std::filesystem::path& path, int width, int height, PngLayout layout,
                 const std::uint8_t* samples, int compression = 6);
/// Reads a PNG that is exactly of `layout` (no conversion); sets width and height. Throws
/// RuntimeError naming the file (missing, not a PNG, damaged, another layout).
std::vector<std::uint8_t> readPngRaw(const std::filesystem::path& path, PngLayout layout,
                                     int& width, int& height);

/// Writes an 8-bit RGB PNG. `compression` is zlib's level 0..9 (1: fast, for sequences).
/// Throws RuntimeError naming the file on I/O failure.
void writePng(const std::filesystem::path& path, const Image& image, int compression = 6);
/// Reads any 8- or 16-bit PNG (grey, grey + alpha, RGB, RGBA, palette) as 8-bit RGB; alpha is
/// dropped. Throws RuntimeError naming the file (missing, not a PNG, damaged).
Image readPng(const std::filesystem::path& path);

/// How two images of the same size differ, over all channels.
struct ImageDifference {
    double psnr = 0.0;    ///< dB; +infinity when identical (peak 255)
    int maxAbs = 0;       ///< largest channel difference, 0..255
    double meanAbs = 0.0; ///< mean channel difference
};
/// Throws std::invalid_argument when the sizes differ.
ImageDifference compareImages(const Image& a, const Image& b);

/// Mean and standard deviation of the luminance (0..255) and the number of distinct colours:
/// what the not-blank test looks at.
struct ImageStats {
    double meanLuma = 0.0;
    double stddevLuma = 0.0;
    std::size_t distinctColours = 0;
};
ImageStats imageStats(const Image& image);

/// Box-filtered downscale by an integer factor (>= 1); partial edge blocks are averaged too.
Image downscale(const Image& image, int factor);
/// Tiles `images` (all of one size) `columns` per row, with a `gap`-pixel dark border.
/// Throws std::invalid_argument for no images or mixed sizes.
Image contactSheet(std::span<const Image> images, int columns, int gap = 4);

} // namespace swell::runtime
