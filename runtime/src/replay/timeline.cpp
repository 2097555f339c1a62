#include "swell/runtime/replay/timeline.h"

#include "swell/runtime/replay/surface_envelope.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace swell::runtime {

Timeline Timeline::range(std::uint32_t first, std::uint32_t count, FramePolicy policy) {
    if (policy == FramePolicy::Seamless)
        throw std::invalid_argument("Timeline::range: the seamless policy needs loop points");
    if (count == 0 || count > 0x7fffffffu || first > 0x7fffffffu - count) {
        throw std::invalid_argument(
            fmt::format("a timeline needs 1 .. 2^31 - 1 frames, got {} from {}", count, first));
    }
    Timeline t;
    t.m_policy = policy;
    t.m_entries.resize(count);
    for (std::uint32_t i = 0; i < count; ++i)
        t.m_entries[i] = {first + i, first + i, 0.0};
    return t;
}

Timeline Timeline::whole(std::size_t frameCount, FramePolicy policy) {
    if (frameCount == 0 || frameCount > 0x7fffffffu) {
        throw std::invalid_argument(
            fmt::format("cache has {} frames; need 1 .. 2^31 - 1", frameCount));
    }
    if (policy == FramePolicy::Seamless) {
        throw std::invalid_argument(
            "the seamless policy needs a planned timeline (planTimeline, timeline.h)");
    }
    return range(0, static_cast<std::uint32_t>(frameCount), policy);
}

Timeline Timeline::seamless(const LoopPoints& loop) {
    const long long L = loop.crossfade;
    const long long P = static_cast<long long>(loop.out) - static_cast<long long>(loop.in);
    if (L < 0 || P < 2 * L + 1 || static_cast<long long>(loop.in) < L || P > 0x7fffffff) {
        throw std::invalid_argument(fmt::format(
            "loop {} .. {} with a {}-frame cross-fade: need out - in >= 2 L + 1 and in >= L",
            loop.in, loop.out, loop.crossfade));
    }
    Timeline t;
    t.m_policy = FramePolicy::Seamless;
    t.m_loop = loop;
    t.m_entries.resize(static_cast<std::size_t>(P));
    for (long long p = 0; p < P; ++p) {
        const auto a = static_cast<std::uint32_t>(loop.in + p);
        TimelineEntry e{a, a, 0.0};
        const long long i = p - (P - L); // 0 .. L - 1 inside the cross-fade
        if (i >= 0) {
            e.b = static_cast<std::uint32_t>(loop.in + p - P);
            e.alpha = static_cast<double>(i + 1) / static_cast<double>(L + 1);
        }
        t.m_entries[static_cast<std::size_t>(p)] = e;
    }
    return t;
}

std::size_t Timeline::index(long long s) const {
    const auto n = static_cast<long long>(m_entries.size());
    if (m_policy == FramePolicy::Clamp)
        return static_cast<std::size_t>(std::clamp(s, 0LL, n - 1));
    return static_cast<std::size_t>(((s % n) + n) % n);
}

std::uint32_t Timeline::maxFrame() const {
    std::uint32_t m = 0;
    for (const TimelineEntry& e : m_entries)
        m = std::max({m, e.a, e.b});
    return m;
}

LoopSearch loopSearch(std::size_t windowFrames, int crossfade) {
    const auto W = static_cast<long long>(windowFrames);
    const long long L = crossfade;
    const long long span = std::min(W / 4, kMaxLoopCandidates);
    LoopSearch s{L, std::min(W - 1, L + span), std::max(0LL, W - 1 - span), W - 1, L};
    if (L < 0 || s.inLo > s.inHi || s.outHi - s.inLo < 2 * L + 1) {
        throw std::invalid_argument(fmt::format(
            "a window of {} frames is too short for a seamless loop with a {}-frame cross-fade", W,
            crossfade));
    }
    return s;
}

bool LoopSearch::reads(long long i) const {
    return (i >= inLo - crossfade && i <= inHi) || (i >= outLo - crossfade && i <= outHi);
}

