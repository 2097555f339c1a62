#pragma once
// FNV-1a over bytes: a fixed hash for "same output" checks in tests.

#include <cstddef>
#include <cstdint>

namespace swell::test {

inline std::uint64_t fnv1a(const void* data, std::size_t size,
                           std::uint64_t h = 0xcbf29ce484222325ULL) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
        h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

} // namespace swell::test
