#pragma once
// swell-mps-bench's command line, parsed and checked (its built-in scene with the --set
// overrides included) without running, so that mps_bench_main.cpp and the options fuzz target
// (tests/fuzz) share it.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "swell/bake/scene.h"

namespace swell::bake {

struct MpsBenchCommandLine {
    int threads = 0; ///< 0: all
    int warmup = 100;
    int steps = 400;
    std::vector<std::string> sets;
    bool asJson = false;
};

/// Parses argv into `cl`. Returns the exit status when swell-mps-bench should stop now: 0 after
/// --help (printed on `out`), CLI11's code after a bad command line (one line
/// "swell-mps-bench: ... (see --help)" on `err`); nullopt when it should go on.
std::optional<int> parseMpsBenchCommandLine(int argc, const char* const* argv,
                                            MpsBenchCommandLine& cl, std::ostream& out,
                                            std::ostream& err);

/// The built-in scene (a 2.0 m x 1.04 m tank, l0 = 0.01 m, a 1.0 m x 0.84 m water column) with
/// the --set overrides. Throws SceneError.
Scene mpsBenchScene(const MpsBenchCommandLine& cl);

} // namespace swell::bake
