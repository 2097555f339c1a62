#pragma once
// The double-precision CPU reference of the replay: eq. (5)-(6) slice lookup and eq. (7)
// reconstruction, written directly from the equations (one 2D Gaussian per particle, no
// separable sums, no precomputed tables), so the GPU path can be tested against it.
//
// Definitions (shared with the GPU path; docs/runtime.md):
//  * Cut-off window [3 dx, 2 dz) of cell (n, m): the surface particles whose x bin
//    b = floor((x - xMin) / dx) is n - 1, n or n + 1 (3 dx, centred on P), of the slices j
//    with z_j - P_z in [-dz, dz) (2 dz, half-open), i.e. in integers
//    -2K <= (j + 1) M - (2m + 1) K < 2K. If no slice lies in that range (only when M > 2K),
//    the one nearest slice is used (ties: the lower j).
//  * eq. (7): h(P) = sum G h_l / sum G, G = exp(-((x - P_x)^2 + (z - P_z)^2) / (2 sigma^2)),
//    x, z in cell units, particle z = its slice's z.
//  * Fallback (no particle in the window, sum G = 0): per window slice, the plain mean
//    height of the particles in the nearest non-empty bins n - d, n + d (d >= 2, both when
//    both are non-empty; bins run -1 .. N), or the domain's yMin when the slice's frame has
//    no surface particle; the cell takes the G_z-weighted mean of those,
//    G_z = exp(-(z_j - P_z)^2 / (2 sigma^2)). Every cell is finite.
//  * Column sums: eq. (7) separates into per-slice column sums S = sum G_x h, W = sum G_x
//    (W = 0: S holds the fallback) and h = sum_j G_z S_j / sum_j G_z W_j. With
//    Reconstruction::Envelope a frame's column is (eta(P_x), 1), eta the frame's surface
//    envelope (surface_envelope.h), or (yMin, 0) for a frame without surface particles.
//  * Cross-fade (timeline.h): a blended entry's column is blendColumns of its two frames'.

#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"

#include <cstdint>
#include <vector>

namespace swell::runtime {

/// One column of one frame (or cross-fade): W > 0: the profile is S / W; W = 0: S is the
/// fallback height.
struct ColumnSum {
    double S = 0.0;
    double W = 0.0;
    double height() const { return W > 0.0 ? S / W : S; }
};

/// The cross-fade of two columns, alpha the weight of b: heights h = (1 - alpha) h_a +
/// alpha h_b and W = (1 - alpha) W_a + alpha W_b, stored as (h W, W), or (h, 0) when W = 0.
/// Continuous in alpha; alpha = 0 gives a's profile.
ColumnSum blendColumns(ColumnSum a, ColumnSum b, double alpha);

/// The slices j in the z window of row m (ascending), or the one nearest slice when the
/// window holds none (definition above).
std::vector<int> windowSlices(const Grid& grid, int m);

class CpuReconstruction {
public:
    /// Keeps references to `frames` and `sampler`, which must outlive it. Throws
    /// std::invalid_argument on bad parameters or frames.
    CpuReconstruction(const FrameSet& frames, const ReplayParams& params,
                      const SliceSampler& sampler);

    /// The height field at animation time tau. Throws std::invalid_argument if a selected
    /// frame is not in the frame set.
    HeightField heights(double tau) const;
    /// The column sums of cache frame `frame` at column n (P_x = n + 1/2): paper: S = sum G_x h
    /// and W = sum G_x over bins n - 1 .. n + 1 (G_z is one constant per slice), or (fallback,
    /// 0) when the window is empty; envelope: (eta(P_x), 1). Throws std::invalid_argument if
    /// the frame is not in the frame set.
    ColumnSum column(std::uint32_t frame, int n) const;
    /// The column of a timeline entry (blended when the entry is).
    ColumnSum column(const TimelineEntry& entry, int n) const;
    /// The profile one slice showing `entry` has at column n: column(entry, n).height(). The
    /// whirlpool's spiral profile.
    double profile(const TimelineEntry& entry, int n) const { return column(entry, n).height(); }
    const Grid& grid() const { return m_grid; }

private:
    struct BinnedFrame {
        std::vector<std::uint32_t> start; ///< N + 3 offsets: bins -1 .. N
        std::vector<double> u;            ///< x in cell units, sorted by bin
        std::vector<double> h;            ///< heights, same order
    };
    const BinnedFrame& binned(std::uint32_t frame) const;
    double fallback(const BinnedFrame& f, int n) const;

    const FrameSet& m_frames;
    const SliceSampler& m_sampler;
    ReplayParams m_params;
    Grid m_grid;
    std::vector<BinnedFrame> m_binned;           ///< per held frame (FrameSet order)
    std::vector<std::vector<double>> m_envelope; ///< Envelope: eta at each column, per held frame
    std::vector<std::vector<int>> m_rowSlices;   ///< slices in each row's z window
};

} // namespace swell::runtime
