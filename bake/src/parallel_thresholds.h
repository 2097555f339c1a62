#pragma once
// Sizes below which the solver's OpenMP loops run on one thread (internal to swell_bake).
#include <cstddef>

namespace swell::bake {

// Loops shorter than this run on one thread: below it an OpenMP fork/join costs more than
// it saves, and on a busy machine a woken thread may wait a whole scheduler slice.
constexpr std::size_t kParallelMin = 4096;
// Same for the cheap per-element vector operations of the conjugate gradient.
constexpr std::size_t kParallelVector = 65536;

} // namespace swell::bake
