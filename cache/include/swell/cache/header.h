#pragma once
// Header metadata of a .swell cache (docs/cache-format.md).

#include <cstdint>
#include <string>

namespace swell::cache {

/// Current (and highest readable) format version.
inline constexpr std::uint32_t kFormatVersion = 1;

/// How particle records are stored inside a frame.
enum class Encoding : std::uint32_t {
    Float32 = 0,     ///< IEEE float32, lossless (default)
    Quantized16 = 1, ///< positions as uint16 over the domain bounds; velocities float32
};

/// Axis-aligned bounds of everything stored (metres).
struct Domain {
    float xMin = 0.0f;
    float yMin = 0.0f;
    float xMax = 1.0f;
    float yMax = 1.0f;

    /// Whether (x, y) lies inside, bounds included: the rule every stored position keeps (false
    /// for a NaN).
    bool contains(float x, float y) const {
        return x >= xMin && x <= xMax && y >= yMin && y <= yMax;
    }
};

/// What a bake says about itself; written once, read back verbatim.
struct Header {
    Encoding encoding = Encoding::Float32;
    /// Byte-shuffle filter before zstd (improves the ratio on smooth float data).
    bool shuffle = true;
    /// Delta filter (each value minus the previous particle's) before the shuffle;
    /// pays off when particles are stored in order along the surface.
    bool delta = true;
    /// zstd compression level used by the writer (1..19); informational when read.
    int compressionLevel = 3;
    Domain domain;
    /// Simulation time step (s).
    double dt = 0.001;
    /// Simulation steps between stored frames.
    std::uint32_t frameInterval = 1;
    /// Seed of the bake (piston motion etc.).
    std::uint64_t seed = 0;
    /// Scene and solver parameters, program version: JSON text, stored verbatim.
    std::string metadataJson = "{}";

    /// Simulated seconds between stored frames.
    double frameTime() const { return dt * frameInterval; }
    /// Largest position error of the encoding (m): 0 for float32, half a
    /// quantization step (per axis) for Quantized16.
    float maxPositionError() const;
};

} // namespace swell::cache
