#pragma once
// FNV-1a over bytes: a fixed hash for "same output" checks in tests.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace swell::test {

inline std::uint64_t fnv1a(const void* data, std::size_t size,
                           std::uint64_t h = 0xcbf29ce484222325ULL) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
        h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

/// h * 31 + FNV-1a of `frames` (slice frame indices): a chain of hashes over many updates.
inline std::uint64_t chainFrames(std::uint64_t h, const std::vector<std::uint32_t>& frames) {
    return h * 31 + fnv1a(frames.data(), frames.size() * sizeof(std::uint32_t));
}

/// h * 31 + FNV-1a of `heights` as float32 (what the GPU computed).
inline std::uint64_t chainHeights(std::uint64_t h, const std::vector<double>& heights) {
    const std::vector<float> f(heights.begin(), heights.end());
    return h * 31 + fnv1a(f.data(), f.size() * sizeof(float));
}

} // namespace swell::test
