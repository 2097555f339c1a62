#include "swell/runtime/mode_replay.h"

#include <stdexcept>

namespace swell::runtime {
namespace {

void checkSets(const ModeParams& mode, std::span<const SliceSampler> samplers) {
    mode.validate();
    if (samplers.size() != static_cast<std::size_t>(mode.sliceSets()))
        throw std::logic_error("mode replay: one slice sampler per slice set (makeSamplers)");
}

} // namespace

ModeReplay::ModeReplay(const FrameSet& frames, const ReplayParams& params, const ModeParams& mode,
                       std::span<const SliceSampler> samplers)
    : m_mode(mode.mode) {
    checkSets(mode, samplers);
    switch (mode.mode) {
    case ReplayMode::Surging:
        m_surging = std::make_unique<GpuReplay>(frames, params, samplers[0]);
        break;
    case ReplayMode::Ripple:
        m_ripple = std::make_unique<GpuRipple>(frames, params, mode.ripple, samplers);
        break;
    case ReplayMode::Whirlpool:
        m_whirlpool = std::make_unique<GpuWhirlpool>(frames, params, mode.whirlpool, samplers[0]);
        break;
    }
}

void ModeReplay::update(double tau) {
    if (m_surging)
        m_surging->update(tau);
    else if (m_ripple)
        m_ripple->update(tau);
    else
        m_whirlpool->update(tau);
}

void ModeReplay::finish() const {
    const GpuReplay& any = m_surging  ? *m_surging
                           : m_ripple ? m_ripple->direction(0)
                                      : m_whirlpool->slices();
    any.finish();
}

void ModeReplay::setTiming(bool on) {
    if (m_surging)
        m_surging->setTiming(on);
    else if (m_ripple)
        m_ripple->setTiming(on);
    else
        m_whirlpool->setTiming(on);
}

ModeStageTimes ModeReplay::stageTimes() const {
    ModeStageTimes t;
    if (m_surging) {
        const StageTimes s = m_surging->stageTimes();
        t.sliceLookupMs = s.sliceLookupMs;
        t.reconstructMs = s.reconstructMs;
    } else if (m_ripple) {
        const RippleStageTimes s = m_ripple->stageTimes();
        t.sliceLookupMs = s.sliceLookupMs;
        t.reconstructMs = s.reconstructMs;
        t.synthesisMs = s.synthesisMs;
    } else {
        const WhirlpoolStageTimes s = m_whirlpool->stageTimes();
        t.sliceLookupMs = s.sliceLookupMs;
        t.spiralMs = s.spiralMs;
    }
    return t;
}

double ModeReplay::columnPassMs() const {
    if (m_surging)
        return m_surging->columnPassMs();
    if (m_whirlpool)
        return m_whirlpool->slices().columnPassMs();
    double sum = 0.0;
    for (int d = 0; d < m_ripple->directions(); ++d)
        sum += m_ripple->direction(d).columnPassMs();
    return sum;
}

GlName ModeReplay::heightBuffer() const {
    return m_surging  ? m_surging->heightBuffer()
           : m_ripple ? m_ripple->heightBuffer()
                      : m_whirlpool->heightBuffer();
}

GlName ModeReplay::heightTexture() {
    return m_surging  ? m_surging->heightTexture()
           : m_ripple ? m_ripple->heightTexture()
                      : m_whirlpool->heightTexture();
}

HeightField ModeReplay::readHeights() const {
    return m_surging  ? m_surging->readHeights()
           : m_ripple ? m_ripple->readHeights()
                      : m_whirlpool->readHeights();
}

std::vector<std::vector<std::uint32_t>> ModeReplay::readSliceFrames() const {
    if (m_surging)
        return {m_surging->readSliceFrames()};
    if (m_whirlpool)
        return {m_whirlpool->slices().readSliceFrames()};
    std::vector<std::vector<std::uint32_t>> out;
    for (int d = 0; d < m_ripple->directions(); ++d)
        out.push_back(m_ripple->direction(d).readSliceFrames());
    return out;
}

const Grid& ModeReplay::grid() const {
    return m_surging ? m_surging->grid() : m_ripple ? m_ripple->grid() : m_whirlpool->grid();
}

std::size_t ModeReplay::uploadedBytes() const {
    return m_surging  ? m_surging->uploadedBytes()
           : m_ripple ? m_ripple->uploadedBytes()
                      : m_whirlpool->uploadedBytes();
}

CpuModeReference::CpuModeReference(const FrameSet& frames, const ReplayParams& params,
                                   const ModeParams& mode, std::span<const SliceSampler> samplers) {
    checkSets(mode, samplers);
    switch (mode.mode) {
    case ReplayMode::Surging:
        m_surging = std::make_unique<CpuReconstruction>(frames, params, samplers[0]);
        break;
    case ReplayMode::Ripple:
        m_ripple = std::make_unique<CpuRipple>(frames, params, mode.ripple, samplers);
        break;
    case ReplayMode::Whirlpool:
        m_whirlpool = std::make_unique<CpuWhirlpool>(frames, params, mode.whirlpool, samplers[0]);
        break;
    }
}

HeightField CpuModeReference::heights(double tau) const {
    if (m_surging)
        return m_surging->heights(tau);
    if (m_ripple)
        return m_ripple->heights(tau);
    return m_whirlpool->heights(tau);
}

} // namespace swell::runtime
