#pragma once
// A stored frame's free surface, defined from its particles: the upper envelope of the surface
// particles. It is what the replay is measured against (fidelity.h), what the loop search
// compares (timeline.h) and, with Reconstruction::Envelope, the column profile of eq. (7).
//
// Definition (docs/runtime.md, "Fidelity"): the x axis is cut into bins of width w (the bake's
// particle spacing l0) at b = floor(x / w); in each bin the highest surface particle (ties: the
// smaller x) is an envelope point; eta(x) is the piecewise-linear curve through the points in
// order of x, constant beyond the first and the last. Splash particles are not part of it.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"
#include "swell/runtime/replay/replay_params.h"

#include <vector>

namespace swell::runtime {

class SurfaceEnvelope {
public:
    /// Throws std::invalid_argument when binWidth is not > 0.
    SurfaceEnvelope(const cache::Frame& frame, double binWidth);

    /// eta(x), metres; NaN when the frame has no surface particle.
    double at(double x) const;
    bool empty() const { return m_x.empty(); }
    /// x of the first and the last envelope point (where eta is not extrapolated).
    double xFirst() const { return m_x.front(); }
    double xLast() const { return m_x.back(); }
    const std::vector<double>& xs() const { return m_x; }

private:
    std::vector<double> m_x;
    std::vector<double> m_y;
};

/// Envelope bin width of a replay: the cache's recorded particle spacing l0 (bake_record.h),
/// or half the grid's cell width when the cache records none.
double envelopeBinWidth(const cache::Header& header, const Grid& grid);

/// eta at x0 + (i + 1/2) dx, i = 0 .. count - 1 (column centres); empty when the envelope is
/// (the frame has no surface particle).
std::vector<double> sampleEnvelope(const SurfaceEnvelope& envelope, double x0, double dx,
                                   int count);

} // namespace swell::runtime
