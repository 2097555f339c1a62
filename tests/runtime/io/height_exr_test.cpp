// OpenEXR height, normal and displacement maps (height_exr.h): round trips in half and float,
// the orientation and greyscale channel as OpenEXR's own RGBA interface sees them, normals
// against analytic surfaces, and clear errors for bad paths and damaged files.
#include "swell/runtime/error.h"
#include "swell/runtime/io/height_exr.h"

#include "temp_dir.h"

#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

/// A 37 x 21 field of heights around 0.4 m that no half or float represents exactly.
HeightField wavyField() {
    HeightField f;
    f.cellsX = 37;
    f.cellsZ = 21;
    for (int m = 0; m < f.cellsZ; ++m) {
        for (int n = 0; n < f.cellsX; ++n)
            f.heights.push_back(0.4 + 0.1 * std::sin(n * 0.3 + m * 0.7) + 1e-9 * n);
    }
    return f;
}

/// Largest relative rounding error of a half (10 stored mantissa bits, round to nearest),
/// plus the float the value passes through on its way.
constexpr double kHalfRelative = 1.0 / 2048.0 + 1e-7;

std::size_t filesIn(const fs::path& dir) {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

} // namespace

TEST(HeightExr, FloatRoundTripIsExactAndZipCompressed) {
    const HeightField f = wavyField();
    const swell::test::TempDir temp("swell_height_exr_");
    const fs::path path = temp / "height.exr";
    writeHeightExr(path, f, ExrPixelType::Float);
    const HeightField back = readHeightExr(path);
    ASSERT_EQ(back.cellsX, f.cellsX);
    ASSERT_EQ(back.cellsZ, f.cellsZ);
    for (std::size_t i = 0; i < f.heights.size(); ++i)
        EXPECT_EQ(back.heights[i], static_cast<double>(static_cast<float>(f.heights[i]))) << i;
    const ExrImage image = readExr(path);
    EXPECT_EQ(image.channels, std::vector<std::string>{"Y"});
    EXPECT_EQ(image.types, std::vector<std::string>{"float"});
    EXPECT_EQ(image.compression, "zip");
    EXPECT_NE(image.comments.find("height"), std::string::npos);
    EXPECT_EQ(filesIn(temp.path()), 1u); // no temporary left behind
}

TEST(HeightExr, HalfRoundTripIsWithinHalfPrecision) {
    const HeightField f = wavyField();
    const swell::test::TempDir temp("swell_height_exr_");
    writeHeightExr(temp / "half.exr", f, ExrPixelType::Half);
    writeHeightExr(temp / "float.exr", f, ExrPixelType::Float);
    const HeightField back = readHeightExr(temp / "half.exr");
    double worst = 0.0;
    for (std::size_t i = 0; i < f.heights.size(); ++i) {
        const double error = std::abs(back.heights[i] - f.heights[i]);
        EXPECT_LE(error, kHalfRelative * std::abs(f.heights[i])) << i;
        worst = std::max(worst, error);
    }
    // Really stored as half: coarser than float, and about half the bytes.
    EXPECT_GT(worst, 1e-5);
    EXPECT_EQ(readExr(temp / "half.exr").types, std::vector<std::string>{"half"});
    EXPECT_LT(fs::file_size(temp / "half.exr"), fs::file_size(temp / "float.exr"));
}

