#pragma once
// The cache frames a replay holds in memory: all of them, or only those its slices will
// select (SliceSampler::framesUsed), so that frames never selected are never decoded.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"

#include <cstdint>
#include <vector>

namespace swell::runtime {

struct FrameSet {
    cache::Header header;             ///< the cache's header (domain, dt, frame interval)
    std::size_t frameCount = 0;       ///< frames in the cache (eq. 5's range, clamp / loop)
    std::vector<std::uint32_t> ids;   ///< cache indices of the frames held, strictly ascending
    std::vector<cache::Frame> frames; ///< frames[i] is cache frame ids[i]

    /// Every frame of an in-memory cache.
    static FrameSet whole(cache::Header header, std::vector<cache::Frame> frames);
    /// The held frame with cache index `id`, or null.
    const cache::Frame* find(std::uint32_t id) const;
    /// Throws std::invalid_argument if ids are not ascending, out of range or not matched by
    /// frames, a surface array has odd length, or a surface value is not finite.
    void validate() const;
};

} // namespace swell::runtime
