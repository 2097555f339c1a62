#pragma once
// Parameters of one replay (Sec. 4.1-4.3), with the paper's defaults, and the base-mesh
// geometry they imply.

#include "swell/cache/header.h"
#include "swell/runtime/fbm_noise.h"

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace swell::runtime {

/// What a slice shows when eq. (5) selects a frame outside the cache.
enum class FramePolicy {
    Clamp, ///< frames before the first show the first, frames after the last show the last
    Loop,  ///< frame indices wrap around modulo the frame count
};

/// Name of a policy as written in JSON and on the command line ("clamp", "loop").
std::string toString(FramePolicy policy);
/// Inverse of toString; throws std::invalid_argument naming "policy".
FramePolicy framePolicyFromString(const std::string& name);

/// Smallest Gaussian sigma of eq. (7), cells: below it float32 weights underflow in the window.
inline constexpr double kMinSigma = 0.25;

struct ReplayParams {
    int cellsX = 128;             ///< N: base-mesh cells along x, propagation (paper 128)
    int cellsZ = 128;             ///< M: base-mesh cells along z, transverse (paper 128)
    int slices = 256;             ///< K: real slices along z; K - 1 more are inserted (paper 256)
    double fluctuation = 0.3;     ///< F of eq. (5); 0 <= F <= 1 is eq. (6) (paper 0.3 surging)
    double timeUnitSeconds = 4.0; ///< simulated seconds per animation time unit: A = this / frame
                                  ///< time (paper: A = 4/dt steps)
    FramePolicy policy = FramePolicy::Loop; ///< frames outside the cache (see FramePolicy)
    double sigma = 2.0; ///< Gaussian sigma of eq. (7), in cells (paper 2.0), >= kMinSigma
    double extentZ = 0.0;   ///< transverse extent in metres; 0: cellsZ * dx (square cells)
    std::uint64_t seed = 1; ///< noise seed
    NoiseParams noise;      ///< T, beta, c, filter of N (paper: 16, 2.0, 128, low-pass)

    /// Throws std::invalid_argument naming the key, e.g. "fluctuation F = 1.5 breaks eq. (6)".
    void validate() const;
};

/// `params` as JSON, keys in snake_case and enums as names:
/// {"cells_x", "cells_z", "slices", "fluctuation", "time_unit_seconds", "policy", "sigma",
///  "extent_z", "seed", "noise": {"time_samples", "beta", "cutoff", "filter"}}.
nlohmann::json toJson(const ReplayParams& params);
/// Reads the keys present over the defaults, then validate(). An unknown key, a wrong type or
/// a bad value throws std::invalid_argument naming the key.
ReplayParams replayParamsFromJson(const nlohmann::json& j);

/// The base mesh I_XZ and the slices (Sec. 4.2). x spans the cache domain [xMin, xMax];
/// z spans [0, extentZ]. Cell (n, m) covers [x0 + n dx, x0 + (n+1) dx) x [m dz, (m+1) dz) and
/// its centre P is at cell coordinates (n + 1/2, m + 1/2). Slice j (j = 0 .. 2K - 2; even j
/// are the K real slices, odd j the inserted ones) lies at z_j = (j + 1) extentZ / (2K), i.e.
/// at (j + 1) M / (2K) in cell units.
struct Grid {
    int cellsX = 0;       ///< N
    int cellsZ = 0;       ///< M
    int slices = 0;       ///< K
    double x0 = 0.0;      ///< x of the mesh's first edge (the cache's xMin), metres
    double dx = 0.0;      ///< cell size along x, metres
    double dz = 0.0;      ///< cell size along z, metres
    double extentZ = 0.0; ///< M dz, metres

    int sliceCount() const { return 2 * slices - 1; }
    /// z of slice j in cell units.
    double sliceZCells(int j) const { return static_cast<double>(j + 1) * cellsZ / (2.0 * slices); }
};

/// The geometry of `params` over the cache's domain. Throws std::invalid_argument for an
/// empty domain.
Grid makeGrid(const cache::Header& header, const ReplayParams& params);

/// A of eq. (5) in cache frames per animation time unit: timeUnitSeconds / (dt frameInterval).
/// The paper's A = 4/dt simulation steps is timeUnitSeconds = 4.
double framesPerTimeUnit(const cache::Header& header, const ReplayParams& params);

} // namespace swell::runtime
