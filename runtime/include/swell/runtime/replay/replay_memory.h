#pragma once
// What a replay will hold, estimated from the cache's frame index before anything is decoded or
// uploaded, and the memory budget it is checked against: a replay that would need more fails up
// front with a message naming the budget (or, in swell-play heights and render, streams its
// frames in chunks that fit), never running out of memory midway.
//
// The estimate follows GpuReplay's construction (gpu_replay.h) per slice set: the column sums of
// every held frame and cross-faded timeline entry (8 floats per column quad), their CPU staging
// copy, the particles and bin index uploaded for the paper's column pass, the timeline and slice
// tables, and the N x M height buffer and texture; plus the decoded frames themselves (exact:
// the index records each frame's particle counts). On Mesa llvmpipe the GPU buffers are process
// memory too; docs/BENCHMARKS.md ("Memory on long caches") compares it with measured peaks.

#include "swell/cache/reader.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/timeline.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace swell::runtime {

/// The default budget of swell-play (--memory-budget) and Playback, GiB.
inline constexpr double kDefaultMemoryBudgetGiB = 2.0;

struct ReplayMemory {
    std::size_t frames = 0;       ///< cache frames held
    std::size_t decodedBytes = 0; ///< the held frames, decoded (surface and splash particles)
    std::size_t gpuBytes = 0;     ///< GPU buffers of every slice set
    std::size_t stagingBytes = 0; ///< CPU copies made while uploading (the peak of construction)
    std::size_t total() const { return decodedBytes + gpuBytes + stagingBytes; }
};

/// Estimate for holding cache frames `ids` of `reader` in a replay with `params` (its grid) and
/// `sliceSets` slice sets (1, or the ripple's directions) over `timeline` (its entries' tables
/// and one column slot per cross-faded entry, in each set).
ReplayMemory estimateReplayMemory(const cache::Reader& reader, std::span<const std::uint32_t> ids,
                                  const ReplayParams& params, std::size_t sliceSets,
                                  const Timeline& timeline);

/// Bytes of `gib` GiB; throws std::invalid_argument naming `option` unless 0 < gib <= 1 TiB.
std::size_t budgetBytes(double gib, const std::string& option);

/// Throws std::invalid_argument when m.total() > budget: "`what` needs about X GiB (F frames
/// decoded: X GiB, GPU buffers: X GiB, upload copies: X GiB), above the memory budget of B GiB
/// (`option`): `advice`".
void checkMemoryBudget(const ReplayMemory& m, std::size_t budget, const std::string& what,
                       const std::string& option, const std::string& advice);

} // namespace swell::runtime
