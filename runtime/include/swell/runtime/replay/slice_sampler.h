#pragma once
// Slice sampling, eq. (5)-(6) (Sec. 4.1), with the inserted half slices of Sec. 4.2: which
// cache frame each slice shows at animation time tau. The CPU side of slice_lookup.comp.

#include "swell/runtime/replay/fbm_noise.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/timeline.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace swell::runtime {

/// What slice j shows at one animation time: (1 - weight) x entry `first` + weight x entry
/// `second` (column profiles); weight 0 with TimeSampling::Nearest or on a stored frame.
struct SliceBlend {
    std::size_t first = 0;  ///< timeline entry at floor(s) (Nearest: the nearest entry)
    std::size_t second = 0; ///< timeline entry at floor(s) + 1 (== first when weight == 0)
    double weight = 0.0;    ///< fraction of s = (tau + F N) A past floor(s), in [0, 1)
};

class SliceSampler {
public:
    /// Builds the noise (none when F = 0). The slices show `timeline`'s entries (timeline.h),
    /// `A` cache frames per animation time unit. Throws std::invalid_argument on bad parameters.
    SliceSampler(const ReplayParams& params, Timeline timeline, double A);
    /// Every one of `frameCount` cache frames in order: Timeline::range(0, frameCount,
    /// params.policy) (the seamless policy needs planTimeline: std::invalid_argument).
    SliceSampler(const ReplayParams& params, std::size_t frameCount, double A);

    /// Timeline entry of slice j (0 .. 2K - 2) at animation time tau (eq. 5):
    ///   s_j = floor((tau + F N(tau, j/2)) A + 1/2), then the timeline's policy.
    /// N is linear in tau between noise samples (period T); an inserted slice (odd j) takes
    /// the mean of its neighbours' noise, i.e. N at k + 1/2. Throws std::invalid_argument
    /// when |tau| is so large that (|tau| + 1) A leaves the 32-bit frame range.
    std::size_t entry(double tau, int j) const;
    /// The two timeline entries around slice j's continuous frame number s = (tau + F N) A
    /// and the fraction between them (TimeSampling::Linear); with Nearest, entry(tau, j) with
    /// weight 0. A fraction within 1e-9 of a stored frame snaps to it. shown() of the heavier
    /// entry is frame(tau, j) in both.
    SliceBlend blend(double tau, int j) const;
    /// entry(tau, j) for every slice.
    std::vector<std::size_t> entries(double tau) const;
    /// The cache frame slice j shows (its entry's TimelineEntry::shown()).
    std::uint32_t frame(double tau, int j) const;
    /// frame(tau, j) for every slice.
    std::vector<std::uint32_t> frames(double tau) const;
    /// Every cache frame some slice shows or blends at some tau of `taus`: sorted, unique. A
    /// replay needs only these decoded.
    std::vector<std::uint32_t> framesUsed(std::span<const double> taus) const;
    /// N(tau, j/2) as used by frame() (0 when F = 0).
    double noiseAt(double tau, int j) const;

    int sliceCount() const { return 2 * m_K - 1; }
    const Timeline& timeline() const { return m_timeline; }
    double A() const { return m_A; }
    double fluctuation() const { return m_F; }
    TimeSampling timeSampling() const { return m_sampling; }
    FramePolicy policy() const { return m_timeline.policy(); }
    /// The noise, or null when F = 0 (none is built).
    const FbmNoise* noise() const { return m_noise ? &*m_noise : nullptr; }

private:
    int m_K;
    Timeline m_timeline;
    double m_A;
    double m_F;
    TimeSampling m_sampling;
    std::optional<FbmNoise> m_noise;
};

} // namespace swell::runtime
