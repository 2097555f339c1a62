#include "swell/runtime/io/exporters.h"

#include "swell/runtime/error.h"
#include "swell/runtime/io/atomic_write.h"
#include "swell/runtime/render/splash_system.h"

#include <bit>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace swell::runtime {
namespace {

static_assert(std::endian::native == std::endian::little,
              "PLY writers assume a little-endian host");

/// Exports are built in memory and written atomically (writeBytesAtomically): a failed write
/// leaves no partial file.
void finish(const std::ostringstream& f, const std::filesystem::path& path) {
    writeBytesAtomically(path, f.view());
}

std::string commentLine(const std::string& comment) {
    if (comment.empty())
        return {};
    std::string c = comment;
    for (char& ch : c) {
        if (ch == '\n' || ch == '\r')
            ch = ' ';
    }
    return "comment " + c + "\n";
}

} // namespace

SurfaceMesh makeSurfaceMesh(const HeightField& field, const Grid& grid) {
    const int N = field.cellsX, M = field.cellsZ;
    if (N != grid.cellsX || M != grid.cellsZ ||
        field.heights.size() != static_cast<std::size_t>(N) * M) {
        throw std::invalid_argument("height field and grid disagree");
    }
    if (N < 2 || M < 2)
        throw std::invalid_argument("a surface mesh needs at least 2 x 2 cells");
    SurfaceMesh mesh;
    mesh.positions.reserve(static_cast<std::size_t>(N) * M * 3);
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            mesh.positions.push_back(static_cast<float>(grid.x0 + (n + 0.5) * grid.dx));
            mesh.positions.push_back(static_cast<float>(field.at(n, m)));
            mesh.positions.push_back(static_cast<float>((m + 0.5) * grid.dz));
        }
    }
    mesh.triangles.reserve(static_cast<std::size_t>(N - 1) * (M - 1) * 6);
    for (int m = 0; m + 1 < M; ++m) {
        for (int n = 0; n + 1 < N; ++n) {
            const auto a = static_cast<std::uint32_t>(m * N + n), b = a + 1;
            const auto c = a + static_cast<std::uint32_t>(N), d = c + 1;
            // Counter-clockwise seen from +y (x right, z towards the viewer): a, c, b and b, c, d.
            for (std::uint32_t i : {a, c, b, b, c, d})
                mesh.triangles.push_back(i);
        }
    }
    return mesh;
}

void writeSurfacePly(const std::filesystem::path& path, const SurfaceMesh& mesh,
                     const std::string& comment) {
    const std::size_t vertices = mesh.positions.size() / 3, faces = mesh.triangles.size() / 3;
    std::ostringstream f;
    f << "ply\nformat binary_little_endian 1.0\n"
      << commentLine(comment) << "element vertex " << vertices
      << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face " << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
    f.write(reinterpret_cast<const char*>(mesh.positions.data()),
            static_cast<std::streamsize>(vertices * 3 * sizeof(float)));
    for (std::size_t t = 0; t < faces; ++t) {
        const char three = 3;
        f.write(&three, 1);
        f.write(reinterpret_cast<const char*>(&mesh.triangles[3 * t]), 3 * sizeof(std::uint32_t));
    }
    finish(f, path);
}

void writeSplashPly(const std::filesystem::path& path, std::span<const SplashSprite> sprites,
                    const std::string& comment) {
    static_assert(sizeof(SplashSprite) == 4 * sizeof(float));
    std::ostringstream f;
    f << "ply\nformat binary_little_endian 1.0\n"
      << commentLine(comment) << "element vertex " << sprites.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float "
         "alpha\nend_header\n";
    f.write(reinterpret_cast<const char*>(sprites.data()),
            static_cast<std::streamsize>(sprites.size_bytes()));
    finish(f, path);
}

PlyData readPly(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f)
        throw RuntimeError(fmt::format("cannot open {}", path.string()));
    auto fail = [&](const std::string& why) {
        return RuntimeError(fmt::format("{}: {}", path.string(), why));
    };
    std::string line;
    if (!std::getline(f, line) || line != "ply")
        throw fail("not a PLY file");
    PlyData data;
    std::size_t vertexCount = 0, faceCount = 0;
    std::string element;
    bool formatOk = false, faceList = false, faceIndexSigned = false;
    for (;;) {
        if (!std::getline(f, line))
            throw fail("truncated header");
        if (line == "end_header")
            break;
        std::istringstream in(line);
        std::string word;
        in >> word;
        if (word == "format") {
            std::string fmtName, version;
            in >> fmtName >> version;
            if (fmtName != "binary_little_endian")
                throw fail("only binary_little_endian PLY is read, got " + fmtName);
            formatOk = true;
        } else if (word == "comment") {
            if (data.comment.empty())
                data.comment = line.size() > 8 ? line.substr(8) : "";
        } else if (word == "element") {
            std::size_t count = 0;
            in >> element >> count;
            if (!in)
                throw fail("bad element line");
            if (element == "vertex") {
                vertexCount = count;
            } else if (element == "face") {
                faceCount = count;
            } else {
                throw fail("unsupported element " + element);
            }
        } else if (word == "property") {
            std::string type;
            in >> type;
            if (element == "vertex") {
                std::string name;
                in >> name;
                if (type != "float" && type != "float32")
                    throw fail("vertex property " + name + " is not float");
                data.vertexProperties.push_back(name);
            } else if (element == "face") {
                std::string countType, indexType, name;
                in >> countType >> indexType >> name;
                if (type != "list" || (countType != "uchar" && countType != "uint8") ||
                    (indexType != "int" && indexType != "uint" && indexType != "int32" &&
                     indexType != "uint32")) {
                    throw fail("unsupported face property");
                }
                faceIndexSigned = indexType == "int" || indexType == "int32";
                faceList = true;
            }
        } else {
            throw fail("unexpected header line '" + line + "'");
        }
    }
    if (!formatOk)
        throw fail("no format line");
    if (faceCount > 0 && !faceList)
        throw fail("faces without a vertex_indices list");
    const std::size_t props = data.vertexProperties.size();
    if (vertexCount > (std::size_t{1} << 31) / std::max<std::size_t>(props, 1))
        throw fail("too many vertices");
    data.vertices.resize(vertexCount * props);
    f.read(reinterpret_cast<char*>(data.vertices.data()),
           static_cast<std::streamsize>(data.vertices.size() * sizeof(float)));
    if (!f)
        throw fail("truncated vertex data");
    data.triangles.reserve(std::min<std::size_t>(faceCount, std::size_t{1} << 26) * 3);
    for (std::size_t t = 0; t < faceCount; ++t) {
        unsigned char count = 0;
        f.read(reinterpret_cast<char*>(&count), 1);
        if (!f)
            throw fail("truncated face data");
        if (count != 3)
            throw fail(fmt::format("face {} has {} vertices, not 3", t, count));
        std::uint32_t idx[3];
        f.read(reinterpret_cast<char*>(idx), sizeof(idx));
        if (!f)
            throw fail("truncated face data");
        for (std::uint32_t i : idx) {
            if ((faceIndexSigned && static_cast<std::int32_t>(i) < 0) || i >= vertexCount) {
                throw fail(fmt::format("face {} refers to vertex {} of {}", t, i, vertexCount));
            }
            data.triangles.push_back(i);
        }
    }
    if (f.peek() != std::char_traits<char>::eof())
        throw fail("trailing bytes after the last element");
    return data;
}

} // namespace swell::runtime
