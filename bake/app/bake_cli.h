#pragma once
// swell-bake's command line (README.md, "Programs"): its options, parsed and checked without
// baking, so that main.cpp and the options fuzz target (tests/fuzz/options_fuzz.cpp) share it.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "swell/bake/scene.h"

namespace swell::bake {

/// What swell-bake was asked to do.
struct BakeCommandLine {
    std::string scenePath, output, probes;
    std::vector<std::string> sets; ///< --set overrides, in order
    int threads = 0;               ///< 0: OpenMP's choice
    long checkpointEvery = 0;
    bool asJson = false, quiet = false, resume = false;
};

/// Parses argv into `cl`. Returns the exit status when swell-bake should stop now: 0 after
/// --help (printed on `out`), 2 after a bad option (one line "swell-bake: ... (see --help)" on
/// `err`); nullopt when it should go on.
std::optional<int> parseBakeCommandLine(int argc, const char* const* argv, BakeCommandLine& cl,
                                        std::ostream& out, std::ostream& err);

/// The scene a bake would run: loaded with the --set overrides and checked as runBake checks it
/// before its first step (fixed dt, whole frame interval, step count). Throws SceneError.
Scene loadBakeScene(const BakeCommandLine& cl);

} // namespace swell::bake
