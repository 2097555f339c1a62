#include "swell/runtime/replay/frame_set.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

FrameSet FrameSet::whole(cache::Header header, std::vector<cache::Frame> frames) {
    FrameSet set;
    set.header = std::move(header);
    set.frameCount = frames.size();
    set.ids.resize(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i)
        set.ids[i] = static_cast<std::uint32_t>(i);
    set.frames = std::move(frames);
    return set;
}

const cache::Frame* FrameSet::find(std::uint32_t id) const {
    auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it == ids.end() || *it != id)
        return nullptr;
    return &frames[static_cast<std::size_t>(it - ids.begin())];
}

void FrameSet::validate() const {
    if (frameCount == 0)
        throw std::invalid_argument("the cache holds no frames");
    if (ids.size() != frames.size()) {
        throw std::invalid_argument(
            fmt::format("frame set: {} ids but {} frames", ids.size(), frames.size()));
    }
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] >= frameCount || (i > 0 && ids[i] <= ids[i - 1])) {
            throw std::invalid_argument(fmt::format(
                "frame set: id {} out of order or beyond {} frames", ids[i], frameCount));
        }
        if (frames[i].surface.size() % 2 != 0) {
            throw std::invalid_argument(fmt::format("frame {}: odd surface array", ids[i]));
        }
        for (float v : frames[i].surface) {
            if (!std::isfinite(v)) {
                throw std::invalid_argument(
                    fmt::format("frame {}: non-finite surface particle value", ids[i]));
            }
        }
    }
}

} // namespace swell::runtime