LoopPoints findLoop(std::span<const std::vector<double>> profiles, std::uint32_t first,
                    int crossfade) {
    const LoopSearch search = loopSearch(profiles.size(), crossfade);
    const long long L = crossfade;
    const long long inLo = search.inLo, inHi = search.inHi;
    const long long outLo = search.outLo, outHi = search.outHi;
    const std::size_t Q = profiles[static_cast<std::size_t>(inLo - L)].size();
    for (std::size_t i = 0; i < profiles.size(); ++i) {
        if (search.reads(static_cast<long long>(i)) && profiles[i].size() != Q)
            throw std::invalid_argument("findLoop: profiles of different lengths");
    }
    // D^2 between frames i in [inLo - L, inHi] and j in [outLo - L, outHi], computed once.
    const long long i0 = inLo - L, j0 = outLo - L;
    const long long ni = inHi - i0 + 1, nj = outHi - j0 + 1;
    std::vector<double> d2(static_cast<std::size_t>(ni * nj));
    for (long long a = 0; a < ni; ++a) {
        const std::vector<double>& pa = profiles[static_cast<std::size_t>(i0 + a)];
        for (long long b = 0; b < nj; ++b) {
            const std::vector<double>& pb = profiles[static_cast<std::size_t>(j0 + b)];
            double s = 0.0;
            for (std::size_t q = 0; q < Q; ++q)
                s += (pa[q] - pb[q]) * (pa[q] - pb[q]);
            d2[static_cast<std::size_t>(a * nj + b)] = Q > 0 ? s / static_cast<double>(Q) : 0.0;
        }
    }
    auto D2 = [&](long long i, long long j) {
        return d2[static_cast<std::size_t>((i - i0) * nj + (j - j0))];
    };
    LoopPoints best;
    double bestCost = std::numeric_limits<double>::infinity();
    long long bestP = -1;
    for (long long in = inLo; in <= inHi; ++in) {
        for (long long out = std::max(outLo, in + 2 * L + 1); out <= outHi; ++out) {
            double c = 0.0;
            for (long long k = 0; k <= L; ++k)
                c += D2(in - k, out - k); // the seam and the cross-fade pairs
            c /= static_cast<double>(L + 1);
            const long long P = out - in;
            if (c < bestCost || (c == bestCost && P > bestP)) {
                bestCost = c;
                bestP = P;
                best.in = first + static_cast<std::uint32_t>(in);
                best.out = first + static_cast<std::uint32_t>(out);
            }
        }
    }
    double mean = 0.0;
    for (double v : d2)
        mean += std::sqrt(v);
    best.crossfade = crossfade;
    best.residual = std::sqrt(bestCost);
    best.typicalDifference = d2.empty() ? 0.0 : mean / static_cast<double>(d2.size());
    return best;
}

