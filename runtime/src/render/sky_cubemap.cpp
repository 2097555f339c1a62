#include "swell/runtime/render/sky_cubemap.h"

#include "swell/runtime/error.h"
#include "swell/split_mix64.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace swell::runtime {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Smooth value noise on a periodic 3D lattice of `n` cells (random values from SplitMix64).
class ValueNoise3 {
public:
    ValueNoise3(std::uint64_t seed, int n) : m_n(n), m_values(static_cast<std::size_t>(n) * n * n) {
        SplitMix64 rng(seed);
        for (double& v : m_values)
            v = rng.uniform();
    }
    double operator()(double x, double y, double z) const {
        const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
        const double tx = smooth(x - fx), ty = smooth(y - fy), tz = smooth(z - fz);
        const int ix = static_cast<int>(fx), iy = static_cast<int>(fy), iz = static_cast<int>(fz);
        double c[2][2][2];
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
                for (int d = 0; d < 2; ++d)
                    c[a][b][d] = at(ix + a, iy + b, iz + d);
        auto lerp = [](double u, double v, double t) { return u + (v - u) * t; };
        const double x00 = lerp(c[0][0][0], c[1][0][0], tx), x10 = lerp(c[0][1][0], c[1][1][0], tx);
        const double x01 = lerp(c[0][0][1], c[1][0][1], tx), x11 = lerp(c[0][1][1], c[1][1][1], tx);
        return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
    }

private:
    static double smooth(double t) { return t * t * (3.0 - 2.0 * t); }
    double at(int x, int y, int z) const {
        auto wrap = [this](int v) { return ((v % m_n) + m_n) % m_n; };
        return m_values[(static_cast<std::size_t>(wrap(z)) * m_n + wrap(y)) * m_n + wrap(x)];
    }
    int m_n;
    std::vector<double> m_values;
};

std::uint8_t toByte(double v) {
    // Linear to sRGB-ish display value (gamma 2.2), rounded.
    const double g = std::pow(std::clamp(v, 0.0, 1.0), 1.0 / 2.2);
    return static_cast<std::uint8_t>(std::lround(g * 255.0));
}

} // namespace

void SkyParams::validate() const {
    if (!(sunElevationDegrees > -90.0 && sunElevationDegrees < 90.0)) {
        throw std::invalid_argument(fmt::format(
            "sky sun elevation must be in (-90, 90) degrees, got {}", sunElevationDegrees));
    }
    if (!std::isfinite(sunAzimuthDegrees))
        throw std::invalid_argument("sky sun azimuth must be finite");
    if (!(cloudCover >= 0.0 && cloudCover <= 1.0)) {
        throw std::invalid_argument(
            fmt::format("sky cloud cover must be in [0, 1], got {}", cloudCover));
    }
    if (!(sunRadiusDegrees > 0.0 && sunRadiusDegrees <= 10.0)) {
        throw std::invalid_argument(
            fmt::format("sky sun radius must be in (0, 10] degrees, got {}", sunRadiusDegrees));
    }
    if (!(sunGlow >= 0.0 && sunGlow <= 4.0))
        throw std::invalid_argument(fmt::format("sky sun glow must be in [0, 4], got {}", sunGlow));
    if (faceSize < 8 || faceSize > 4096) {
        throw std::invalid_argument(
            fmt::format("sky face size must be in [8, 4096], got {}", faceSize));
    }
}

