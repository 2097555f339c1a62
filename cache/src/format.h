#pragma once
// On-disk layout of a .swell file (docs/cache-format.md). Private to swell_cache.

#include "swell/cache/byte_fields.h"
#include "swell/cache/frame.h"
#include "swell/cache/header.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace swell::cache::format {

/// PNG-style magic: non-ASCII first byte, CR LF and ^Z catch text-mode mangling.
inline constexpr std::uint8_t kMagic[8] = {0x89, 'S', 'W', 'L', '\r', '\n', 0x1a, '\n'};
/// Size of the fixed header, before the metadata JSON.
inline constexpr std::size_t kFixedHeaderSize = 96;
/// Size of one frame-index entry.
inline constexpr std::size_t kIndexEntrySize = 40;
/// Upper bounds that make a damaged file fail fast instead of allocating wildly.
inline constexpr std::uint64_t kMaxMetadataBytes = 16u << 20;  // 16 MiB
inline constexpr std::uint64_t kMaxRawFrameBytes = 256u << 20; // 256 MiB per frame

/// A frame's raw size is at most 1 MiB + 1024 x its compressed size: particle positions and
/// velocities compress a few times, never a thousand, so a small file stating huge frames is
/// damaged, and is refused when opened rather than after decoding them.
inline constexpr std::uint64_t kRatioSlackBytes = 1u << 20;
inline constexpr std::uint64_t kMaxCompressionRatio = 1024;
inline bool rawSizeFits(std::uint64_t rawSize, std::uint64_t compressedSize) {
    return rawSize <= kRatioSlackBytes + kMaxCompressionRatio * compressedSize;
}
inline constexpr std::uint32_t kFlagShuffle = 1u;
inline constexpr std::uint32_t kFlagDelta = 2u;

/// Byte offsets of the fixed header fields.
enum Offset : std::size_t {
    kOffVersion = 8,
    kOffHeaderSize = 12,
    kOffEncoding = 16,
    kOffFlags = 20,
    kOffDomain = 24, // 4 x f32
    kOffDt = 40,
    kOffFrameInterval = 48,
    kOffLevel = 52,
    kOffSeed = 56,
    kOffMaxError = 64,
    kOffMetadataLength = 68,
    kOffFrameCount = 72,
    kOffIndexOffset = 80,
    kOffHeaderChecksum = 88,
};

/// Bytes of the decoded record of a frame with these counts.
std::uint64_t rawRecordSize(Encoding enc, std::uint64_t surfaceCount, std::uint64_t splashCount);

/// Encodes `frame` into `out` (sections laid out as the spec says; no shuffle).
void encodeRecord(const Header& h, const Frame& frame, std::vector<std::uint8_t>& out);
/// Decodes a record of known counts (sizes already validated).
Frame decodeRecord(const Header& h, std::span<const std::uint8_t> raw, std::uint32_t surfaceCount,
                   std::uint32_t splashCount);

/// Byte-shuffle filter, section by section (element size 4 for float32, 2 for uint16).
void shuffle(Encoding enc, std::uint32_t surfaceCount, std::uint32_t splashCount,
             std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out, bool inverse);

/// XXH3-64 of a byte range (frame records, the index).
/// Delta filter, in place: each element minus the same component of the previous
/// particle, as unsigned integers of the element size (wrapping). Applied before shuffle.
void delta(Encoding enc, std::uint32_t surfaceCount, std::uint32_t splashCount,
           std::span<std::uint8_t> data, bool inverse);

std::uint64_t checksum(const void* data, std::size_t size);
/// XXH3-64 of the fixed header up to the checksum field, followed by the metadata.
/// `head` holds the fixed header and the metadata, contiguous.
std::uint64_t headerChecksum(std::span<const std::uint8_t> head);

} // namespace swell::cache::format
