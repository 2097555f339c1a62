#include "swell/runtime/error.h"
#include "swell/runtime/io/height_png.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace swell::runtime {

TEST(HeightPng, RoundTripWithinHalfAStep) {
    HeightField f;
    f.cellsX = 37;
    f.cellsZ = 21;
    for (int m = 0; m < f.cellsZ; ++m) {
        for (int n = 0; n < f.cellsX; ++n)
            f.heights.push_back(0.4 + 0.1 * std::sin(n * 0.3 + m * 0.7));
    }
    const HeightScale scale{0.0, 1.0 / 65535.0};
    const swell::test::TempDir temp("swell_height_png_");
    const auto path = temp / "heights.png";
    writeHeightPng(path, f, scale);
    const HeightField back = readHeightPng(path, scale);
    std::filesystem::remove(path);
    ASSERT_EQ(back.cellsX, f.cellsX);
    ASSERT_EQ(back.cellsZ, f.cellsZ);
    for (std::size_t i = 0; i < f.heights.size(); ++i) {
        EXPECT_NEAR(back.heights[i], f.heights[i], 0.5 * scale.scale + 1e-12);
    }
}

TEST(HeightPng, UnwritablePathIsAClearError) {
    HeightField f{2, 2, {0, 0, 0, 0}};
    EXPECT_THROW(writeHeightPng("/nonexistent-dir/x.png", f, {}), RuntimeError);
    EXPECT_THROW(readHeightPng("/nonexistent-dir/x.png", {}), RuntimeError);
}

} // namespace swell::runtime