TimelinePlan planTimeline(const cache::Header& header, std::size_t frameCount,
                          const ReplayParams& params,
                          const std::function<cache::Frame(std::uint32_t)>& readFrame) {
    params.validate();
    TimelinePlan plan;
    plan.record = bakeRecord(header);
    plan.frameTime = header.frameTime();
    if (!(plan.frameTime > 0.0) || !std::isfinite(plan.frameTime)) {
        throw std::invalid_argument(
            fmt::format("cache frame time dt * frame_interval = {} * {} is not positive", header.dt,
                        header.frameInterval));
    }
    if (frameCount == 0 || frameCount > 0x7fffffffu)
        throw std::invalid_argument(
            fmt::format("cache has {} frames; need 1 .. 2^31 - 1", frameCount));
    plan.sliceSpreadSeconds = 2.0 * params.fluctuation * params.timeUnitSeconds;
    const bool steady = params.steadyWindow && plan.record.recorded;
    const double endSeconds = static_cast<double>(frameCount - 1) * plan.frameTime;
    std::size_t first = 0;
    if (steady) {
        first = static_cast<std::size_t>(
            std::ceil(plan.record.steadyStartSeconds / plan.frameTime - 1e-9));
        if (first >= frameCount) {
            throw std::invalid_argument(fmt::format(
                "the bake ends at t = {:.2f} s, before its flow is steady (t = {:.2f} s: {}): "
                "bake at least {:.1f} s longer (solver.end_time >= {:.1f} s), or replay every "
                "frame with --window all",
                endSeconds, plan.record.steadyStartSeconds, plan.record.steadyReason,
                plan.record.steadyStartSeconds + plan.sliceSpreadSeconds - endSeconds,
                plan.record.steadyStartSeconds + plan.sliceSpreadSeconds));
        }
    }
    const std::size_t count = frameCount - first;
    const double windowSeconds = static_cast<double>(count) * plan.frameTime;
    if (steady && windowSeconds < plan.sliceSpreadSeconds) {
        throw std::invalid_argument(fmt::format(
            "the steady window holds {:.2f} s (t = {:.2f} .. {:.2f} s; steady from {:.2f} s: {}), "
            "shorter than the slice spread 2 F x time unit = 2 x {} x {} s = {:.2f} s: bake at "
            "least {:.2f} s longer (solver.end_time >= {:.2f} s), lower -F, or replay every frame "
            "with --window all",
            windowSeconds, static_cast<double>(first) * plan.frameTime, endSeconds,
            plan.record.steadyStartSeconds, plan.record.steadyReason, params.fluctuation,
            params.timeUnitSeconds, plan.sliceSpreadSeconds,
            plan.sliceSpreadSeconds - windowSeconds,
            endSeconds + plan.sliceSpreadSeconds - windowSeconds));
    }
    plan.windowFirst = static_cast<std::uint32_t>(first);
    plan.windowLast = static_cast<std::uint32_t>(frameCount - 1);
    if (params.policy != FramePolicy::Seamless || count < 4) {
        const FramePolicy p =
            params.policy == FramePolicy::Seamless ? FramePolicy::Loop : params.policy;
        plan.timeline = Timeline::range(plan.windowFirst, static_cast<std::uint32_t>(count), p);
        return plan;
    }

    // Seamless: the envelope of every window frame at 256 points over the grid's x range.
    const auto t0 = std::chrono::steady_clock::now();
    const Grid grid = makeGrid(header, params);
    constexpr int kSamples = 256;
    const double step = grid.dx * grid.cellsX / kSamples;
    const int L = std::min(static_cast<int>(std::lround(params.crossfadeSeconds / plan.frameTime)),
                           static_cast<int>(count / 8));
    const LoopSearch search = loopSearch(count, L);
    std::vector<std::vector<double>> profiles(count); // only the frames the search compares
    const double binWidth = envelopeBinWidth(header, grid);
    for (std::size_t i = 0; i < count; ++i) {
        if (!search.reads(static_cast<long long>(i)))
            continue;
        profiles[i] = sampleEnvelope(
            SurfaceEnvelope(readFrame(static_cast<std::uint32_t>(first + i)), binWidth), grid.x0,
            step, kSamples);
        if (profiles[i].empty()) // no surface particle: the empty-frame height
            profiles[i].assign(kSamples, header.domain.yMin);
    }
    plan.timeline = Timeline::seamless(findLoop(profiles, plan.windowFirst, L));
    plan.searchMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return plan;
}

nlohmann::json toJson(const TimelinePlan& plan) {
    nlohmann::json loop = nullptr;
    if (const auto& l = plan.timeline.loop()) {
        loop = {{"in_frame", l->in},
                {"out_frame", l->out},
                {"in_s", l->in * plan.frameTime},
                {"out_s", l->out * plan.frameTime},
                {"loop_seconds", (l->out - l->in) * plan.frameTime},
                {"crossfade_frames", l->crossfade},
                {"residual_m", l->residual},
                {"typical_difference_m", l->typicalDifference}};
    }
    return {{"policy", toString(plan.timeline.policy())},
            {"window",
             {{"first_frame", plan.windowFirst},
              {"last_frame", plan.windowLast},
              {"start_s", plan.windowFirst * plan.frameTime},
              {"end_s", plan.windowLast * plan.frameTime},
              {"recorded", plan.record.recorded},
              {"steady_start_s", plan.record.steadyStartSeconds},
              {"steady_reason", plan.record.steadyReason}}},
            {"entries", plan.timeline.size()},
            {"slice_spread_s", plan.sliceSpreadSeconds},
            {"loop", loop}};
}

} // namespace swell::runtime
