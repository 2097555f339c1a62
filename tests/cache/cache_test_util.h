#pragma once
// Helpers shared by the cache test files: temp folders, raw file access and the
// byte layout of docs/cache-format.md (tests poke at it on purpose).

#include "swell/cache/synthetic.h"
#include "swell/cache/writer.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <vector>
#include <xxhash.h>

#include "temp_dir.h"

namespace swell::cache::testing {

namespace fs = std::filesystem;

/// A fresh folder (tests/support/temp_dir.h), removed at scope exit.
using swell::test::TempDir;

inline std::vector<std::uint8_t> readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

inline void writeBytes(const fs::path& p, const std::vector<std::uint8_t>& b) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

template <class T> T peek(const std::vector<std::uint8_t>& b, std::size_t off) {
    T v;
    std::memcpy(&v, b.data() + off, sizeof v);
    return v;
}
template <class T> void poke(std::vector<std::uint8_t>& b, std::size_t off, T v) {
    std::memcpy(b.data() + off, &v, sizeof v);
}

/// Layout constants of format version 1 (docs/cache-format.md).
inline constexpr std::size_t kFixedHeader = 96, kEntry = 40, kOffFrameCount = 72,
                             kOffIndexOffset = 80, kOffHeaderSum = 88, kOffVersion = 8;

/// Offset of frame-index entry `i`.
inline std::size_t entryOffset(const std::vector<std::uint8_t>& b, std::size_t i) {
    return static_cast<std::size_t>(peek<std::uint64_t>(b, kOffIndexOffset)) + i * kEntry;
}

/// Recomputes the index checksum after a deliberate index edit, so that the
/// reader's deeper checks (not the checksum) are what is exercised.
inline void resealIndex(std::vector<std::uint8_t>& b) {
    const auto count = peek<std::uint64_t>(b, kOffFrameCount);
    const std::size_t off = peek<std::uint64_t>(b, kOffIndexOffset);
    poke<std::uint64_t>(b, off + count * kEntry, XXH3_64bits(b.data() + off, count * kEntry));
}

/// Same for the header checksum.
inline void resealHeader(std::vector<std::uint8_t>& b) {
    const auto meta = peek<std::uint32_t>(b, 68);
    XXH3_state_t* st = XXH3_createState();
    XXH3_64bits_reset(st);
    XXH3_64bits_update(st, b.data(), kOffHeaderSum);
    XXH3_64bits_update(st, b.data() + kFixedHeader, meta);
    poke<std::uint64_t>(b, kOffHeaderSum, XXH3_64bits_digest(st));
    XXH3_freeState(st);
}

/// A small synthetic wave for tests.
inline SyntheticWave smallWave(std::size_t surface = 40, std::size_t splash = 3) {
    SyntheticWave w;
    w.surfaceCount = surface;
    w.splashCount = splash;
    return w;
}

inline Header headerFor(const SyntheticWave& w, Encoding enc = Encoding::Float32) {
    Header h;
    h.encoding = enc;
    h.domain = syntheticDomain(w);
    h.dt = 0.001;
    h.frameInterval = 20;
    h.seed = 42;
    h.metadataJson = R"({"scene":"test","nested":{"k":[1,2,3]}})";
    return h;
}

/// Writes `frames` synthetic frames and returns them.
inline std::vector<Frame> writeSynthetic(const fs::path& p, const Header& h, const SyntheticWave& w,
                                         std::size_t frames) {
    std::vector<Frame> out;
    Writer writer(p, h);
    for (std::size_t i = 0; i < frames; ++i) {
        out.push_back(syntheticFrame(w, i));
        writer.addFrame(out.back());
    }
    writer.finish();
    return out;
}

} // namespace swell::cache::testing
