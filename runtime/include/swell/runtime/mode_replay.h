#pragma once
// One interface over the three layouts (replay_mode.h), for swell-play and renderers:
// ModeReplay on the GPU, CpuModeReference its double-precision reference. Every mode writes
// the same output: an SSBO of N x M floats, [m * N + n] = height in metres at the centre of
// cell (n, m), x = x0 + (n + 1/2) dx, z = (m + 1/2) dz, or the same as an R32F texture.

#include "swell/runtime/cpu_reconstruction.h"
#include "swell/runtime/gpu_reconstruction.h"
#include "swell/runtime/replay_mode.h"
#include "swell/runtime/ripple_synthesis.h"
#include "swell/runtime/spiral_slices.h"

#include <memory>
#include <span>
#include <vector>

namespace swell::runtime {

/// GPU time of each stage of the last timed update() (ms); stages a mode skips read 0.
struct ModeStageTimes {
    double sliceLookupMs = 0.0; ///< eq. (5)-(6), every slice set
    double reconstructMs = 0.0; ///< eq. (7) (surging, each ripple direction; not whirlpool)
    double synthesisMs = 0.0;   ///< eq. (8), ripple with a synthesis pass
    double spiralMs = 0.0;      ///< spiral mapping, whirlpool
};

class ModeReplay {
public:
    /// `samplers`: makeSamplers(params, mode, ...) (not kept). Uploads the frames.
    ModeReplay(const FrameSet& frames, const ReplayParams& params, const ModeParams& mode,
               std::span<const SliceSampler> samplers);

    void update(double tau);
    void finish() const;
    void setTiming(bool on);
    ModeStageTimes stageTimes() const;
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
    GpuRipple* ripple() { return m_ripple.get(); }
    /// The whirlpool, or null in another mode.
    GpuWhirlpool* whirlpool() { return m_whirlpool.get(); }

private:
    ReplayMode m_mode;
    std::unique_ptr<GpuReplay> m_surging;
    std::unique_ptr<GpuRipple> m_ripple;
    std::unique_ptr<GpuWhirlpool> m_whirlpool;
};

class CpuModeReference {
public:
    /// `frames` and `samplers` must outlive it.
    CpuModeReference(const FrameSet& frames, const ReplayParams& params, const ModeParams& mode,
                     std::span<const SliceSampler> samplers);
    HeightField heights(double tau) const;

private:
    std::unique_ptr<CpuReconstruction> m_surging;
    std::unique_ptr<CpuRipple> m_ripple;
    std::unique_ptr<CpuWhirlpool> m_whirlpool;
};

} // namespace swell::runtime