TEST(HeightExr, RowZeroIsZCellZeroAndYReadsAsGreyThroughOpenExrRgba) {
    // height = 0.01 (10 m + n): every cell different, so a flip or transpose shows.
    HeightField f{5, 3, {}};
    for (int m = 0; m < 3; ++m) {
        for (int n = 0; n < 5; ++n)
            f.heights.push_back(0.01 * (10 * m + n));
    }
    const swell::test::TempDir temp("swell_height_exr_");
    const fs::path path = temp / "h.exr";
    writeHeightExr(path, f, ExrPixelType::Float);
    // OpenEXR's RGBA interface (what most viewers use) sees a luminance-only image, grey.
    Imf::RgbaInputFile file(path.c_str());
    EXPECT_EQ(file.channels(), Imf::WRITE_Y);
    const Imath::Box2i window = file.dataWindow();
    ASSERT_EQ(window.min.x, 0);
    ASSERT_EQ(window.min.y, 0);
    ASSERT_EQ(window.max.x, 4);
    ASSERT_EQ(window.max.y, 2);
    EXPECT_EQ(file.lineOrder(), Imf::INCREASING_Y); // row 0 is stored first: the top row
    std::vector<Imf::Rgba> pixels(15);
    file.setFrameBuffer(pixels.data(), 1, 5);
    file.readPixels(0, 2);
    for (int m = 0; m < 3; ++m) {
        for (int n = 0; n < 5; ++n) {
            const Imf::Rgba& p = pixels[static_cast<std::size_t>(m * 5 + n)];
            EXPECT_NEAR(float(p.r), f.at(n, m), 1e-3) << n << ", " << m;
            EXPECT_EQ(float(p.r), float(p.g));
            EXPECT_EQ(float(p.g), float(p.b));
        }
    }
}

TEST(HeightExr, NormalsOfATiltedPlaneAreExactEverywhere) {
    // h = 0.3 + 0.2 x - 0.1 z: normal (-0.2, 1, 0.1) / |.|, also at the one-sided edges.
    const double dx = 0.05, dz = 0.02;
    HeightField f{9, 7, {}};
    for (int m = 0; m < 7; ++m) {
        for (int n = 0; n < 9; ++n)
            f.heights.push_back(0.3 + 0.2 * (n + 0.5) * dx - 0.1 * (m + 0.5) * dz);
    }
    const double length = std::sqrt(0.04 + 1.0 + 0.01);
    const std::vector<double> normals = surfaceNormals(f, dx, dz);
    ASSERT_EQ(normals.size(), 9u * 7u * 3u);
    for (std::size_t i = 0; i < 63; ++i) {
        EXPECT_NEAR(normals[3 * i], -0.2 / length, 1e-12) << i;
        EXPECT_NEAR(normals[3 * i + 1], 1.0 / length, 1e-12) << i;
        EXPECT_NEAR(normals[3 * i + 2], 0.1 / length, 1e-12) << i;
    }
    // The file holds them as R, G, B.
    const swell::test::TempDir temp("swell_height_exr_");
    writeNormalExr(temp / "n.exr", f, dx, dz, ExrPixelType::Float);
    const ExrImage image = readExr(temp / "n.exr");
    EXPECT_EQ(image.channels, (std::vector<std::string>{"B", "G", "R"})); // OpenEXR sorts
    const std::size_t r = image.channel("R"), g = image.channel("G"), b = image.channel("B");
    for (int m = 0; m < 7; ++m) {
        for (int n = 0; n < 9; ++n) {
            const std::size_t i = static_cast<std::size_t>(m * 9 + n);
            EXPECT_EQ(image.at(n, m, r), static_cast<float>(normals[3 * i]));
            EXPECT_EQ(image.at(n, m, g), static_cast<float>(normals[3 * i + 1]));
            EXPECT_EQ(image.at(n, m, b), static_cast<float>(normals[3 * i + 2]));
        }
    }
}

