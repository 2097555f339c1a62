#pragma once
// One interface over the three layouts (mode_params.h), for swell-play and renderers:
// ModeReplay on the GPU, CpuModeReference its double-precision reference. Every mode writes
// the same output: an SSBO of N x M floats, [m * N + n] = height in metres at the centre of
// cell (n, m), x = x0 + (n + 1/2) dx, z = (m + 1/2) dz, or the same as an R32F texture.

#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/modes/ripple.h"
#include "swell/runtime/modes/whirlpool.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/gpu_replay.h"

#include <memory>
#include <span>
#include <variant>
#include <vector>

namespace swell::runtime {

class ModeReplay {
public:
    /// `samplers`: makeSamplers(params, mode, ...) (not kept). Uploads the frames.
    ModeReplay(const FrameSet& frames, const ReplayParams& params, const ModeParams& mode,
               std::span<const SliceSampler> samplers);

    void update(double tau);
    void finish() const;
    void setTiming(bool on);
    StageTimes stageTimes() const;
    /// The one-off column pass(es), summed (ms).
    double columnPassMs() const;

    GlName heightBuffer() const;
    GlName heightTexture();
    HeightField readHeights() const;
    /// The frame of every slice of every slice set (readSliceFrames of each), blocks.
    std::vector<std::vector<std::uint32_t>> readSliceFrames() const;

    ReplayMode mode() const { return m_mode; }
    const Grid& grid() const;
    std::size_t uploadedBytes() const;
    /// The ripple, or null in another mode.
    GpuRipple* ripple();
    /// The whirlpool, or null in another mode.
    GpuWhirlpool* whirlpool();

private:
    /// Calls f on the mode's replay, whichever it is.
    template <class F> decltype(auto) visit(F&& f) const {
        return std::visit([&](const auto& p) -> decltype(auto) { return f(*p); }, m_replay);
    }
    template <class F> decltype(auto) visit(F&& f) {
        return std::visit([&](auto& p) -> decltype(auto) { return f(*p); }, m_replay);
    }

    ReplayMode m_mode;
    std::variant<std::unique_ptr<GpuReplay>, std::unique_ptr<GpuRipple>,
                 std::unique_ptr<GpuWhirlpool>>
        m_replay;
};

class CpuModeReference {
public:
    /// `frames` and `samplers` must outlive it.
    CpuModeReference(const FrameSet& frames, const ReplayParams& params, const ModeParams& mode,
                     std::span<const SliceSampler> samplers);
    HeightField heights(double tau) const;

private:
    std::variant<std::unique_ptr<CpuReconstruction>, std::unique_ptr<CpuRipple>,
                 std::unique_ptr<CpuWhirlpool>>
        m_reference;
};

} // namespace swell::runtime