Vec3 sunDirection(const SkyParams& sky) {
    const double a = sky.sunAzimuthDegrees * kDeg, e = sky.sunElevationDegrees * kDeg;
    return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

Vec3 cubeDirection(int face, int x, int y, int size) {
    const double s = 2.0 * (x + 0.5) / size - 1.0;
    const double t = 2.0 * (y + 0.5) / size - 1.0;
    switch (face) {
    case 0:
        return {1.0, -t, -s};
    case 1:
        return {-1.0, -t, s};
    case 2:
        return {s, 1.0, t};
    case 3:
        return {s, -1.0, -t};
    case 4:
        return {s, -t, 1.0};
    case 5:
        return {-s, -t, -1.0};
    default:
        throw std::logic_error("cube face out of range");
    }
}

CubeFaces proceduralSky(const SkyParams& sky) {
    sky.validate();
    const Vec3 sun = sunDirection(sky);
    const ValueNoise3 noise(sky.cloudSeed, 32);
    const int n = sky.faceSize;
    CubeFaces faces;
    for (int face = 0; face < 6; ++face) {
        Image& im = faces[static_cast<std::size_t>(face)];
        im = Image(n, n);
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                Vec3 d = cubeDirection(face, x, y, n);
                const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (double& v : d)
                    v /= len;
                Vec3 c;
                if (d[1] >= 0.0) {
                    // Gradient from the horizon to the zenith.
                    const double t = std::pow(d[1], 0.45);
                    for (int k = 0; k < 3; ++k)
                        c[k] =
                            sky.horizonColour[k] + (sky.zenithColour[k] - sky.horizonColour[k]) * t;
                    // Clouds: fBm of value noise on the sky dome projected onto a plane, faded
                    // towards the horizon.
                    if (sky.cloudCover > 0.0 && d[1] > 0.02) {
                        const double px = d[0] / (d[1] + 0.15) * 3.0,
                                     pz = d[2] / (d[1] + 0.15) * 3.0;
                        double f = 0.0, amp = 0.5, freq = 1.0;
                        for (int o = 0; o < 5; ++o) {
                            f += amp * noise(px * freq + 11.3, pz * freq + 5.7, 1.7 * o);
                            amp *= 0.5;
                            freq *= 2.03;
                        }
                        const double threshold = 1.0 - sky.cloudCover;
                        double cloud = std::clamp((f - threshold * 0.9) / 0.25, 0.0, 1.0);
                        cloud *= std::clamp(d[1] / 0.12, 0.0, 1.0);
                        for (int k = 0; k < 3; ++k)
                            c[k] += (0.95 - c[k]) * cloud * 0.85;
                    }
                } else {
                    // Below the horizon: haze blending into the ground colour.
                    const double t = std::clamp(-d[1] * 4.0, 0.0, 1.0);
                    for (int k = 0; k < 3; ++k)
                        c[k] =
                            sky.horizonColour[k] + (sky.groundColour[k] - sky.horizonColour[k]) * t;
                }
                // Sun: a disc of angular radius sunRadiusDegrees with a soft rim, a tight
                // glow around it and a wide haze, warm-tinted (the glint's light, sunDirection).
                const double cosSun = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
                const double angle = std::acos(std::clamp(cosSun, -1.0, 1.0)) / kDeg;
                const double disc =
                    std::clamp((sky.sunRadiusDegrees + 0.25 - angle) / 0.5, 0.0, 1.0);
                const double near = std::max(cosSun, 0.0);
                const double glow =
                    sky.sunGlow * (0.6 * std::pow(near, 300.0) + 0.3 * std::pow(near, 24.0) +
                                   0.12 * std::pow(near, 4.0));
                static constexpr double kWarm[3] = {1.0, 0.92, 0.75};
                for (int k = 0; k < 3; ++k)
                    c[k] += (glow + 2.0 * disc) * kWarm[k];
                std::uint8_t* p = im.pixel(x, y);
                for (int k = 0; k < 3; ++k)
                    p[k] = toByte(c[k]);
            }
        }
    }
    return faces;
}

CubeFaces loadSkyImages(const std::filesystem::path& dir) {
    static constexpr const char* kNames[6] = {"px.png", "nx.png", "py.png",
                                              "ny.png", "pz.png", "nz.png"};
    CubeFaces faces;
    for (int i = 0; i < 6; ++i) {
        const auto path = dir / kNames[i];
        if (!std::filesystem::exists(path)) {
            throw RuntimeError(fmt::format(
                "sky image {} is missing (need px, nx, py, ny, pz, nz .png)", path.string()));
        }
        faces[static_cast<std::size_t>(i)] = readPng(path);
        const Image& im = faces[static_cast<std::size_t>(i)];
        if (im.width != im.height || im.width != faces[0].width) {
            throw RuntimeError(
                fmt::format("sky image {} is {}x{}: all six must be square and one size",
                            path.string(), im.width, im.height));
        }
    }
    return faces;
}

Vec3 zenithRadiance(const CubeFaces& faces) {
    const Image& top = faces[2]; // +y
    if (top.width <= 0 || top.height <= 0)
        throw std::invalid_argument("zenithRadiance: empty +y face");
    auto decode = [](std::uint8_t byte) { // the GL sRGB8 decoding
        const double c = byte / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    // (0, 1, 0) is the face's centre: texel (n - 1) / 2 for odd n, the four around it for even.
    const int x0 = (top.width - 1) / 2, x1 = top.width / 2;
    const int y0 = (top.height - 1) / 2, y1 = top.height / 2;
    Vec3 sum{0.0, 0.0, 0.0};
    for (int y : {y0, y1})
        for (int x : {x0, x1})
            for (int k = 0; k < 3; ++k)
                sum[static_cast<std::size_t>(k)] += decode(top.pixel(x, y)[k]);
    for (double& c : sum)
        c *= 0.25;
    return sum;
}

GlTexture makeCubemapTexture(const CubeFaces& faces) {
    const int n = faces[0].width;
    for (const Image& im : faces) {
        if (im.width != n || im.height != n || n <= 0)
            throw std::invalid_argument("cube faces must be square and one size");
    }
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &name);
    GlTexture texture(name);
    int levels = 1;
    while ((n >> levels) > 0)
        ++levels;
    glTextureStorage2D(name, levels, GL_SRGB8, n, n); // sampled as linear RGB
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int face = 0; face < 6; ++face) {
        glTextureSubImage3D(name, 0, 0, 0, face, n, n, 1, GL_RGB, GL_UNSIGNED_BYTE,
                            faces[static_cast<std::size_t>(face)].rgb.data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glGenerateTextureMipmap(name);
    // Reflections sample one fixed level (ShadingParams::reflectionLod): bilinear within it.
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(name, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    checkGl("creating the sky cube map");
    return texture;
}

} // namespace swell::runtime
