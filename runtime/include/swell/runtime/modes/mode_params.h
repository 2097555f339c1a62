#pragma once
// The three replay layouts of the paper (Sec. 4.2, 4.4, 4.5) and their parameters:
//  * surging: one slice set along z (eq. 5-7), GpuReplay / CpuReconstruction;
//  * ripple: several directions, each a rotated copy of the surging slice set with its own
//    noise, synthesised by eq. (8) (ripple.h);
//  * whirlpool: the slices bent into log spirals around the centre (whirlpool.h).

#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <vector>

namespace swell::runtime {

enum class ReplayMode {
    Surging,   ///< Sec. 4.2: one slice set, eq. (5)-(7)
    Ripple,    ///< Sec. 4.4: several directions, eq. (8)
    Whirlpool, ///< Sec. 4.5: spiral slices
};

/// "surging", "ripple", "whirlpool".
std::string toString(ReplayMode mode);
/// Inverse of toString; throws std::invalid_argument naming "mode".
ReplayMode replayModeFromString(const std::string& name);

/// Ripple directions (Sec. 4.4). Direction d propagates along (cos a_d, sin a_d) in the base
/// mesh's (x, z) plane: its slice set is the surging one rotated by a_d about the mesh centre.
struct RippleParams {
    std::vector<double> anglesDegrees{0.0, 30.0}; ///< a_d; paper: two, about 30 degrees apart
    std::vector<double> weights;                  ///< omega_d of eq. (8), >= 0; empty: the mean

    /// Throws std::invalid_argument naming "ripple.angles" / "ripple.weights".
    void validate() const;
    /// The weights normalised to sum 1 (equal when `weights` is empty).
    std::vector<double> normalisedWeights() const;
};

/// Whirlpool spirals (Sec. 4.5): slice j starts at angle phi_j = 2 pi j / J + spin and runs
/// along r(t) = a e^(b t), angle phi_j + t, t in [0, 2 pi] (J = 2K - 1 slices).
struct WhirlpoolParams {
    double innerRadiusCells = 15.0;  ///< a in cells of dx (paper: a = 15 dx)
    double growth = 25.0 / 128.0;    ///< b per radian (paper: b = 25 dz with dz = 1/128 of its
                                     ///< unit mesh; outer radius a e^(2 pi b) = 3.41 a)
    double turnsPerTimeUnit = 0.125; ///< spin: turns of the spiral set per animation time unit
                                     ///< (counter-clockwise in (x, z); 0: still)
    double eyeDepth = 0.0;           ///< depth of the eye's funnel at the centre, metres
                                     ///< (whirlpool.h; 0: the paper's flat eye)

    /// Throws std::invalid_argument naming "whirlpool.inner_radius_cells" etc.
    void validate() const;
};

/// Which layout, and the parameters of the non-surging ones.
struct ModeParams {
    ReplayMode mode = ReplayMode::Surging; ///< layout
    RippleParams ripple;                   ///< used by ReplayMode::Ripple
    WhirlpoolParams whirlpool;             ///< used by ReplayMode::Whirlpool

    void validate() const;
    /// Number of slice sets (noise fields): the ripple's directions, else 1.
    int sliceSets() const;
};

/// {"mode": name, "ripple": {"angles_degrees", "weights"}, "whirlpool": {"inner_radius_cells",
///  "growth", "turns_per_time_unit"}}.
nlohmann::json toJson(const ModeParams& params);
/// Reads the keys present over the defaults, then validate(); unknown keys throw naming them.
ModeParams modeParamsFromJson(const nlohmann::json& j);

/// The paper's Table 4 / Sec. 6 values for `mode` (K, F, beta, c); every other field default.
/// surging: K 256, F 0.3, beta 2.0, c 128; ripple: K 256, F 0.4, beta 2.5, c 128;
/// whirlpool: K 128, F 0.4, beta 2.5, c 64.
ReplayParams paperDefaults(ReplayMode mode);

/// swell-play's noise defaults for `mode` (`--preset swell`): surging F 0.07, beta 4, c 4 with
/// K 256, chosen from a measured sweep for long crests that still differ between seeds
/// (docs/runtime.md, "Presets"); ripple and whirlpool: paperDefaults(mode).
ReplayParams swellDefaults(ReplayMode mode);

/// Noise seed of slice set d: the run's seed for d = 0 (so one ripple direction at 0 degrees
/// is exactly the surging replay), else the d-th output of SplitMix64(seed).
std::uint64_t sliceSetSeed(std::uint64_t seed, int d);

/// The replay parameters of slice set d (its seed; everything else as `params`).
ReplayParams sliceSetParams(const ReplayParams& params, int d);

/// One SliceSampler per slice set (sliceSets() of them), seeds from sliceSetSeed.
std::vector<SliceSampler> makeSamplers(const ReplayParams& params, const ModeParams& mode,
                                       std::size_t frameCount, double A);
/// One SliceSampler per slice set over `timeline` (planTimeline), seeds from sliceSetSeed.
std::vector<SliceSampler> makeSamplers(const ReplayParams& params, const ModeParams& mode,
                                       const Timeline& timeline, double A);
/// Every frame some slice of some set shows at some tau: sorted, unique.
std::vector<std::uint32_t> framesUsed(std::span<const SliceSampler> samplers,
                                      std::span<const double> taus);

} // namespace swell::runtime