TEST(HeightExr, NormalsOfASineFollowItsSlopeToSecondOrder) {
    // h = 0.5 + 0.05 sin(k x + 0.3) + 0.02 cos(q z): central differences are second order,
    // each slope within its third derivative's bound times dx^2 / 6 (Taylor), and a unit
    // normal moves no more than the slopes do.
    using std::numbers::pi;
    const double dx = 0.01, dz = 0.015, k = 2.0 * pi / 0.8, q = 2.0 * pi / 1.1;
    const double tolerance =
        0.05 * k * k * k * dx * dx / 6.0 + 0.02 * q * q * q * dz * dz / 6.0 + 1e-9; // 5.4e-4
    HeightField f{80, 60, {}};
    for (int m = 0; m < f.cellsZ; ++m) {
        for (int n = 0; n < f.cellsX; ++n) {
            const double x = (n + 0.5) * dx, z = (m + 0.5) * dz;
            f.heights.push_back(0.5 + 0.05 * std::sin(k * x + 0.3) + 0.02 * std::cos(q * z));
        }
    }
    const std::vector<double> normals = surfaceNormals(f, dx, dz);
    for (int m = 1; m < f.cellsZ - 1; ++m) {
        for (int n = 1; n < f.cellsX - 1; ++n) {
            const double x = (n + 0.5) * dx, z = (m + 0.5) * dz;
            const double sx = 0.05 * k * std::cos(k * x + 0.3), sz = -0.02 * q * std::sin(q * z);
            const double length = std::sqrt(sx * sx + 1.0 + sz * sz);
            const double* got = &normals[3 * static_cast<std::size_t>(m * f.cellsX + n)];
            EXPECT_NEAR(got[0], -sx / length, tolerance) << n << ", " << m;
            EXPECT_NEAR(got[1], 1.0 / length, tolerance) << n << ", " << m;
            EXPECT_NEAR(got[2], -sz / length, tolerance) << n << ", " << m;
            EXPECT_NEAR(got[0] * got[0] + got[1] * got[1] + got[2] * got[2], 1.0, 1e-12);
        }
    }
}

TEST(HeightExr, DisplacementIsHeightAboveTheReferenceInGreen) {
    const HeightField f = wavyField();
    const swell::test::TempDir temp("swell_height_exr_");
    writeDisplacementExr(temp / "d.exr", f, 0.45, ExrPixelType::Float);
    writeDisplacementExr(temp / "dh.exr", f, 0.45, ExrPixelType::Half);
    const ExrImage image = readExr(temp / "d.exr"), half = readExr(temp / "dh.exr");
    EXPECT_EQ(image.compression, "zip");
    EXPECT_EQ(half.types, (std::vector<std::string>{"half", "half", "half"}));
    const std::size_t r = image.channel("R"), g = image.channel("G"), b = image.channel("B");
    for (int m = 0; m < f.cellsZ; ++m) {
        for (int n = 0; n < f.cellsX; ++n) {
            const double d = f.at(n, m) - 0.45;
            EXPECT_EQ(image.at(n, m, r), 0.0f);
            EXPECT_EQ(image.at(n, m, g), static_cast<float>(d));
            EXPECT_EQ(image.at(n, m, b), 0.0f);
            EXPECT_NEAR(half.at(n, m, g), d, kHalfRelative * std::abs(d) + 1e-7);
        }
    }
}

TEST(HeightExr, BadPathsAndDamagedFilesAreClearErrors) {
    const HeightField f = wavyField();
    try {
        writeHeightExr("/nonexistent-dir/h.exr", f, ExrPixelType::Float);
        ADD_FAILURE() << "no error";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/h.exr"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(readHeightExr("/nonexistent-dir/h.exr"), RuntimeError);
    const swell::test::TempDir temp("swell_height_exr_");
    std::ofstream(temp / "text.exr") << "not an image\n";
    EXPECT_THROW(readExr(temp / "text.exr"), RuntimeError);
    // A truncated file is an error, not a short image.
    writeHeightExr(temp / "whole.exr", f, ExrPixelType::Float);
    fs::copy_file(temp / "whole.exr", temp / "cut.exr");
    fs::resize_file(temp / "cut.exr", fs::file_size(temp / "whole.exr") / 2);
    EXPECT_THROW(readHeightExr(temp / "cut.exr"), RuntimeError);
    // A normal map is not a height map.
    writeNormalExr(temp / "n.exr", f, 0.1, 0.1, ExrPixelType::Half);
    EXPECT_THROW(readHeightExr(temp / "n.exr"), RuntimeError);
    // Malformed fields and grids are the caller's bug.
    EXPECT_THROW(writeHeightExr(temp / "x.exr", HeightField{2, 2, {0.0}}, ExrPixelType::Float),
                 std::invalid_argument);
    EXPECT_THROW(surfaceNormals(f, 0.0, 0.1), std::invalid_argument);
    EXPECT_FALSE(fs::exists(temp / "x.exr"));
}

} // namespace swell::runtime
