#include "swell/runtime/error.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/io/image_io.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

Image gradient(int w, int h) {
    Image im(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = im.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(x * 255 / (w - 1));
            p[1] = static_cast<std::uint8_t>(y * 255 / (h - 1));
            p[2] = static_cast<std::uint8_t>((x * 7 + y * 13) % 256);
        }
    }
    return im;
}

TEST(ImageIo, PngRoundTripIsExactAtEveryCompressionLevel) {
    const Image im = gradient(37, 23);
    for (int level : {0, 1, 9}) {
        const fs::path p = swell::test::programTempFile("swell_image_io_", "rt.png");
        writePng(p, im, level);
        const Image back = readPng(p);
        EXPECT_EQ(back.width, 37);
        EXPECT_EQ(back.height, 23);
        EXPECT_EQ(back.rgb, im.rgb) << "level " << level;
        fs::remove(p);
    }
}

TEST(ImageIo, ReadsSixteenBitGreyAsRgb) {
    HeightField f{3, 2, {0.0, 0.5, 1.0, 0.25, 0.75, 1.0}};
    const fs::path p = swell::test::programTempFile("swell_image_io_", "grey16.png");
    writeHeightPng(p, f, HeightScale{0.0, 1.0 / 65535.0});
    const Image im = readPng(p);
    ASSERT_EQ(im.width, 3);
    ASSERT_EQ(im.height, 2);
    EXPECT_EQ(im.pixel(0, 0)[0], 0);
    EXPECT_EQ(im.pixel(2, 0)[1], 255);
    EXPECT_EQ(im.pixel(1, 0)[2], 128); // 0.5 * 65535 rounds to 32768: high byte 128
    fs::remove(p);
}

TEST(ImageIo, BadFilesThrowNamingTheFile) {
    EXPECT_THROW(readPng(swell::test::programTempFile("swell_image_io_", "missing.png")),
                 RuntimeError);
    const fs::path p = swell::test::programTempFile("swell_image_io_", "not.png");
    std::ofstream(p) << "this is not a png file at all";
    try {
        readPng(p);
        FAIL();
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("not.png"), std::string::npos);
    }
    // A PNG cut in half is damaged.
    const fs::path good = swell::test::programTempFile("swell_image_io_", "cut.png");
    writePng(good, gradient(64, 64), 0);
    const auto size = fs::file_size(good);
    fs::resize_file(good, size / 2);
    EXPECT_THROW(readPng(good), RuntimeError);
    fs::remove(p);
    fs::remove(good);
    EXPECT_THROW(writePng("/nonexistent-dir/x.png", gradient(4, 4)), RuntimeError);
}

TEST(ImageIo, CompareGivesKnownPsnrAndMaxError) {
    Image a(10, 10), b(10, 10);
    EXPECT_TRUE(std::isinf(compareImages(a, b).psnr));
    EXPECT_EQ(compareImages(a, b).maxAbs, 0);
    b.pixel(3, 4)[1] = 51; // one channel of 300 differs by 51: MSE = 51^2 / 300
    const ImageDifference d = compareImages(a, b);
    EXPECT_EQ(d.maxAbs, 51);
    EXPECT_NEAR(d.psnr, 10.0 * std::log10(255.0 * 255.0 / (51.0 * 51.0 / 300.0)), 1e-9);
    EXPECT_NEAR(d.meanAbs, 51.0 / 300.0, 1e-12);
    EXPECT_THROW(compareImages(Image(2, 2), Image(2, 3)), std::invalid_argument);
}

TEST(ImageIo, StatsSeparateUniformFromStructured) {
    Image flat(16, 16);
    for (auto& v : flat.rgb)
        v = 90;
    const ImageStats s = imageStats(flat);
    EXPECT_EQ(s.distinctColours, 1u);
    EXPECT_NEAR(s.stddevLuma, 0.0, 1e-9);
    EXPECT_NEAR(s.meanLuma, 90.0, 1e-9);
    const ImageStats g = imageStats(gradient(16, 16));
    EXPECT_GT(g.distinctColours, 100u);
    EXPECT_GT(g.stddevLuma, 20.0);
}

TEST(ImageIo, DownscaleAveragesBlocksAndContactSheetTiles) {
    Image im(4, 2);
    for (int x = 0; x < 4; ++x)
        im.pixel(x, 0)[0] = static_cast<std::uint8_t>(x * 40); // 0 40 80 120
    const Image d = downscale(im, 2);
    ASSERT_EQ(d.width, 2);
    ASSERT_EQ(d.height, 1);
    EXPECT_EQ(d.pixel(0, 0)[0], 10); // (0 + 40 + 0 + 0) / 4
    EXPECT_EQ(d.pixel(1, 0)[0], 50); // (80 + 120) / 4
    EXPECT_THROW(downscale(im, 0), std::invalid_argument);

    std::vector<Image> tiles(5, Image(6, 4));
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        for (auto& v : tiles[i].rgb)
            v = static_cast<std::uint8_t>(100 + i);
    }
    const Image sheet = contactSheet(tiles, 3, 2);
    EXPECT_EQ(sheet.width, 2 + 3 * (6 + 2));
    EXPECT_EQ(sheet.height, 2 + 2 * (4 + 2));
    EXPECT_EQ(sheet.pixel(2, 2)[0], 100);         // tile 0
    EXPECT_EQ(sheet.pixel(2 + 8 * 2, 2)[0], 102); // tile 2, first row
    EXPECT_EQ(sheet.pixel(2 + 8, 2 + 6)[0], 104); // tile 4, second row
    EXPECT_EQ(sheet.pixel(0, 0)[0], 24);          // border
    EXPECT_THROW(contactSheet(std::vector<Image>{}, 3), std::invalid_argument);
    std::vector<Image> mixed{Image(2, 2), Image(3, 2)};
    EXPECT_THROW(contactSheet(mixed, 2), std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
