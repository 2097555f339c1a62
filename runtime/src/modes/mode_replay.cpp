#include "swell/runtime/modes/mode_replay.h"

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
        m_replay = std::make_unique<GpuReplay>(frames, params, samplers[0]);
        break;
    case ReplayMode::Ripple:
        m_replay = std::make_unique<GpuRipple>(frames, params, mode.ripple, samplers);
        break;
    case ReplayMode::Whirlpool:
        m_replay = std::make_unique<GpuWhirlpool>(frames, params, mode.whirlpool, samplers[0]);
        break;
    }
}

void ModeReplay::update(double tau) {
    visit([&](auto& r) { r.update(tau); });
}

void ModeReplay::finish() const {
    visit([](const auto& r) { r.sliceSets().front()->finish(); });
}

void ModeReplay::setTiming(bool on) {
    visit([&](auto& r) { r.setTiming(on); });
}

StageTimes ModeReplay::stageTimes() const {
    return visit([](const auto& r) { return r.stageTimes(); });
}

double ModeReplay::columnPassMs() const {
    double sum = 0.0;
    for (const GpuReplay* s : visit([](const auto& r) { return r.sliceSets(); }))
        sum += s->columnPassMs();
    return sum;
}

GlName ModeReplay::heightBuffer() const {
    return visit([](const auto& r) { return r.heightBuffer(); });
}

GlName ModeReplay::heightTexture() {
    return visit([](auto& r) { return r.heightTexture(); });
}

HeightField ModeReplay::readHeights() const {
    return visit([](const auto& r) { return r.readHeights(); });
}

std::vector<std::vector<std::uint32_t>> ModeReplay::readSliceFrames() const {
    std::vector<std::vector<std::uint32_t>> out;
    for (const GpuReplay* s : visit([](const auto& r) { return r.sliceSets(); }))
        out.push_back(s->readSliceFrames());
    return out;
}

const Grid& ModeReplay::grid() const {
    return visit([](const auto& r) -> const Grid& { return r.grid(); });
}

std::size_t ModeReplay::uploadedBytes() const {
    return visit([](const auto& r) { return r.uploadedBytes(); });
}

GpuRipple* ModeReplay::ripple() {
    auto* p = std::get_if<std::unique_ptr<GpuRipple>>(&m_replay);
    return p != nullptr ? p->get() : nullptr;
}

GpuWhirlpool* ModeReplay::whirlpool() {
    auto* p = std::get_if<std::unique_ptr<GpuWhirlpool>>(&m_replay);
    return p != nullptr ? p->get() : nullptr;
}

CpuModeReference::CpuModeReference(const FrameSet& frames, const ReplayParams& params,
                                   const ModeParams& mode, std::span<const SliceSampler> samplers) {
    checkSets(mode, samplers);
    switch (mode.mode) {
    case ReplayMode::Surging:
        m_reference = std::make_unique<CpuReconstruction>(frames, params, samplers[0]);
        break;
    case ReplayMode::Ripple:
        m_reference = std::make_unique<CpuRipple>(frames, params, mode.ripple, samplers);
        break;
    case ReplayMode::Whirlpool:
        m_reference = std::make_unique<CpuWhirlpool>(frames, params, mode.whirlpool, samplers[0]);
        break;
    }
}

HeightField CpuModeReference::heights(double tau) const {
    return std::visit([&](const auto& r) { return r->heights(tau); }, m_reference);
}

} // namespace swell::runtime
