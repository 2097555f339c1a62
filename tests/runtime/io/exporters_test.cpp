#include "swell/runtime/error.h"
#include "swell/runtime/io/exporters.h"
#include "swell/runtime/render/splash_system.h"

#include "temp_dir.h"

#include "synthetic_frames.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

Grid smallGrid(int n, int m) {
    Grid g;
    g = test::sized(n, m, 4, g);
    g.x0 = -0.5;
    g.dx = 0.25;
    g.dz = 0.5;
    g.extentZ = m * g.dz;
    return g;
}

HeightField field(int n, int m) {
    HeightField f{n, m, {}};
    for (int j = 0; j < m; ++j) {
        for (int i = 0; i < n; ++i)
            f.heights.push_back(0.4 + 0.01 * i - 0.02 * j);
    }
    return f;
}

TEST(Exporters, SurfaceMeshPlacesCellCentresAndFacesUp) {
    const SurfaceMesh mesh = makeSurfaceMesh(field(4, 3), smallGrid(4, 3));
    ASSERT_EQ(mesh.positions.size(), 4u * 3u * 3u);
    ASSERT_EQ(mesh.triangles.size(), 3u * 2u * 6u);
    // Vertex m * N + n at (x0 + (n + 1/2) dx, h, (m + 1/2) dz).
    const std::size_t v = (2 * 4 + 3) * 3;
    EXPECT_FLOAT_EQ(mesh.positions[v + 0], static_cast<float>(-0.5 + 3.5 * 0.25));
    EXPECT_FLOAT_EQ(mesh.positions[v + 1], static_cast<float>(0.4 + 0.03 - 0.04));
    EXPECT_FLOAT_EQ(mesh.positions[v + 2], static_cast<float>(2.5 * 0.5));
    // Every triangle's geometric normal points up (+y) on this gentle surface.
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const float* a = &mesh.positions[3 * mesh.triangles[t]];
        const float* b = &mesh.positions[3 * mesh.triangles[t + 1]];
        const float* c = &mesh.positions[3 * mesh.triangles[t + 2]];
        const float ux = b[0] - a[0], uz = b[2] - a[2], vx = c[0] - a[0], vz = c[2] - a[2];
        EXPECT_GT(uz * vx - ux * vz, 0.0f) << "triangle " << t / 3; // y of u x v
    }
    EXPECT_THROW(makeSurfaceMesh(field(4, 3), smallGrid(3, 4)), std::invalid_argument);
    EXPECT_THROW(makeSurfaceMesh(field(1, 3), smallGrid(1, 3)), std::invalid_argument);
}

TEST(Exporters, SurfacePlyRoundTripIsExact) {
    const SurfaceMesh mesh = makeSurfaceMesh(field(7, 5), smallGrid(7, 5));
    const fs::path p = swell::test::programTempFile("swell_export_", "surface.ply");
    writeSurfacePly(p, mesh, "frame 3\nsecond line");
    const PlyData d = readPly(p);
    EXPECT_EQ(d.vertexProperties, (std::vector<std::string>{"x", "y", "z"}));
    EXPECT_EQ(d.vertices, mesh.positions);
    EXPECT_EQ(d.triangles, mesh.triangles);
    EXPECT_EQ(d.comment, "frame 3 second line");
    // The header is plain PLY that other tools read.
    std::ifstream f(p, std::ios::binary);
    std::string header((std::istreambuf_iterator<char>(f)), {});
    header = header.substr(0, header.find("end_header"));
    EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos);
    EXPECT_NE(header.find("element vertex 35"), std::string::npos);
    EXPECT_NE(header.find("element face 48"), std::string::npos);
    EXPECT_NE(header.find("property list uchar uint vertex_indices"), std::string::npos);
    // Size: header + 35 * 12 bytes + 48 * 13 bytes.
    EXPECT_EQ(fs::file_size(p),
              header.size() + std::string("end_header\n").size() + 35 * 12 + 48 * 13);
    fs::remove(p);
}

TEST(Exporters, SplashPlyRoundTripIsExact) {
    const std::vector<SplashSprite> sprites{{0.1f, 0.2f, 0.3f, 1.0f}, {-1.0f, 2.5f, 3.25f, 0.125f}};
    const fs::path p = swell::test::programTempFile("swell_export_", "splash.ply");
    writeSplashPly(p, sprites);
    const PlyData d = readPly(p);
    EXPECT_EQ(d.vertexProperties, (std::vector<std::string>{"x", "y", "z", "alpha"}));
    ASSERT_EQ(d.vertices.size(), 8u);
    EXPECT_EQ(d.vertices[4], -1.0f);
    EXPECT_EQ(d.vertices[7], 0.125f);
    EXPECT_TRUE(d.triangles.empty());
    writeSplashPly(p, {});
    EXPECT_TRUE(readPly(p).vertices.empty());
    fs::remove(p);
}

TEST(Exporters, ReaderRejectsDamagedAndForeignFiles) {
    const fs::path p = swell::test::programTempFile("swell_export_", "bad.ply");
    const SurfaceMesh mesh = makeSurfaceMesh(field(3, 3), smallGrid(3, 3));
    writeSurfacePly(p, mesh);
    const auto size = fs::file_size(p);
    fs::resize_file(p, size - 5);
    EXPECT_THROW(readPly(p), RuntimeError); // truncated faces
    std::ofstream(p) << "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
    EXPECT_THROW(readPly(p), RuntimeError); // ASCII is not read
    std::ofstream(p) << "solid stl\n";
    EXPECT_THROW(readPly(p), RuntimeError);
    {
        std::ofstream f(p, std::ios::binary);
        f << "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
             "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
        const float x = 1.0f;
        f.write(reinterpret_cast<const char*>(&x), 4);
        const unsigned char three = 3;
        const std::uint32_t idx[3] = {0, 0, 7};
        f.write(reinterpret_cast<const char*>(&three), 1);
        f.write(reinterpret_cast<const char*>(idx), 12);
    }
    try {
        readPly(p);
        FAIL() << "an index out of range was accepted";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 7"), std::string::npos) << e.what();
    }
    EXPECT_THROW(writeSurfacePly("/nonexistent-dir/a.ply", mesh), RuntimeError);
    fs::remove(p);
}

} // namespace
} // namespace swell::runtime
