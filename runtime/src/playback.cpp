#include "swell/runtime/playback.h"

#include "swell/runtime/modes/mode_splashes.h"
#include "swell/runtime/parallel_chunks.h"
#include "swell/runtime/replay/bake_record.h"
#include "swell/runtime/replay/height_sampling.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

ReplayParams playbackDefaults(ReplayMode mode) {
    ReplayParams p = paperDefaults(mode);
    p.reconstruction = Reconstruction::Envelope;
    p.policy = FramePolicy::Seamless;
    return p;
}

int autoCells(const cache::Header& header, const ReplayParams& params) {
    const BakeRecord record = bakeRecord(header);
    if (!(record.particleSpacing > 0.0))
        return 256;
    ReplayParams p = params;
    p.cellsX = p.cellsZ = 1;
    const Grid g = makeGrid(header, p); // one cell: dx is the x range the grid spans
    return std::clamp(static_cast<int>(std::lround(g.dx / record.particleSpacing)), 16, 4096);
}

std::vector<std::uint32_t> timelineFrames(const Timeline& timeline) {
    std::vector<std::uint32_t> ids;
    ids.reserve(2 * timeline.size());
    for (const TimelineEntry& e : timeline.entries()) {
        ids.push_back(e.a);
        if (e.blended())
            ids.push_back(e.b);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

FrameSet readFrames(const cache::Reader& reader, std::vector<std::uint32_t> ids) {
    FrameSet set;
    set.header = reader.header();
    set.frameCount = reader.frameCount();
    set.ids = std::move(ids);
    // Decoded on every core (Reader::readFrame is safe to call concurrently); a damaged frame
    // is reported as in a serial read: the first one, in cache order.
    set.frames.resize(set.ids.size());
    forEachChunk(set.ids.size(), chunkCount(set.ids.size(), 64),
                 [&](std::size_t, std::size_t begin, std::size_t end) {
                     for (std::size_t i = begin; i < end; ++i)
                         set.frames[i] = reader.readFrame(set.ids[i]);
                 });
    return set;
}

namespace {

PlaybackConfig resolved(const cache::Reader& reader, PlaybackConfig c) {
    if (c.params.cellsX <= 0 || c.params.cellsZ <= 0)
        c.params.cellsX = c.params.cellsZ = autoCells(reader.header(), c.params);
    c.params.validate();
    c.mode.validate();
    c.splash.validate();
    return c;
}

TimelinePlan planOf(const cache::Reader& reader, const ReplayParams& params) {
    try {
        return planTimeline(reader.header(), reader.frameCount(), params,
                            [&](std::uint32_t id) { return reader.readFrame(id); });
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format("{}: {}", reader.path().string(), e.what()));
    }
}

/// The frames the timeline can show, once the replay holding them is known to fit the budget.
std::vector<std::uint32_t> budgeted(const cache::Reader& reader, const PlaybackConfig& config,
                                    const TimelinePlan& plan, std::size_t sliceSets) {
    std::vector<std::uint32_t> ids = timelineFrames(plan.timeline);
    checkMemoryBudget(
        estimateReplayMemory(reader, ids, config.params, sliceSets, plan.timeline),
        budgetBytes(config.memoryBudgetGiB, "memory_budget_gib"),
        fmt::format("{}: a replay holding every frame of its timeline", reader.path().string()),
        "memory_budget_gib", "raise it, lower the mesh, or replay a shorter cache");
    return ids;
}

} // namespace

PlaybackConfig playbackConfig(const PlaybackChoice& choice, std::string_view where) {
    PlaybackConfig config;
    config.params = playbackDefaults(choice.mode);
    nlohmann::json modeJson = {{"mode", toString(choice.mode)}};
    for (const auto& [key, value] : choice.named.items()) {
        if (key == "params") {
            for (const char* own : {"cells_x", "cells_z", "slices", "fluctuation", "seed"}) {
                if (value.is_object() && value.contains(own))
                    throw std::invalid_argument(
                        fmt::format("set {} in {}, not in params", own, where));
            }
            config.params = replayParamsFromJson(value, config.params);
        } else if (key == "ripple" || key == "whirlpool") {
            modeJson[key] = value;
        } else if (key == "splash") {
            config.splash = splashParamsFromJson(value);
        } else if (key == "memory_budget_gib") {
            if (!value.is_number())
                throw std::invalid_argument("memory_budget_gib: a number of GiB");
            config.memoryBudgetGiB = value.get<double>();
            (void)budgetBytes(config.memoryBudgetGiB, "memory_budget_gib");
        } else {
            throw std::invalid_argument(fmt::format(
                "unknown key {} (params, ripple, whirlpool, splash, memory_budget_gib)", key));
        }
    }
    config.mode = modeParamsFromJson(modeJson);
    if (choice.cellsX < 0 || choice.cellsZ < 0 || (choice.cellsX == 0) != (choice.cellsZ == 0))
        throw std::invalid_argument(
            fmt::format("cells_x, cells_z: both > 0, or both 0 for auto; got {} x {}",
                        choice.cellsX, choice.cellsZ));
    config.params.cellsX = choice.cellsX;
    config.params.cellsZ = choice.cellsZ;
    if (choice.slices)
        config.params.slices = *choice.slices;
    if (choice.fluctuation)
        config.params.fluctuation = *choice.fluctuation;
    config.params.seed = choice.seed;
    return config;
}

Playback::Playback(const cache::Reader& reader, PlaybackConfig config)
    : m_config(resolved(reader, std::move(config))), m_plan(planOf(reader, m_config.params)),
      m_samplers(makeSamplers(m_config.params, m_config.mode, m_plan.timeline,
                              framesPerTimeUnit(reader.header(), m_config.params))),
      m_frames(readFrames(reader, budgeted(reader, m_config, m_plan, m_samplers.size()))),
      m_gpu(std::make_unique<ModeReplay>(m_frames, m_config.params, m_config.mode, m_samplers)),
      m_splashes(makeSplashSystems(m_frames, m_gpu->grid(), m_config.splash, m_config.params.seed,
                                   m_samplers.size())) {}

void Playback::advance(double seconds) {
    if (!std::isfinite(seconds))
        throw std::invalid_argument(fmt::format("time must be finite, got {}", seconds));
    m_gpu->update(seconds / m_config.params.timeUnitSeconds);
    m_seconds = seconds;
    m_advanced = true;
    m_heightsRead = false;
}

void Playback::ensureAdvanced() {
    if (!m_advanced)
        advance(0.0);
}

const HeightField& Playback::heights() {
    ensureAdvanced();
    if (!m_heightsRead) {
        m_heights = m_gpu->readHeights();
        m_heightsRead = true;
    }
    return m_heights;
}

void Playback::sample(std::span<const double> x, std::span<const double> z, std::span<double> out) {
    sampleHeights(heights(), grid(), x, z, out);
}

std::vector<SplashSprite> Playback::splashes() const {
    return modeSplashes(m_splashes, m_samplers, m_gpu->grid(), m_config.mode,
                        m_seconds / m_config.params.timeUnitSeconds, m_seconds);
}

PlaybackSession::PlaybackSession(const cache::Reader& reader, PlaybackConfig config,
                                 Context context) {
    if (context == Context::Own)
        m_context.emplace();
    else
        requireCurrentContext();
    m_playback = std::make_unique<Playback>(reader, std::move(config));
}

PlaybackSession::~PlaybackSession() {
    if (m_context)
        m_context->makeCurrent(); // the GL objects are deleted in their own context
    m_playback.reset();
}

Playback& PlaybackSession::playback() {
    if (m_context)
        m_context->makeCurrent();
    return *m_playback;
}

const Playback& PlaybackSession::playback() const {
    if (m_context)
        m_context->makeCurrent();
    return *m_playback;
}

} // namespace swell::runtime
