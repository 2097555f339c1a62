#pragma once
// Parameters of one replay (Sec. 4.1-4.3), with the paper's defaults, and the base-mesh
// geometry they imply.

#include "swell/cache/header.h"
#include "swell/runtime/replay/fbm_noise.h"

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace swell::runtime {

/// What a slice shows when eq. (5) selects a frame outside the cache.
/// What a slice shows when eq. (5) selects a frame before or after the replay's frames (the
/// steady window, timeline.h).
enum class FramePolicy {
    Clamp,    ///< frames before the first show the first, frames after the last show the last
    Loop,     ///< frame indices wrap around modulo the window's frame count (a jump at the seam)
    Seamless, ///< loop between the two most alike frames with a cross-fade (video textures)
};

/// Name of a policy as written in JSON and on the command line ("clamp", "loop", "seamless").
std::string toString(FramePolicy policy);
/// Inverse of toString; throws std::invalid_argument naming "policy".
FramePolicy framePolicyFromString(const std::string& name);

/// Which x range the base mesh's N cells span.
enum class ExtentX {
    Water,    ///< the water's x range recorded by the bake less the wave maker's zone
              ///< (bake_record.h, shownWaterX); the cache domain when the cache has no record
    Domain,   ///< the cache's whole domain (the solver's padded box)
    Explicit, ///< [ReplayParams::extentX0, extentX1]
};

/// How a frame's column profile (the x part of eq. (7)) is made from its surface particles.
enum class Reconstruction {
    /// The paper's eq. (7): the Gaussian-weighted mean of every surface particle in the [3 dx)
    /// window (with eq. (7)'s z Gaussian over the slices in [2 dz)).
    Paper,
    /// The frame's free surface, the upper envelope of its surface particles
    /// (surface_envelope.h), at the column centre; the slices are joined by eq. (7)'s z Gaussian
    /// over [2 dz) as in Paper.
    Envelope,
};

/// What a slice shows between two stored frames (eq. (5)'s frame number is continuous).
enum class TimeSampling {
    /// eq. (5) as the paper writes it: the nearest stored frame (halves up).
    Nearest,
    /// The column profiles of the two stored frames around s = (tau + F N) A, blended linearly
    /// by the fraction of s: two slices a fraction of a frame apart differ by that fraction.
    Linear,
};

std::string toString(TimeSampling sampling);
/// Inverse of toString; throws std::invalid_argument naming "time_sampling".
TimeSampling timeSamplingFromString(const std::string& name);

std::string toString(ExtentX extent);
std::string toString(Reconstruction reconstruction);
/// Inverse of toString; throws std::invalid_argument naming "reconstruction".
Reconstruction reconstructionFromString(const std::string& name);

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
    double sigma = 2.0;     ///< Gaussian sigma of eq. (7), in cells (paper 2.0), >= kMinSigma
    double extentZ = 0.0;   ///< transverse extent in metres; 0: cellsZ * dx (square cells)
    std::uint64_t seed = 1; ///< noise seed
    NoiseParams noise;      ///< T, beta, c, filter of N (paper: 16, 2.0, 128, low-pass)
    ExtentX extentX = ExtentX::Water; ///< x range of the base mesh (see ExtentX)
    double extentX0 = 0.0;            ///< with ExtentX::Explicit: first edge, metres
    double extentX1 = 0.0;            ///< with ExtentX::Explicit: last edge, metres (> extentX0)
    /// Column profiles (see Reconstruction). The library default is the paper's; swell-play's
    /// default is Envelope (docs/runtime.md, "Fidelity").
    Reconstruction reconstruction = Reconstruction::Paper;
    /// Only frames of the bake's steady window (bake_record.h) are replayed; false: every frame.
    bool steadyWindow = true;
    /// Frames between stored frames (see TimeSampling). The library default is the paper's;
    /// swell-play's default is Linear for surging and ripple.
    TimeSampling timeSampling = TimeSampling::Nearest;
    /// Length of the seamless loop's cross-fade (FramePolicy::Seamless), simulated seconds.
    double crossfadeSeconds = 0.4;

    /// Throws std::invalid_argument naming the key, e.g. "fluctuation F = 1.5 breaks eq. (6)".
    void validate() const;
};

/// `params` as JSON, keys in snake_case and enums as names:
/// {"cells_x", "cells_z", "slices", "fluctuation", "time_unit_seconds", "policy", "sigma",
///  "extent_z", "seed", "noise": {"time_samples", "beta", "cutoff", "filter"},
///  "extent_x": "water" | "domain" | [x0, x1], "reconstruction": "paper" | "envelope",
///  "window": "steady" | "all", "crossfade_seconds", "time_sampling": "nearest" | "linear"}.
nlohmann::json toJson(const ReplayParams& params);
/// Reads the keys present over the defaults, then validate(). An unknown key, a wrong type or
/// a bad value throws std::invalid_argument naming the key.
ReplayParams replayParamsFromJson(const nlohmann::json& j);
/// The same over `base` instead of the defaults.
ReplayParams replayParamsFromJson(const nlohmann::json& j, const ReplayParams& base);

/// The base mesh I_XZ and the slices (Sec. 4.2). x spans [x0, x0 + N dx]: the water's recorded
/// x range, the cache domain or an explicit range (ReplayParams::extentX);
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

/// The geometry of `params` over the x range params.extentX names (the water's recorded range
/// by default, bake_record.h). Throws std::invalid_argument for an empty range.
Grid makeGrid(const cache::Header& header, const ReplayParams& params);

/// A of eq. (5) in cache frames per animation time unit: timeUnitSeconds / (dt frameInterval).
/// The paper's A = 4/dt simulation steps is timeUnitSeconds = 4.
double framesPerTimeUnit(const cache::Header& header, const ReplayParams& params);

} // namespace swell::runtime
