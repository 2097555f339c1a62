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
//    Height: the two nearest spirals j0 = floor(s), j1 = (j0 + 1) mod J, weights 1 - (s - j0)
//    and s - j0, each read at u from its frame's eq. (7) profile (CpuReconstruction::profile:
//    the Gaussian mean of the slice's particles around the column centre, or the fallback)
//    linearly between column centres: fu = clamp(u - 1/2, 0, N - 1), n0 = min(floor(fu), N - 2)
//    (0 when N = 1), weight fu - n0 for min(n0 + 1, N - 1).
//  * Outside the spiral band a <= r <= R: the eye r < a shows the inner ends (t = 0, u = 0) of
//    the spirals through the cell's angle (radial there); beyond R (the mesh's corners with
//    the defaults) the spirals keep winding, r = a e^(b t) with t > 2 pi, and show their outer
//    end's profile (u = N). The field is continuous at r = a and r = R, with no hole and no
//    NaN. The slice axis wraps around (j = J - 1 neighbours j = 0; the noise is periodic in k).

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
    double t = 0.0; ///< spiral parameter ln(r / a) / b, 0 in the eye (> 2 pi beyond R)
    double u = 0.0; ///< column coordinate along the profile, N t / (2 pi), in [0, N]
    double s = 0.0; ///< slice coordinate at spin 0, (theta - t) J / (2 pi) mod J, in [0, J)
};

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
/// once) and slice lookup (per frame), then spiral_mapping.comp instead of the surging
/// reconstruction (which it never runs).
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
    GlProgram m_mapping;
    GlBuffer m_cells;    ///< per cell (n0, beta, s at spin 0)
    GlBuffer m_profiles; ///< per held frame and column (p(n), p(min(n + 1, N - 1)))
    int m_spinLocation = -1;
    bool m_timing = false;
    bool m_timed = false;
    std::size_t m_uploadedBytes = 0;
    GlQuery m_queries[3];
};

} // namespace swell::runtime
