#pragma once
// Whirlpool (Sec. 4.5): the slices of eq. (5)-(6) bent into logarithmic spirals
//     x(t) = a e^(b t) cos t,  z(t) = a e^(b t) sin t,  t in [0, 2 pi],
// placed radially around the centre and rotating with animation time.
//
// Definitions (docs/runtime.md, "Whirlpool"), in metres unless said:
//  * Centre C = (x0 + N dx / 2, extentZ / 2); a = innerRadiusCells dx; b = growth (per radian);
//    outer radius R = a e^(2 pi b). Defaults a = 15 dx, b = 25 / 128: R = 3.41 a = 51.2 dx,
//    inside the 64-cell half width of the paper's 128 x 128 mesh.
//  * The J = 2K - 1 slices (real and inserted, Sec. 4.2) are spirals with start angles
//    phi_j = 2 pi j / J + spin(tau), spin(tau) = 2 pi turnsPerTimeUnit tau (radial sampling:
//    evenly around the centre, so neighbouring spirals are closest, and the noise's slice
//    axis most visible, near the centre). Slice j is the curve r = a e^(b t), angle phi_j + t.
//  * The cache's x runs along each spiral: t = 2 pi u / N at column coordinate u (cells), so
//    the inner end t = 0 shows the cache's xMin and the outer end t = 2 pi its xMax.
//  * Cell centre P at polar (r, theta) about C (theta from +x towards +z):
//    t = ln(r / a) / b for r > a, else 0; u = N min(t, 2 pi) / (2 pi);
//    s = (theta - t - spin(tau)) J / (2 pi) mod J, in [0, J).
//  * The spirals as a function of s: f(s) = sum_j hat(s - j) p_j(u), hat(x) = max(0, 1 - |x|)
//    (linear between the two nearest spirals), p_j(u) slice j's eq. (7) profile
//    (CpuReconstruction::profile: the Gaussian mean of the slice's particles around the column
//    centre, or the fallback; with TimeSampling::Linear the blend of the two stored frames
//    around its frame number) linear between column centres u = k + 1/2 and constant beyond
//    the first and last.
//  * Footprint filter: the two cells (c = 2 max(dx, dz)) that the surface's bilinear
//    interpolation spans cover |grad s| c slices, |grad s| = J sqrt(1 + 1 / b^2) / (2 pi r)
//    (the angle's and the spiral parameter's share; used in the eye too, where it
//    over-filters on purpose), and |grad u| c columns of the profile, |grad u| =
//    N / (2 pi b r) in the band a < r < R (0 beyond R). In the eye the profile window widens
//    from its width W_a at r = a to the whole profile at the centre: max(W_a, N (1 - r/a)).
//    The cell's height is the box mean of f over w = clamp(|grad s| c, 1, J) slices centred
//    on s and wu = clamp(|grad u| c, 1, N) columns centred on u clamped into
//    [wu / 2, N - wu / 2] (so the window stays on the profile and moves continuously):
//      sum_j [H(s + w/2 - j) - H(s - w/2 - j)] / w  x  (1 / wu) integral of p_j over the box,
//    H(x) the integral of the hat to x, so that a cell that spans several spirals or several
//    profile columns shows their mean, not one of them (point sampling there aliases the
//    slices' frame noise and the profile's short waves into single-cell needles), and the
//    eye's centre shows the mean of every spiral over its whole length (steady: the tank's
//    water volume) instead of the wave maker's end of each. The profile's integral uses
//    C_j(k) = sum_{i < k} (p_j(i) + p_j(i + 1)) / 2 at column centres.
//  * Eye funnel: minus the surface of a Rankine vortex of depth D at the
//    centre (WhirlpoolParams::eyeDepth), d(r) = D (1 - r^2 / (2 a^2)) for r <= a, D a^2 / (2 r^2)
//    (1 - smoothstep(a, R, r)) for a < r < R (value and slope continuous at a), 0 beyond R.
//  * Outside the spiral band a <= r <= R: the eye r < a shows the inner ends (t = 0, u = 0) of
//    the spirals through the cell's angle (radial there, filtered as above); beyond R (the mesh's
//    corners with the defaults) the spirals keep winding, r = a e^(b t) with t > 2 pi, and show
//    their outer end's profile (u = N). The field is continuous at r = a and r = R, with no hole
//    and no NaN. The slice axis wraps around (j = J - 1 neighbours j = 0; the noise is periodic in
//    k).

#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/gpu_replay.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/height_output.h"
#include "swell/runtime/replay/slice_sampler.h"

#include <memory>
#include <vector>

