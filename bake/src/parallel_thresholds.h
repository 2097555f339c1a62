#pragma once
// Sizes below which the solver's OpenMP loops run on one thread (internal to swell_bake).
#include <cstddef>

namespace swell::bake {

// Loops shorter than this run on one thread: below it an OpenMP fork/join costs more than
// it saves, and on a busy machine a woken thread may wait a whole scheduler slice.
constexpr std::size_t kParallelMin = 4096;
// Same for the cheap per-element vector operations of the conjugate gradient.
constexpr std::size_t kParallelVector = 65536;
// Chunk of the particle loops whose work differs by kind. The particles are stored water
// first, then the fixed ones, which the explicit, collision, correction and shifting loops
// skip: plain static halves gave the first thread all water and the second the walls (at the
// paper's scale 5,376 water particles against 3,024 and 2,352 fixed ones). Chunks dealt
// round-robin share the kinds evenly; each particle's result does not depend on the thread
// that computes it, so the bits are those of any other schedule.
constexpr int kParticleChunk = 256;

} // namespace swell::bake
