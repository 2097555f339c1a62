// The environment cube map: face directions, the procedural sky, user images.
#include "swell/runtime/error.h"
#include "swell/runtime/io/image_io.h"
#include "swell/runtime/render/sky_cubemap.h"

#include "temp_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace swell::runtime {
namespace {

TEST(SkyCubemap, FaceDirectionsFollowTheGlConvention) {
    const auto centre = [](int face) { return cubeDirection(face, 1, 1, 3); }; // the middle texel
    EXPECT_EQ(centre(0), (Vec3{1.0, 0.0, 0.0}));
    EXPECT_EQ(centre(1), (Vec3{-1.0, 0.0, 0.0}));
    EXPECT_EQ(centre(2), (Vec3{0.0, 1.0, 0.0}));
    EXPECT_EQ(centre(3), (Vec3{0.0, -1.0, 0.0}));
    EXPECT_EQ(centre(4), (Vec3{0.0, 0.0, 1.0}));
    EXPECT_EQ(centre(5), (Vec3{0.0, 0.0, -1.0}));
    // Row 0 of a side face looks up (t = -1 maps to +y).
    EXPECT_GT(cubeDirection(0, 1, 0, 3)[1], 0.0);
}

TEST(SkyCubemap, ProceduralSkyIsDeterministicBlueAboveAndBrightAtTheSun) {
    SkyParams p;
    p.faceSize = 32;
    p.cloudCover = 0.0;
    const CubeFaces a = proceduralSky(p), b = proceduralSky(p);
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(a[f].rgb, b[f].rgb);
    const std::uint8_t* zenith = a[2].pixel(16, 16);
    EXPECT_GT(zenith[2], zenith[0] + 40); // blue sky
    // Brightest texel of the sky lies near the sun direction.
    const Vec3 sun = sunDirection(p);
    int best = -1;
    double bestCos = -2.0;
    int bestSum = -1;
    for (int f = 0; f < 6; ++f) {
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                const std::uint8_t* q = a[f].pixel(x, y);
                const int sum = q[0] + q[1] + q[2];
                if (sum > bestSum) {
                    bestSum = sum;
                    Vec3 d = cubeDirection(f, x, y, 32);
                    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    bestCos = (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]) / l;
                    best = f;
                }
            }
        }
    }
    EXPECT_GE(best, 0);
    EXPECT_GT(bestCos, 0.97);
    SkyParams clouds = p;
    clouds.cloudCover = 0.7;
    EXPECT_NE(proceduralSky(clouds)[2].rgb, a[2].rgb);
    SkyParams bad;
    bad.sunElevationDegrees = 95.0;
    EXPECT_THROW(proceduralSky(bad), std::invalid_argument);
}

TEST(SkyCubemap, UserImagesLoadOrNameTheMissingFile) {
    const swell::test::TempDir temp("swell_sky_");
    const std::filesystem::path& dir = temp.path();
    SkyParams p;
    p.faceSize = 8;
    const CubeFaces faces = proceduralSky(p);
    const char* names[6] = {"px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"};
    for (int i = 0; i < 5; ++i)
        writePng(dir / names[i], faces[i]);
    try {
        loadSkyImages(dir);
        FAIL();
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("nz.png"), std::string::npos) << e.what();
    }
    writePng(dir / names[5], faces[5]);
    const CubeFaces back = loadSkyImages(dir);
    for (int i = 0; i < 6; ++i)
        EXPECT_EQ(back[i].rgb, faces[i].rgb);
    writePng(dir / names[2], Image(8, 4));
    EXPECT_THROW(loadSkyImages(dir), RuntimeError);
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace swell::runtime

namespace swell::runtime {
namespace {

TEST(SkyCubemap, ZenithRadianceIsTheSrgbDecodedCentreOfTheTopFace) {
    CubeFaces faces;
    for (Image& f : faces)
        f = Image(4, 4);
    // The centre of an even face lies between its four middle texels: their mean, decoded.
    const std::uint8_t values[4] = {0, 255, 128, 10};
    int k = 0;
    for (int y : {1, 2})
        for (int x : {1, 2}) {
            std::uint8_t* p = faces[2].pixel(x, y);
            p[0] = values[k++];
            p[1] = 255;
            p[2] = 0;
        }
    const Vec3 z = zenithRadiance(faces);
    const double mid = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(z[0], (0.0 + 1.0 + mid + 10.0 / 255.0 / 12.92) / 4.0, 1e-12);
    EXPECT_NEAR(z[1], 1.0, 1e-12);
    EXPECT_NEAR(z[2], 0.0, 1e-12);
    // An odd face: its middle texel.
    faces[2] = Image(3, 3);
    faces[2].pixel(1, 1)[2] = 255;
    EXPECT_NEAR(zenithRadiance(faces)[2], 1.0, 1e-12);
    EXPECT_NEAR(zenithRadiance(faces)[0], 0.0, 1e-12);
    // The procedural sky: bluish straight up.
    const Vec3 sky = zenithRadiance(proceduralSky(SkyParams{}));
    EXPECT_GT(sky[2], sky[0]);
}

} // namespace
} // namespace swell::runtime
