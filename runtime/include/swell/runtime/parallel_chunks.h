#pragma once
// CPU work split over the machine's cores, for the per-frame splash sprites (built and culled
// while llvmpipe's rasteriser threads shade the surface; on 2 cores the threads take turns, and
// a core that would wait for the other does work). Plain std::threads rather than OpenMP:
// OpenMP's idle threads spin after a parallel region and would take the cores from the
// rasteriser.

#include <cstddef>
#include <functional>

namespace swell::runtime {

/// Calls f(chunk, begin, end) once for each of `chunks` consecutive ranges that split
/// [0, n) (chunk c covers [n c / chunks, n (c + 1) / chunks)), chunk 0 on the calling thread and
/// the others on threads of their own, and returns when all are done. The ranges and their
/// order do not depend on timing, so results written per range are deterministic. An exception
/// from any chunk is rethrown (the first by chunk index) after all have finished.
void forEachChunk(
    std::size_t n, std::size_t chunks,
    const std::function<void(std::size_t chunk, std::size_t begin, std::size_t end)>& f);

/// How many chunks to split `n` items into: one per hardware thread, but at least
/// `minPerChunk` items per chunk (and at least one chunk).
std::size_t chunkCount(std::size_t n, std::size_t minPerChunk);

} // namespace swell::runtime