namespace swell::runtime {

/// Where a cell lies on the spiral set at spin 0.
struct SpiralPoint {
    double t = 0.0;       ///< spiral parameter ln(r / a) / b, 0 in the eye (> 2 pi beyond R)
    double u = 0.0;       ///< column coordinate along the profile, N t / (2 pi), in [0, N]
    double s = 0.0;       ///< slice coordinate at spin 0, (theta - t) J / (2 pi) mod J, in [0, J)
    double uWidth = 1.0;  ///< footprint filter width along the profile, columns, in [1, N]
    double uCentre = 0.5; ///< centre of that window, u clamped into [uWidth / 2, N - uWidth / 2]
    double width = 1.0;   ///< footprint filter width w across the spirals, slices, in [1, J]
    double dip = 0.0;     ///< eye funnel depth d(r) subtracted from the height, metres
};

/// Weight of spiral j (an integer offset x = j - s from the cell's slice coordinate) in the
/// box mean of width w of the linear interpolant: [H(w/2 - x) - H(-w/2 - x)] / w.
double footprintWeight(double x, double w);

class SpiralGeometry {
public:
    /// Throws std::invalid_argument on bad parameters.
    SpiralGeometry(const Grid& grid, const WhirlpoolParams& params);

    /// The point of cell (n, m) (definitions above), in double precision.
    SpiralPoint at(int n, int m) const;
    /// spin(tau) in slice units, wrapped into [0, J).
    double spinSlices(double tau) const;

    double centreX() const { return m_cx; }    ///< metres
    double centreZ() const { return m_cz; }    ///< metres
    double innerRadius() const { return m_a; } ///< a, metres
    double outerRadius() const;                ///< R = a e^(2 pi b), metres
    int sliceCount() const { return m_J; }

private:
    Grid m_grid;
    WhirlpoolParams m_params;
    int m_J;
    double m_cx;
    double m_cz;
    double m_a;
};

/// Double-precision reference of the whirlpool, straight from the definitions.
class CpuWhirlpool {
public:
    /// `frames` and `sampler` must outlive it.
    CpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                 const WhirlpoolParams& whirlpool, const SliceSampler& sampler);
    HeightField heights(double tau) const;
    const SpiralGeometry& geometry() const { return m_geometry; }

private:
    const SliceSampler& m_sampler;
    CpuReconstruction m_profiles;
    SpiralGeometry m_geometry;
};

/// The whirlpool on the GPU: GpuReplay's column pass (once, turned into per-frame profiles
/// once) and slice lookup (per frame), then spiral_prefix.comp (the spirals' integrals, double)
/// and spiral_mapping.comp (each cell's footprint box mean from four of them, O(1) per cell)
/// instead of the surging reconstruction (which it never runs). CpuWhirlpool sums the
/// footprint's spirals one by one, so the comparison also checks the integrals' algebra.
class GpuWhirlpool {
public:
    GpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                 const WhirlpoolParams& whirlpool, const SliceSampler& sampler);

    void update(double tau);
    void setTiming(bool on) { m_timing = on; }
    /// Slice lookup and spiral mapping of the last timed update().
    StageTimes stageTimes() const;

    /// SSBO of N x M floats, [m * N + n] (GpuReplay's layout).
    GlName heightBuffer() const { return m_out.buffer(); }
    GlName heightTexture() { return m_out.texture(); }
    HeightField readHeights() const { return m_out.read(); }

    GpuReplay& slices() { return m_replay; }
    const GpuReplay& slices() const { return m_replay; }
    const Grid& grid() const { return m_replay.grid(); }
    const SpiralGeometry& geometry() const { return m_geometry; }
    std::size_t uploadedBytes() const { return m_uploadedBytes; }
    /// The slice set: the one GpuReplay whose columns the spirals map.
    std::vector<const GpuReplay*> sliceSets() const { return {&m_replay}; }

private:
    GpuReplay m_replay;
    SpiralGeometry m_geometry;
    HeightOutput m_out;
    GlProgram m_prefix;  ///< spiral_prefix.comp
    GlProgram m_mapping; ///< spiral_mapping.comp
    GlBuffer m_cells;    ///< per cell (v, wu, s at spin 0, w, funnel depth)
    GlBuffer m_profiles; ///< per held frame and column (p(k), p(min(k + 1, N - 1)), C(k))
    GlBuffer m_along;    ///< per frame, (C, p) of each spiral (spiral_prefix.comp)
    GlBuffer m_across;   ///< per frame, their integrals across the spirals (T, P)
    int m_spinLocation = -1;
    bool m_timing = false;
    bool m_timed = false;
    std::size_t m_uploadedBytes = 0;
    GlQuery m_queries[3];
};

} // namespace swell::runtime
