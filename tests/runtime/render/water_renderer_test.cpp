// The renderer on llvmpipe: a golden image, a not-blank / not-uniform check (headless EGL can
// silently give black pictures), splashes, multisampling, bad parameters.
//
// Golden image: tests/runtime/data/water_golden.png, 160 x 90, of an analytic height field
// with fixed splash sprites (goldenScene below). It must match with PSNR >= 38 dB and no
// channel off by more than 64 (llvmpipe is deterministic on one build; the slack covers other
// LLVM / Mesa versions rounding differently). After an intended change of the shading, regenerate:
//   SWELL_UPDATE_GOLDEN=1 build/bin/water_renderer_test --gtest_filter='*Golden*'
// look at the picture, and commit it.

#include "swell/runtime/error.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/io/image_io.h"
#include "swell/runtime/render/camera.h"
#include "swell/runtime/render/sky_cubemap.h"
#include "swell/runtime/render/water_renderer.h"

#include "gl_fixture.h"
#include "render/render_scene.h"

#include <gtest/gtest.h>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <unistd.h>

namespace swell::runtime {
namespace {

class WaterRendering : public swell::test::GlSuite {};

Grid testGrid() {
    return test::renderGrid();
}

const cache::Domain kDomain = test::kRenderDomain;

/// A crossing-wave height field around 0.5 m depth, [m * N + n].
std::vector<float> waveHeights(const Grid& g, double phase) {
    std::vector<float> h;
    for (int m = 0; m < g.cellsZ; ++m) {
        for (int n = 0; n < g.cellsX; ++n) {
            const double x = g.x0 + (n + 0.5) * g.dx, z = (m + 0.5) * g.dz;
            h.push_back(static_cast<float>(0.5 + 0.06 * std::cos(2.0 * x - phase) +
                                           0.02 * std::sin(3.1 * x + 2.3 * z)));
        }
    }
    return h;
}

std::vector<SplashSprite> fixedSplashes() {
    std::vector<SplashSprite> s;
    for (int i = 0; i < 40; ++i) {
        s.push_back({static_cast<float>(1.5 + 0.02 * i), static_cast<float>(0.62 + 0.003 * (i % 7)),
                     static_cast<float>(1.0 + 0.03 * (i % 11)),
                     1.0f - 0.02f * static_cast<float>(i)});
    }
    return s;
}

struct Scene {
    Grid grid = testGrid();
    SkyParams sky;
    ShadingParams shading;
    Scene(int w, int h, int samples) {
        sky.faceSize = 64;
        shading.width = w;
        shading.height = h;
        shading.samples = samples;
    }
    Image render(const std::vector<SplashSprite>& splashes, double phase = 0.0,
                 const Camera* camera = nullptr) {
        const std::vector<float> h = waveHeights(grid, phase);
        GlBuffer buffer = makeStorageBuffer(h.size() * sizeof(float), h.data());
        WaterRenderer r(grid, kDomain, shading, proceduralSky(sky), sunDirection(sky));
        const Camera cam =
            camera ? *camera
                   : defaultCamera(grid, kDomain, 0.5, double(shading.width) / shading.height);
        r.draw(buffer.get(), cam, splashes, 0.02);
        lastSplashes = r.lastSplashCount();
        return r.readPixels();
    }
    std::size_t lastSplashes = 0;
};

std::filesystem::path goldenPath() {
    return std::filesystem::path(SWELL_TEST_DATA_DIR) / "water_golden.png";
}

TEST_F(WaterRendering, GoldenImage) {
    Scene scene(160, 90, 1);
    const Image image = scene.render(fixedSplashes());
    if (std::getenv("SWELL_UPDATE_GOLDEN") != nullptr) {
        writePng(goldenPath(), image, 9);
        GTEST_SKIP() << "wrote " << goldenPath();
    }
    const Image golden = readPng(goldenPath());
    const ImageDifference d = compareImages(image, golden);
    EXPECT_GE(d.psnr, 38.0) << "max channel error " << d.maxAbs << " on " << s_context->renderer();
    EXPECT_LE(d.maxAbs, 64);
    if (d.psnr < 38.0)
        writePng(std::filesystem::temp_directory_path() / "water_golden_actual.png", image);
    // The tolerance is tight enough to catch a change: the same scene half a wave later fails it.
    const Image moved = scene.render(fixedSplashes(), 1.5);
    EXPECT_LT(compareImages(moved, golden).psnr, 38.0);
}

TEST_F(WaterRendering, FrameIsNotBlankNorUniformAndShowsWaterAndSky) {
    Scene scene(160, 90, 1);
    const Image image = scene.render({});
    const ImageStats s = imageStats(image);
    EXPECT_GT(s.meanLuma, 20.0);
    EXPECT_LT(s.meanLuma, 235.0);
    EXPECT_GT(s.stddevLuma, 8.0);
    EXPECT_GT(s.distinctColours, 200u);
    // The default camera frames the water in the middle of the picture: blue-green there (green
    // and blue above red), and the top row is the sky, brighter than the water.
    const std::uint8_t* mid = image.pixel(80, 50);
    EXPECT_GT(mid[1], mid[0] + 10) << int(mid[0]) << " " << int(mid[1]) << " " << int(mid[2]);
    EXPECT_GT(mid[2], mid[0] + 10);
    double top = 0.0;
    for (int x = 0; x < 160; ++x)
        top += image.pixel(x, 0)[0] + image.pixel(x, 0)[1] + image.pixel(x, 0)[2];
    EXPECT_GT(top / 160.0, mid[0] + mid[1] + mid[2]);
}

TEST_F(WaterRendering, SplashesAreDrawnOnlyWhenThereAreAny) {
    Scene scene(160, 90, 1);
    // From higher up the drops lie over the water, not over the bright haze of the horizon.
    const Camera high = defaultCamera(scene.grid, kDomain, 0.5, 160.0 / 90.0, 40.0, 28.0);
    const Image without = scene.render({}, 0.0, &high);
    EXPECT_EQ(scene.lastSplashes, 0u);
    const Image with = scene.render(fixedSplashes(), 0.0, &high);
    EXPECT_EQ(scene.lastSplashes, 40u);
    const ImageDifference d = compareImages(without, with);
    EXPECT_GT(d.maxAbs, 40);   // bright droplets over the water
    EXPECT_LT(d.meanAbs, 5.0); // ... in a small part of the picture
}

TEST_F(WaterRendering, DrawingInTwoPartsGivesTheSamePictureAsOne) {
    // drawSurface, then (after the caller built the sprites) drawSplashes: the same frame as
    // draw(), which is the two in a row.
    const Grid grid = testGrid();
    SkyParams sky;
    sky.faceSize = 64;
    ShadingParams shading;
    shading.width = 160;
    shading.height = 90;
    const std::vector<float> h = waveHeights(grid, 0.3);
    GlBuffer buffer = makeStorageBuffer(h.size() * sizeof(float), h.data());
    WaterRenderer r(grid, kDomain, shading, proceduralSky(sky), sunDirection(sky));
    const Camera cam = defaultCamera(grid, kDomain, 0.5, 160.0 / 90.0);
    const std::vector<SplashSprite> splashes = fixedSplashes();
    r.draw(buffer.get(), cam, splashes, 0.02);
    const Image one = r.readPixels();
    r.drawSurface(buffer.get(), cam, true);
    r.drawSplashes(splashes, 0.02);
    const Image two = r.readPixels();
    EXPECT_EQ(compareImages(one, two).maxAbs, 0);
    EXPECT_EQ(r.lastSplashCount(), 40u);
    // Out of order: splashes with no surface drawn, or after being told none would follow.
    EXPECT_THROW(r.drawSplashes(splashes, 0.02), std::logic_error);
    r.drawSurface(buffer.get(), cam, false);
    EXPECT_THROW(r.drawSplashes(splashes, 0.02), std::logic_error);
    r.drawSurface(buffer.get(), cam, false);
    r.drawSplashes({}, 0.02);
    EXPECT_EQ(r.lastSplashCount(), 0u);
}

TEST_F(WaterRendering, AMeshWrittenInSeveralDispatchesGivesTheSamePicture) {
    // A mesh whose vertex buffer exceeds one shader-storage block (llvmpipe: 128 MB, 1672 x
    // 1672 cells) is written a block of rows at a time; forced here at 7 and 1 row(s) of the
    // test grid, every pixel must be the one-dispatch picture's.
    Scene whole(160, 90, 1);
    const Image one = whole.render(fixedSplashes());
    for (const int rows : {7, 1}) {
        Scene split(160, 90, 1);
        split.shading.vertexRowsPerDispatch = rows;
        EXPECT_EQ(compareImages(split.render(fixedSplashes()), one).maxAbs, 0) << rows;
    }
    // The split is real: a pass that wrote only its first block would leave the rest unset.
    EXPECT_GT(testGrid().cellsZ, 7);
}

TEST_F(WaterRendering, AMeshBeyondTheDriversStorageBlockIsRefusedNamingWhatFits) {
    // The height buffer (4 bytes a cell) is bound whole: one row of 8192 cells past the block
    // is refused before anything is made, a mesh that fills it is not.
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    const auto rows = static_cast<int>(maxBlock / 4 / 8192);
    EXPECT_NO_THROW(WaterRenderer::checkMeshFits(8192, rows));
    try {
        WaterRenderer::checkMeshFits(8192, rows + 1);
        ADD_FAILURE() << "a mesh beyond the block was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("cells_x x cells_z must fit this driver's"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(WaterRendering, MultisamplingSmoothsButDoesNotChangeThePicture) {
    Scene one(160, 90, 1), four(160, 90, 4);
    const Image a = one.render({});
    const Image b = four.render({});
    const ImageDifference d = compareImages(a, b);
    EXPECT_GT(d.psnr, 24.0);
    EXPECT_GT(d.maxAbs, 0); // edges differ
}

double luma(const Image& im, int x, int y) {
    const std::uint8_t* p = im.pixel(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

TEST_F(WaterRendering, TheFloorIsDrawnAroundTheBlockAndCanBeTurnedOff) {
    // The default camera sees the floor in front of the block in the bottom corners: sand
    // (red above blue); without the floor the sky's dark blue-grey ground is there instead.
    Scene scene(160, 90, 1);
    scene.sky.cloudCover = 0.0;
    const Image with = scene.render({});
    scene.shading.floor.enabled = false;
    const Image without = scene.render({});
    for (int x : {2, 157}) {
        const std::uint8_t* a = with.pixel(x, 87);
        EXPECT_GT(a[0], a[2] + 10) << x << ": " << int(a[0]) << " " << int(a[2]);
        const std::uint8_t* b = without.pixel(x, 87);
        EXPECT_LT(b[0], b[2]) << x << ": " << int(b[0]) << " " << int(b[2]);
    }
    // The water in the middle is the same with and without it.
    EXPECT_EQ(with.pixel(80, 45)[1], without.pixel(80, 45)[1]);
}

/// A camera on the floor's far side looking level towards azimuth `azimuthDegrees`.
Camera levelCamera(double azimuthDegrees, double pitchDegrees) {
    const double a = azimuthDegrees * std::numbers::pi / 180.0;
    const double p = pitchDegrees * std::numbers::pi / 180.0;
    Camera c;
    c.position = {2.0, 1.5, 1.6};
    c.target = {2.0 + std::cos(a) * std::cos(p), 1.5 + std::sin(p),
                1.6 + std::sin(a) * std::cos(p)};
    c.fovYDegrees = 60.0;
    c.nearPlane = 0.05;
    c.farPlane = 500.0;
    return c;
}

TEST_F(WaterRendering, SkyIsBrighterAtTheHorizonThanHigherUp) {
    // Looking level away from the sun: rows just above the horizon (the middle of the picture)
    // are brighter than the top row (30 degrees up), and the top row is blue.
    Scene scene(160, 90, 1);
    scene.sky.cloudCover = 0.0;
    const Camera cam = levelCamera(scene.sky.sunAzimuthDegrees + 180.0, 0.0);
    const Image im = scene.render({}, 0.0, &cam);
    double top = 0.0, nearHorizon = 0.0;
    for (int x = 0; x < 160; ++x) {
        top += luma(im, x, 0);
        nearHorizon += luma(im, x, 42);
        const std::uint8_t* p = im.pixel(x, 0);
        EXPECT_GT(p[2], p[0] + 20) << x;
    }
    EXPECT_GT(nearHorizon, top + 160 * 20.0);
}

TEST_F(WaterRendering, TheBrightestSkyPixelIsTheSunAndFollowsItsDirection) {
    Scene scene(160, 90, 1);
    scene.sky.cloudCover = 0.0;
    scene.sky.sunElevationDegrees = 12.0;
    scene.sky.sunGlow = 0.0; // the disc alone at the brightest value
    const double base = scene.sky.sunAzimuthDegrees;
    const Camera cam = levelCamera(base, 10.0);
    const Mat4 vp = multiply(projectionMatrix(cam, 160.0 / 90.0), viewMatrix(cam));
    for (double offset : {-12.0, 0.0, 12.0}) {
        scene.sky.sunAzimuthDegrees = base + offset;
        const Image im = scene.render({}, 0.0, &cam);
        // The disc saturates: the centre of the pixels at the brightest value.
        double best = -1.0;
        for (int y = 0; y < 90; ++y)
            for (int x = 0; x < 160; ++x)
                best = std::max(best, luma(im, x, y));
        double sx = 0.0, sy = 0.0, count = 0.0;
        for (int y = 0; y < 90; ++y)
            for (int x = 0; x < 160; ++x)
                if (luma(im, x, y) >= best - 0.5) {
                    sx += x + 0.5;
                    sy += y + 0.5;
                    count += 1.0;
                }
        const double bx = sx / count, by = sy / count;
        // Where the sun direction projects: the brightest pixel lies on the disc.
        const Vec3 s = sunDirection(scene.sky);
        double q[4];
        for (int r = 0; r < 4; ++r)
            q[r] = vp[r] * s[0] + vp[4 + r] * s[1] + vp[8 + r] * s[2]; // a direction: w = 0
        const double px = (q[0] / q[3] * 0.5 + 0.5) * 160.0, py = (0.5 - q[1] / q[3] * 0.5) * 90.0;
        EXPECT_NEAR(bx, px, 2.0) << offset;
        EXPECT_NEAR(by, py, 2.0) << offset;
    }
}

TEST_F(WaterRendering, BadParametersThrow) {
    const Grid grid = testGrid();
    SkyParams sky;
    sky.faceSize = 16;
    const CubeFaces faces = proceduralSky(sky);
    ShadingParams s;
    s.width = 8;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    s = ShadingParams{};
    s.samples = 0;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    s = ShadingParams{};
    s.vertexRowsPerDispatch = -1;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    s = ShadingParams{};
    s.refractiveIndex = 0.5;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    s = ShadingParams{};
    s.floor.tileSize = 0.0;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    s = ShadingParams{};
    s.floor.hazeDistance = -1.0;
    EXPECT_THROW(WaterRenderer(grid, kDomain, s, faces, sunDirection(sky)), std::invalid_argument);
    CubeFaces uneven = faces;
    uneven[3] = Image(8, 8);
    EXPECT_THROW(makeCubemapTexture(uneven), std::invalid_argument);
}

} // namespace
} // namespace swell::runtime
