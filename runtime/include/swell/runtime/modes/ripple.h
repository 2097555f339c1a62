#pragma once
// Ripple wave (Sec. 4.4, Algorithm 2b): D directions, each a surging replay (eq. 5-7) on its
// own slice set with its own noise, rotated about the mesh centre; eq. (8) synthesises the
// final height of every base-mesh cell as the weighted sum of the bilinearly interpolated
// heights of each direction.
//
// Definitions (docs/runtime.md, "Ripple"):
//  * Centre C = (x0 + N dx / 2, extentZ / 2), metres. Direction d (angle a_d) propagates along
//    (cos a_d, sin a_d) in (x, z): its height field is the surging field of its own slice set
//    (same N x M grid over the same cache domain), rotated by a_d about C.
//  * Cell centre P maps into direction d's own grid as q = R(-a_d) (P - C) + C, in its cell
//    coordinates u = (q_x - x0) / dx, v = q_z / dz.
//  * eq. (8) neighbours Q: the 2 x 2 cell centres around (u, v), bilinear. Along x (the
//    direction's propagation) clamped to its edge columns: fu = clamp(u - 1/2, 0, N - 1),
//    n0 = min(floor(fu), N - 2) (0 when N = 1), fx = fu - n0, n1 = min(n0 + 1, N - 1).
//    Along z (its transverse axis) periodic with period M: fv = (v - 1/2) mod M,
//    m0 = floor(fv), fz = fv - m0, m1 = (m0 + 1) mod M.
//  * Fallback for the cells a rotated grid does not cover (its corners leave the base mesh
//    for any angle that is not a multiple of 90 degrees): across the transverse edges the
//    direction's field repeats (the noise is periodic along the slice axis, so row M - 1 and
//    row 0 show neighbouring noise), beyond the ends of the cache's x range it continues its
//    edge column. So every direction contributes to every cell with its weight and the sum
//    has no seam, no hole and no NaN.
//  * Weights: eq. (8)'s omega_d (default equal) times an edge taper e that fades a direction
//    out where its own field ends along x inside the base mesh (there its clamped edge column
//    would meet the other directions in a straight crease):
//      e = f + (1 - f) S(min(u, N - u) + max(L - b, 0)),
//    S the smoothstep from 0 to L = kRippleEdgeMargin N cells, b the cell's distance to the
//    base mesh's nearest side in cells of dx (so a direction is not faded within L of the
//    mesh's own sides, and the unrotated direction never is), floor f = kRippleEdgeFloor;
//    the weights of a cell normalised to sum 1 over the directions.
//  * One direction at angle 0: the base cell is the direction's own cell; no synthesis pass.

#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/gpu_replay.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/height_output.h"
#include "swell/runtime/replay/slice_sampler.h"

#include <memory>
#include <span>
#include <vector>

namespace swell::runtime {

/// Edge taper of the ripple weights (definitions above): the share of a direction's cells, at
/// each end of its x range, over which its weight fades, and the weight left beyond its ends.
inline constexpr double kRippleEdgeMargin = 0.15;
inline constexpr double kRippleEdgeFloor = 0.01;
/// e at column coordinate u of a direction with N columns, for a cell `side` cells of dx from
/// the base mesh's nearest side.
double rippleEdgeWeight(double u, int N, double side);

/// Where one base cell reads one direction (definitions above).
struct RippleTap {
    int n0 = 0;          ///< lower column of the 2 x 2 neighbours in the direction's field
    int m0 = 0;          ///< lower row
    int n1 = 0;          ///< upper column (n0 + 1, or n0 when N = 1)
    int m1 = 0;          ///< upper row ((m0 + 1) mod M)
    double fx = 0.0;     ///< bilinear fraction along the direction's x
    double fz = 0.0;     ///< bilinear fraction along the direction's z
    double weight = 0.0; ///< eq. (8) weight omega_d e(u), normalised to sum 1 over the directions
    bool inside = false; ///< (u, v) lies inside the direction's own grid (no fallback used)
};

/// The taps of every cell and direction, [(m * N + n) * D + d], in double precision: the CPU
/// reference's eq. (8) neighbours. ripple_synthesis.comp computes the same mapping itself, in
/// float (it is continuous, so rounding moves a sample by ~1e-5 cells).
std::vector<RippleTap> rippleTaps(const Grid& grid, const RippleParams& ripple);

/// True when the synthesis is the identity (one direction at 0 degrees).
bool rippleIsIdentity(const RippleParams& ripple);

/// Double-precision reference: one CpuReconstruction per direction, then eq. (8).
class CpuRipple {
public:
    /// `samplers` (one per direction, see makeSamplers) and `frames` must outlive it.
    CpuRipple(const FrameSet& frames, const ReplayParams& params, const RippleParams& ripple,
              std::span<const SliceSampler> samplers);
    HeightField heights(double tau) const;

private:
    Grid m_grid;
    int m_D;
    std::vector<std::unique_ptr<CpuReconstruction>> m_dirs;
    std::vector<RippleTap> m_taps;
};

/// The ripple on the GPU: one GpuReplay per direction (each its own upload, column pass, slice
/// lookup and eq. 7 reconstruction), then the directions' buffers are copied into one and
/// ripple_synthesis.comp (eq. 8) writes heightBuffer().
class GpuRipple {
public:
    /// Uploads `frames` once per direction. `samplers`: one per direction (not kept).
    GpuRipple(const FrameSet& frames, const ReplayParams& params, const RippleParams& ripple,
              std::span<const SliceSampler> samplers);

    /// Every direction's two passes, then the synthesis pass (skipped for the identity).
    void update(double tau);
    void setTiming(bool on);
    /// Slice lookup and reconstruct summed over the directions, synthesis (0 without it).
    StageTimes stageTimes() const;
    /// False for one direction at 0 degrees: heightBuffer() is direction 0's own.
    bool synthesises() const { return !m_identity; }

    /// SSBO of N x M floats, [m * N + n]: the synthesised heights (GpuReplay's layout).
    GlName heightBuffer() const;
    /// The same as an R32F N x M texture (copied on the GPU when first asked after update()).
    GlName heightTexture();
    HeightField readHeights() const;

    int directions() const { return static_cast<int>(m_dirs.size()); }
    GpuReplay& direction(int d) { return *m_dirs[static_cast<std::size_t>(d)]; }
    const GpuReplay& direction(int d) const { return *m_dirs[static_cast<std::size_t>(d)]; }
    const Grid& grid() const { return m_dirs.front()->grid(); }
    std::size_t uploadedBytes() const { return m_uploadedBytes; }
    /// The slice sets: one GpuReplay per direction.
    std::vector<const GpuReplay*> sliceSets() const;

private:
    std::vector<std::unique_ptr<GpuReplay>> m_dirs;
    bool m_identity = false;
    bool m_timing = false;
    bool m_timed = false;
    std::size_t m_uploadedBytes = 0;
    GlProgram m_synthesis;
    GlBuffer m_dirHeights;     ///< D x N x M floats, direction d at [d N M + m N + n]
    GlBuffer m_directionTable; ///< per direction (cos a_d, sin a_d, omega_d, 0)
    std::unique_ptr<HeightOutput> m_out;
    GlQuery m_queries[2];
};

} // namespace swell::runtime
