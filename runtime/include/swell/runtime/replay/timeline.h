#pragma once
// The replay's time axis: which cache frames eq. (5)'s frame number s can show, and what it
// shows outside them (docs/runtime.md, "Steady window and seamless loop").
//
// A timeline is a list of entries. Eq. (5) gives every slice an integer s; the policy turns it
// into an entry (clamp: the nearest end; loop and seamless: s modulo the length), and the entry
// names one cache frame, or two with a cross-fade weight. Entry 0 is animation time tau = 0.
//  * range(first, count): frames first .. first + count - 1 (the steady window, or the whole
//    cache), clamp or loop. Looping jumps from the last frame back to the first.
//  * seamless(loop): the video-texture loop of Schoedl et al. (SIGGRAPH 2000) inside the steady
//    window. Loop points `in` < `out` are two frames whose surface profiles are closest; the
//    entries are in .. out - 1 and then in again, so frame in follows frame out - 1 where
//    frame out would have. Over the last L = crossfade entries before the seam, entry
//    p = P - L + i (P = out - in, i = 0 .. L - 1) blends frame in + p with the frame the loop
//    continues from, in + p - P = in - L + i, with weight (i + 1) / (L + 1) on the latter:
//    both run forward one frame per entry, and the weights go linearly from frame out - L - 1
//    (weight 0 on the other) to frame in (weight 1), so no slice ever jumps.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"
#include "swell/runtime/replay/bake_record.h"
#include "swell/runtime/replay/replay_params.h"

#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace swell::runtime {

/// What one timeline entry shows: (1 - alpha) x frame a + alpha x frame b (column profiles).
struct TimelineEntry {
    std::uint32_t a = 0; ///< cache frame
    std::uint32_t b = 0; ///< cache frame blended in (== a when alpha == 0)
    double alpha = 0.0;  ///< weight of b, in [0, 1)

    bool blended() const { return alpha > 0.0; }
    /// The frame a slice showing this entry counts as (splashes, reports): the heavier one.
    std::uint32_t shown() const { return alpha < 0.5 ? a : b; }
    bool operator==(const TimelineEntry&) const = default;
};

/// Chosen loop points of a seamless timeline.
struct LoopPoints {
    std::uint32_t in = 0;  ///< first frame of the loop (entry 0)
    std::uint32_t out = 0; ///< the frame the loop replaces by `in`: the loop is in .. out - 1
    int crossfade = 0;     ///< L: blended entries before the seam
    /// RMS difference (m) of the surface profiles at the seam: sqrt(mean over k = 0 .. L of
    /// D(out - k, in - k)^2), D the RMS difference of two frames' sampled envelopes.
    double residual = 0.0;
    /// RMS difference (m) of two frames of the window on average (the scale of `residual`).
    double typicalDifference = 0.0;
};

class Timeline {
public:
    /// Frames first .. first + count - 1; policy Clamp or Loop (std::invalid_argument else).
    static Timeline range(std::uint32_t first, std::uint32_t count, FramePolicy policy);
    /// Every one of `frameCount` cache frames: range(0, frameCount, policy), with the errors
    /// a cache's frame count can cause (none, too many, a seamless policy without loop points).
    static Timeline whole(std::size_t frameCount, FramePolicy policy);
    /// The seamless loop through `loop` (see above). Throws std::invalid_argument when the
    /// loop is shorter than 2 L + 1 frames or in < L (no frames to blend with).
    static Timeline seamless(const LoopPoints& loop);

    std::size_t size() const { return m_entries.size(); }
    const TimelineEntry& operator[](std::size_t i) const { return m_entries[i]; }
    const std::vector<TimelineEntry>& entries() const { return m_entries; }
    FramePolicy policy() const { return m_policy; }
    /// Entry index of eq. (5)'s frame number s under the policy.
    std::size_t index(long long s) const;
    /// Highest cache frame any entry names.
    std::uint32_t maxFrame() const;
    const std::optional<LoopPoints>& loop() const { return m_loop; }

private:
    std::vector<TimelineEntry> m_entries;
    FramePolicy m_policy = FramePolicy::Loop;
    std::optional<LoopPoints> m_loop;
};

/// The loop search compares at most this many in-points and as many out-points, so its cost
/// (time, memory, frames decoded) does not grow with the length of the cache: a 100,000-frame
/// window would otherwise compare 25,000 x 25,000 frame pairs (5 GB of distances).
inline constexpr long long kMaxLoopCandidates = 1024;

/// Which frames of a window of W frames the loop search compares (window-relative indices):
/// `in` in [inLo, inHi], the first quarter after the first L frames, and `out` in
/// [outLo, outHi], the last quarter, each at most kMaxLoopCandidates + 1 frames long.
struct LoopSearch {
    long long inLo = 0, inHi = 0, outLo = 0, outHi = 0;
    long long crossfade = 0; ///< L
    /// Frames whose profiles the search reads: [inLo - L, inHi] and [outLo - L, outHi].
    bool reads(long long i) const;
};
/// Throws std::invalid_argument when W frames are too short for a loop with this cross-fade.
LoopSearch loopSearch(std::size_t windowFrames, int crossfade);

/// Loop search over the sampled surface profiles of frames first .. first + W - 1
/// (profiles[i] is frame first + i; those LoopSearch::reads, all of one length; the others may
/// be empty): the pair minimising LoopPoints::residual with `in` and `out` in loopSearch()'s
/// ranges (ties: the longer loop, then the earlier in). Throws std::invalid_argument when the
/// window is too short for a loop with this cross-fade.
LoopPoints findLoop(std::span<const std::vector<double>> profiles, std::uint32_t first,
                    int crossfade);

/// The timeline a replay of a cache uses, and where it came from.
struct TimelinePlan {
    Timeline timeline;
    BakeRecord record;
    std::uint32_t windowFirst = 0;   ///< first cache frame of the window the timeline lives in
    std::uint32_t windowLast = 0;    ///< last one
    double frameTime = 0.0;          ///< simulated seconds between cache frames
    double sliceSpreadSeconds = 0.0; ///< 2 F x time unit: the frame spread of one instant
    double searchMs = 0.0;           ///< wall time of the loop search (profiles included)
};

/// Plans the timeline of a replay of a cache with `header` and `frameCount` frames:
///  * the window: frames from the recorded steady start (rounded up to a frame) to the last,
///    when params.steadyWindow and the cache records it; else every frame;
///  * clamp / loop: Timeline::range over the window; seamless: findLoop over the envelopes of
///    the window frames loopSearch() compares, sampled at 256 points over the grid's x range
///    (each such frame is read once through `readFrame`, no other), cross-fade
///    params.crossfadeSeconds (fewer frames when the window is short).
/// Throws std::invalid_argument with a message that says how long the bake must be when the
/// steady window is empty or, with F > 0, shorter than the slice spread 2 F x time unit.
TimelinePlan planTimeline(const cache::Header& header, std::size_t frameCount,
                          const ReplayParams& params,
                          const std::function<cache::Frame(std::uint32_t)>& readFrame);

/// {"policy", "window": {"first_frame", "last_frame", "start_s", "end_s", "steady_start_s",
///  "steady_reason", "recorded"}, "entries", "slice_spread_s", "loop": {"in_frame", "out_frame",
///  "in_s", "out_s", "loop_seconds", "crossfade_frames", "residual_m", "typical_difference_m"} or
///  null}. No wall times: the same replay writes the same record (searchMs is for benches).
nlohmann::json toJson(const TimelinePlan& plan);

} // namespace swell::runtime
