#include "swell/runtime/playback.h"

#include "swell/runtime/modes/mode_splashes.h"
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
    set.frames.reserve(set.ids.size());
    for (std::uint32_t id : set.ids)
        set.frames.push_back(reader.readFrame(id));
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

} // namespace

Playback::Playback(const cache::Reader& reader, PlaybackConfig config)
    : m_config(resolved(reader, std::move(config))), m_plan(planOf(reader, m_config.params)),
      m_A(framesPerTimeUnit(reader.header(), m_config.params)),
      m_samplers(makeSamplers(m_config.params, m_config.mode, m_plan.timeline, m_A)),
      m_frames(readFrames(reader, timelineFrames(m_plan.timeline))),
      m_gpu(std::make_unique<ModeReplay>(m_frames, m_config.params, m_config.mode, m_samplers)) {
    for (std::size_t d = 0; d < m_samplers.size(); ++d)
        m_splashes.emplace_back(m_frames, m_gpu->grid(), m_config.splash,
                                splashSeed(m_config.params.seed, static_cast<int>(d)));
}

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
    std::vector<SplashSprite> sprites;
    if (m_splashes.empty() || !m_splashes.front().active())
        return sprites;
    const double tau = m_seconds / m_config.params.timeUnitSeconds;
    for (std::size_t d = 0; d < m_splashes.size(); ++d) {
        std::vector<SplashSprite> more =
            m_splashes[d].sprites(m_samplers[d].frames(tau), m_seconds);
        placeSplashes(more, m_gpu->grid(), m_config.mode, static_cast<int>(d), tau);
        sprites.insert(sprites.end(), more.begin(), more.end());
    }
    return sprites;
}

} // namespace swell::runtime
