#pragma once
// swell-cache's command line: its subcommands and options, parsed and checked without touching
// a cache, so that main.cpp and the options fuzz target (tests/fuzz/options_fuzz.cpp) share it.

#include "swell/cache/header.h"
#include "swell/cache/synthetic.h"

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

namespace swell::cache {

/// Options of every subcommand (each reads its own).
struct CacheOptions {
    std::string path;
    bool asJson = false;
    std::size_t frameIndex = 0;
    std::string recodeOut;
    SyntheticWave wave;
    std::size_t frames = 1200;
    std::string encoding = "float32";
    bool noShuffle = false;
    bool noDelta = false;
    int level = 3;

    /// The encoding and filter options applied to `h`.
    void applyEncoding(Header& h) const {
        h.encoding = encoding == "float32" ? Encoding::Float32 : Encoding::Quantized16;
        h.shuffle = !noShuffle;
        h.delta = !noDelta;
        h.compressionLevel = level;
    }
};

enum class CacheCommand { Info, Verify, Dump, Recode, Synth };

/// Parses argv into `o` and `command`. Returns the exit status when swell-cache should stop now:
/// 0 after --help (printed on `out`), CLI11's code after a bad command line (one line
/// "swell-cache: ... (see --help)" on `err`); nullopt when it should go on.
std::optional<int> parseCacheCommandLine(int argc, const char* const* argv, CacheOptions& o,
                                         CacheCommand& command, std::ostream& out,
                                         std::ostream& err);

} // namespace swell::cache
