#pragma once

namespace swell::bake {

/// MPS weight function (Koshizuka & Oka 1996; paper Sec. 3.1):
/// w(r) = re / r - 1 for 0 < r < re, 0 otherwise. r = 0 (coincident particles)
/// has no direction and is given weight 0; the collision model separates them.
inline double mpsWeight(double r, double re) {
    return (r > 0.0 && r < re) ? re / r - 1.0 : 0.0;
}

/// The standard constants of a kernel radius on a perfect square lattice.
struct LatticeConstants {
    double n0 = 0.0; ///< particle number density n0 = sum_j w(|r_j - r_i|) (dimensionless)
    double lambda =
        0.0; ///< Laplacian-model lambda = sum r^2 w / sum w (m^2), K&O 1996 Laplacian model
    /// Neighbour-distribution asymmetry |sum_j (r_j - r_i) w| / (n0 l0) of a particle on the
    /// flat top row of a half lattice (its upper neighbours missing); 0 inside a full lattice.
    /// The scale of the distribution free-surface test (mps_params.h, SurfaceTest).
    double flatSurfaceAsymmetry = 0.0;
};

/// n0 and lambda for a particle of a full 2D square lattice of spacing `spacing` (m)
/// with kernel radius `re` (m). Throws std::invalid_argument for spacing <= 0 or re <= 0.
LatticeConstants latticeConstants(double spacing, double re);

} // namespace swell::bake
