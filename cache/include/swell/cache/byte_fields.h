#pragma once
// Fixed-size fields of swell's binary files (a cache's header, index and records; a bake
// checkpoint's header): little-endian, unaligned, copied byte for byte.

#include <bit>
#include <cstdint>
#include <cstring>

namespace swell::cache {

static_assert(std::endian::native == std::endian::little, "swell's binary files are little-endian");

/// Stores `v` at `p` (no alignment needed).
template <class T> void putField(std::uint8_t* p, T v) {
    std::memcpy(p, &v, sizeof(T));
}

/// Loads a T from `p` (no alignment needed).
template <class T> T getField(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

} // namespace swell::cache
