#include "swell/runtime/io/height_exr.h"

#include "swell/runtime/error.h"
#include "swell/runtime/io/atomic_write.h"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStdIO.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <stdexcept>

namespace swell::runtime {
namespace {

void checkField(const HeightField& field, const char* what) {
    if (!field.wellFormed()) {
        throw std::invalid_argument(fmt::format("{}: the field has {} heights for {} x {} cells",
                                                what, field.heights.size(), field.cellsX,
                                                field.cellsZ));
    }
}

/// Writes `channels` (names) of width x height pixels, `samples` interleaved per pixel, rows
/// top to bottom (OpenEXR's increasing y, its default line order), as one scan-line part with
/// ZIP compression (zlib over blocks of 16 rows: lossless, what Blender's Ocean bake uses).
/// Half samples are rounded to nearest by Imath::half (OpenEXR converts only when reading).
void writeExr(const std::filesystem::path& path, int width, int height,
              const std::vector<std::string>& channels, const std::vector<float>& samples,
              ExrPixelType type, const std::string& comments) {
    const std::size_t count = channels.size();
    if (samples.size() !=
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * count) {
        throw std::logic_error("writeExr: samples do not match the image size");
    }
    const bool half = type == ExrPixelType::Half;
    const Imf::PixelType pixelType = half ? Imf::HALF : Imf::FLOAT;
    std::vector<Imath::half> halves;
    if (half)
        halves.assign(samples.begin(), samples.end());
    // OpenEXR only reads the frame buffer (the cast is its API's, not a write).
    char* base = half ? reinterpret_cast<char*>(halves.data())
                      : const_cast<char*>(reinterpret_cast<const char*>(samples.data()));
    const std::size_t size = half ? sizeof(Imath::half) : sizeof(float);
    // Encoded in memory (the OutputFile destructor, which writes the offsets, cannot report a
    // full disk), then written atomically through writeBytesAtomically, which can.
    std::ostringstream encoded;
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::addComments(header, comments);
        Imf::FrameBuffer frame;
        for (std::size_t c = 0; c < count; ++c) {
            header.channels().insert(channels[c], Imf::Channel(pixelType));
            frame.insert(channels[c], Imf::Slice(pixelType, base + c * size, size * count,
                                                 size * count * static_cast<std::size_t>(width)));
        }
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frame);
            file.writePixels(height);
        }
        encoded << stream.str();
    } catch (const std::exception& e) {
        throw RuntimeError(fmt::format("cannot encode EXR {}: {}", path.string(), e.what()));
    }
    writeBytesAtomically(path, encoded.view());
}

const char* compressionName(Imf::Compression c) {
    switch (c) {
    case Imf::NO_COMPRESSION:
        return "none";
    case Imf::RLE_COMPRESSION:
        return "rle";
    case Imf::ZIPS_COMPRESSION:
        return "zips";
    case Imf::ZIP_COMPRESSION:
        return "zip";
    case Imf::PIZ_COMPRESSION:
        return "piz";
    case Imf::PXR24_COMPRESSION:
        return "pxr24";
    case Imf::B44_COMPRESSION:
        return "b44";
    case Imf::B44A_COMPRESSION:
        return "b44a";
    case Imf::DWAA_COMPRESSION:
        return "dwaa";
    case Imf::DWAB_COMPRESSION:
        return "dwab";
    default:
        return "other";
    }
}

const char* pixelTypeName(Imf::PixelType t) {
    switch (t) {
    case Imf::HALF:
        return "half";
    case Imf::FLOAT:
        return "float";
    default:
        return "uint";
    }
}

} // namespace

const char* exrPixelTypeName(ExrPixelType type) {
    return type == ExrPixelType::Half ? "half" : "float";
}

std::size_t ExrImage::channel(const std::string& name) const {
    const auto it = std::find(channels.begin(), channels.end(), name);
    if (it == channels.end())
        throw std::out_of_range("the EXR image has no channel " + name);
    return static_cast<std::size_t>(it - channels.begin());
}

void writeHeightExr(const std::filesystem::path& path, const HeightField& field,
                    ExrPixelType type) {
    checkField(field, "writeHeightExr");
    const std::vector<float> samples(field.heights.begin(), field.heights.end());
    writeExr(path, field.cellsX, field.cellsZ, {kHeightChannel}, samples, type,
             "swell height map: Y = height (m, y up) at each cell centre; row m = z cell, column "
             "n = x cell (heights.json: x0, dx, dz)");
}

