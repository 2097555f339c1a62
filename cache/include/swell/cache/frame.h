#pragma once
// One stored simulation frame: the surface and splash particles kept by the
// eq. (4) classification. Everything else (deep water, walls) is never stored.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace swell::cache {

/// Particles of one simulation frame, float32, interleaved.
struct Frame {
    /// Surface particles as x0, y0, x1, y1, ... (metres).
    std::vector<float> surface;
    /// Splash particles as x, y, vx, vy per particle (metres, metres per second).
    std::vector<float> splash;

    std::size_t surfaceCount() const { return surface.size() / 2; }
    std::size_t splashCount() const { return splash.size() / 4; }
    bool operator==(const Frame&) const = default;
};

/// Index entry of one frame (docs/cache-format.md, "Frame index").
struct FrameInfo {
    std::uint64_t offset = 0;         ///< byte offset of the compressed record in the file
    std::uint64_t compressedSize = 0; ///< bytes on disk
    std::uint64_t rawSize = 0;        ///< bytes after decompression (and unshuffle)
    std::uint32_t surfaceCount = 0;
    std::uint32_t splashCount = 0;
    std::uint64_t checksum = 0; ///< XXH3-64 of the decompressed record
};

} // namespace swell::cache
