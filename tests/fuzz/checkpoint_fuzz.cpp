// libFuzzer target for checkpoint files (bake/src/checkpoint.cpp, docs/scenes.md
// "Checkpoints"): readCheckpoint must return a consistent checkpoint or throw one
// CheckpointError line naming the file; nothing else may escape, crash, hang or allocate
// without bound. The first input byte picks what the rest is, so that the fuzzer gets past the
// checksums: 0 the whole file as is; 1 a payload, zstd-compressed behind a valid header;
// 2 a header + compressed payload whose checksums are made right.
#include "fuzz_check.h"

#include "swell/bake/checkpoint.h"

#include "temp_dir.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <xxhash.h>
#include <zstd.h>

using namespace swell::bake;

namespace {

constexpr std::size_t kHeader = 48; // magic, version, flags, sizes, checksums (checkpoint.h)
constexpr std::uint8_t kMagic[8] = {0x89, 'S', 'W', 'K', '\r', '\n', 0x1a, '\n'};

template <class T> void put(std::uint8_t* p, T v) {
    std::memcpy(p, &v, sizeof(T));
}

/// A file around a payload: valid header, compressed payload, both checksums right.
std::vector<std::uint8_t> wrap(const std::uint8_t* raw, std::size_t size) {
    std::vector<std::uint8_t> file(kHeader + ZSTD_compressBound(size));
    const std::size_t n = ZSTD_compress(file.data() + kHeader, file.size() - kHeader, raw, size, 1);
    swell::fuzz::require(!ZSTD_isError(n), "zstd cannot compress the fuzz input");
    file.resize(kHeader + n);
    std::memcpy(file.data(), kMagic, sizeof kMagic);
    put<std::uint32_t>(file.data() + 8, 1);
    put<std::uint32_t>(file.data() + 12, 0);
    put<std::uint64_t>(file.data() + 16, n);
    put<std::uint64_t>(file.data() + 24, size);
    return file;
}

void fixChecksums(std::vector<std::uint8_t>& file) {
    if (file.size() < kHeader)
        return;
    put<std::uint64_t>(file.data() + 32, XXH3_64bits(file.data() + kHeader, file.size() - kHeader));
    put<std::uint64_t>(file.data() + 40, XXH3_64bits(file.data(), 40));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0)
        return 0;
    std::vector<std::uint8_t> file;
    switch (data[0] % 3) {
    case 0:
        file.assign(data + 1, data + size);
        break;
    case 1:
        file = wrap(data + 1, size - 1);
        fixChecksums(file);
        break;
    default:
        file.assign(data + 1, data + size);
        fixChecksums(file);
        break;
    }
    // One file per process, in a folder removed when the process exits.
    static const swell::test::TempDir folder("swell-checkpoint-fuzz-");
    static const std::filesystem::path path = folder / "input.ckpt";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    swell::fuzz::require(f != nullptr, "cannot write the fuzz input", path.string());
    const bool written = std::fwrite(file.data(), 1, file.size(), f) == file.size();
    swell::fuzz::require(std::fclose(f) == 0 && written, "cannot write the fuzz input");
    try {
        const Checkpoint c = readCheckpoint(path);
        // Accepted: the reader's own promises (checkpoint.h) hold.
        const MpsState& s = c.solver;
        swell::fuzz::require(s.particles.consistent(), "particle arrays differ in length");
        swell::fuzz::require(s.neighborX.size() == s.particles.size() &&
                                 s.neighborY.size() == s.particles.size(),
                             "solver arrays differ in length");
        swell::fuzz::require(c.probeRows.size() == c.frames.size(), "rows and frames differ");
        swell::fuzz::require(s.step >= 0 && c.checkpointEvery >= 0, "negative step");
        for (const auto& fr : c.frames) {
            swell::fuzz::require(fr.surface.size() % 2 == 0 && fr.splash.size() % 4 == 0,
                                 "a frame holds a partial particle");
        }
    } catch (const CheckpointError& e) {
        swell::fuzz::requireClearError(e.what(), path.string() + ": ");
    }
    return 0;
}