HeightField readHeightExr(const std::filesystem::path& path) {
    const ExrImage image = readExr(path);
    if (image.channels != std::vector<std::string>{kHeightChannel}) {
        throw RuntimeError(fmt::format("{} is not a height map: it has {} channel(s), not the one "
                                       "channel {}",
                                       path.string(), image.channels.size(), kHeightChannel));
    }
    HeightField out;
    out.cellsX = image.width;
    out.cellsZ = image.height;
    out.heights.assign(image.samples.begin(), image.samples.end());
    return out;
}

std::vector<double> surfaceNormals(const HeightField& field, double dx, double dz) {
    checkField(field, "surfaceNormals");
    if (!(dx > 0.0) || !(dz > 0.0) || !std::isfinite(dx) || !std::isfinite(dz))
        throw std::invalid_argument(fmt::format("surfaceNormals: dx = {}, dz = {} m", dx, dz));
    const int N = field.cellsX, M = field.cellsZ;
    std::vector<double> normals(field.heights.size() * 3);
    for (int m = 0; m < M; ++m) {
        const int m0 = std::max(m - 1, 0), m1 = std::min(m + 1, M - 1);
        for (int n = 0; n < N; ++n) {
            const int n0 = std::max(n - 1, 0), n1 = std::min(n + 1, N - 1);
            // Central differences; one-sided at an edge; 0 across a single cell.
            const double dhdx = (field.at(n1, m) - field.at(n0, m)) / (std::max(n1 - n0, 1) * dx);
            const double dhdz = (field.at(n, m1) - field.at(n, m0)) / (std::max(m1 - m0, 1) * dz);
            const double length = std::sqrt(dhdx * dhdx + 1.0 + dhdz * dhdz);
            double* out = &normals[3 * (static_cast<std::size_t>(m) * N + n)];
            out[0] = -dhdx / length;
            out[1] = 1.0 / length;
            out[2] = -dhdz / length;
        }
    }
    return normals;
}

void writeNormalExr(const std::filesystem::path& path, const HeightField& field, double dx,
                    double dz, ExrPixelType type) {
    const std::vector<double> normals = surfaceNormals(field, dx, dz);
    const std::vector<float> samples(normals.begin(), normals.end());
    writeExr(path, field.cellsX, field.cellsZ, {"R", "G", "B"}, samples, type,
             "swell normal map: R, G, B = unit normal x, y, z (world space, y up, -1..1) by "
             "central differences of the heights; row m = z cell, column n = x cell");
}

void writeDisplacementExr(const std::filesystem::path& path, const HeightField& field,
                          double referenceLevel, ExrPixelType type) {
    checkField(field, "writeDisplacementExr");
    std::vector<float> samples(field.heights.size() * 3, 0.0f);
    for (std::size_t i = 0; i < field.heights.size(); ++i)
        samples[3 * i + 1] = static_cast<float>(field.heights[i] - referenceLevel);
    writeExr(path, field.cellsX, field.cellsZ, {"R", "G", "B"}, samples, type,
             fmt::format("swell displacement (Blender Ocean-cache layout): R, G, B = x, y, z "
                         "displacement (m, y up); G = height - {} m; row m = z cell, column n = "
                         "x cell",
                         referenceLevel));
}

ExrImage readExr(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path))
        throw RuntimeError(fmt::format("cannot open {}", path.string()));
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (!file.isComplete())
            throw std::runtime_error("incomplete (truncated)");
        const Imath::Box2i window = header.dataWindow();
        ExrImage image;
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        image.compression = compressionName(header.compression());
        if (Imf::hasComments(header))
            image.comments = Imf::comments(header);
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            image.channels.emplace_back(it.name());
            image.types.emplace_back(pixelTypeName(it.channel().type));
        }
        const std::size_t count = image.channels.size();
        image.samples.assign(static_cast<std::size_t>(image.width) *
                                 static_cast<std::size_t>(image.height) * count,
                             0.0f);
        Imf::FrameBuffer frame;
        const std::size_t xStride = sizeof(float) * count;
        for (std::size_t c = 0; c < count; ++c) {
            frame.insert(image.channels[c],
                         Imf::Slice::Make(Imf::FLOAT, image.samples.data() + c, window.min,
                                          image.width, image.height, xStride,
                                          xStride * static_cast<std::size_t>(image.width)));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const std::exception& e) {
        throw RuntimeError(fmt::format("cannot read EXR {}: {}", path.string(), e.what()));
    }
}

} // namespace swell::runtime
