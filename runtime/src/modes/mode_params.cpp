#include "swell/runtime/modes/mode_params.h"

#include "../json_read.h"

#include "swell/split_mix64.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace swell::runtime {
namespace {

using json_read::read;

} // namespace

std::string toString(ReplayMode mode) {
    switch (mode) {
    case ReplayMode::Surging:
        return "surging";
    case ReplayMode::Ripple:
        return "ripple";
    case ReplayMode::Whirlpool:
        return "whirlpool";
    }
    throw std::logic_error("unknown ReplayMode");
}

ReplayMode replayModeFromString(const std::string& name) {
    for (ReplayMode m : {ReplayMode::Surging, ReplayMode::Ripple, ReplayMode::Whirlpool}) {
        if (toString(m) == name)
            return m;
    }
    throw std::invalid_argument(
        fmt::format("mode must be surging, ripple or whirlpool, got '{}'", name));
}

void RippleParams::validate() const {
    if (anglesDegrees.empty() || anglesDegrees.size() > 16) {
        throw std::invalid_argument(
            fmt::format("ripple.angles: need 1 .. 16 directions, got {}", anglesDegrees.size()));
    }
    for (double a : anglesDegrees) {
        if (!std::isfinite(a))
            throw std::invalid_argument("ripple.angles: every angle must be finite");
    }
    if (weights.empty())
        return;
    if (weights.size() != anglesDegrees.size()) {
        throw std::invalid_argument(fmt::format("ripple.weights: {} weights for {} directions",
                                                weights.size(), anglesDegrees.size()));
    }
    double sum = 0.0;
    for (double w : weights) {
        if (!std::isfinite(w) || w < 0.0)
            throw std::invalid_argument(fmt::format("ripple.weights: {} is not >= 0", w));
        sum += w;
    }
    if (!(sum > 0.0))
        throw std::invalid_argument("ripple.weights: the weights sum to 0");
}

std::vector<double> RippleParams::normalisedWeights() const {
    const std::size_t D = anglesDegrees.size();
    if (weights.empty())
        return std::vector<double>(D, 1.0 / static_cast<double>(D));
    double sum = 0.0;
    for (double w : weights)
        sum += w;
    std::vector<double> out(weights);
    for (double& w : out)
        w /= sum;
    return out;
}

void WhirlpoolParams::validate() const {
    if (!std::isfinite(innerRadiusCells) || innerRadiusCells <= 0.0) {
        throw std::invalid_argument(
            fmt::format("whirlpool.inner_radius_cells must be > 0, got {}", innerRadiusCells));
    }
    // e^(2 pi b) is the ratio of outer to inner radius: keep it a finite, sane number.
    if (!std::isfinite(growth) || growth <= 0.0 || growth > 2.0) {
        throw std::invalid_argument(
            fmt::format("whirlpool.growth must be in (0, 2] per radian, got {}", growth));
    }
    if (!std::isfinite(turnsPerTimeUnit) || std::abs(turnsPerTimeUnit) > 1e3) {
        throw std::invalid_argument(
            fmt::format("whirlpool.turns_per_time_unit must be finite and |.| <= 1000, got {}",
                        turnsPerTimeUnit));
    }
    if (!std::isfinite(eyeDepth) || eyeDepth < 0.0 || eyeDepth > 1e3) {
        throw std::invalid_argument(
            fmt::format("whirlpool.eye_depth must be in [0, 1000] m, got {}", eyeDepth));
    }
}

void ModeParams::validate() const {
    if (mode == ReplayMode::Ripple)
        ripple.validate();
    if (mode == ReplayMode::Whirlpool)
        whirlpool.validate();
}

int ModeParams::sliceSets() const {
    return mode == ReplayMode::Ripple ? static_cast<int>(ripple.anglesDegrees.size()) : 1;
}

nlohmann::json toJson(const ModeParams& p) {
    return {{"mode", toString(p.mode)},
            {"ripple", {{"angles_degrees", p.ripple.anglesDegrees}, {"weights", p.ripple.weights}}},
            {"whirlpool",
             {{"inner_radius_cells", p.whirlpool.innerRadiusCells},
              {"growth", p.whirlpool.growth},
              {"turns_per_time_unit", p.whirlpool.turnsPerTimeUnit},
              {"eye_depth", p.whirlpool.eyeDepth}}}};
}

ModeParams modeParamsFromJson(const nlohmann::json& j) {
    json_read::rejectUnknown(j, {"mode", "ripple", "whirlpool"}, "", "mode parameters");
    ModeParams p;
    std::string mode = toString(p.mode);
    read(j, "mode", "", mode);
    p.mode = replayModeFromString(mode);
    if (j.contains("ripple")) {
        const nlohmann::json& r = j.at("ripple");
        json_read::rejectUnknown(r, {"angles_degrees", "weights"}, "ripple.", "ripple");
        read(r, "angles_degrees", "ripple.", p.ripple.anglesDegrees);
        read(r, "weights", "ripple.", p.ripple.weights);
    }
    if (j.contains("whirlpool")) {
        const nlohmann::json& w = j.at("whirlpool");
        json_read::rejectUnknown(
            w, {"inner_radius_cells", "growth", "turns_per_time_unit", "eye_depth"}, "whirlpool.",
            "whirlpool");
        read(w, "inner_radius_cells", "whirlpool.", p.whirlpool.innerRadiusCells);
        read(w, "growth", "whirlpool.", p.whirlpool.growth);
        read(w, "turns_per_time_unit", "whirlpool.", p.whirlpool.turnsPerTimeUnit);
        read(w, "eye_depth", "whirlpool.", p.whirlpool.eyeDepth);
    }
    p.validate();
    return p;
}

ReplayParams paperDefaults(ReplayMode mode) {
    ReplayParams p; // surging: K 256, F 0.3, beta 2.0, c 128 (Table 4)
    if (mode == ReplayMode::Ripple) {
        p.fluctuation = 0.4;
        p.noise.beta = 2.5;
    } else if (mode == ReplayMode::Whirlpool) {
        p.slices = 128; // Sec. 6: "only K = 128 slices are used"
        p.fluctuation = 0.4;
        p.noise.beta = 2.5;
        p.noise.cutoff = 64.0;
    }
    return p;
}

ReplayParams swellDefaults(ReplayMode mode) {
    ReplayParams p = paperDefaults(mode);
    if (mode == ReplayMode::Surging || mode == ReplayMode::Whirlpool) {
        // Surging: crests along z, mean |dh/dz| / mean |dh/dx| 0.31-0.44 on surging_small
        // (seeds 1-3), against 3.0 with Table 4's values. Whirlpool: neighbouring spirals close
        // in time, so that the footprint filter leaves no needle cells (docs/runtime.md).
        p.fluctuation = 0.07;
        p.noise.beta = 4.0;
        p.noise.cutoff = 4.0;
    }
    return p;
}

std::uint64_t sliceSetSeed(std::uint64_t seed, int d) {
    if (d < 0)
        throw std::logic_error("sliceSetSeed: negative slice set");
    if (d == 0)
        return seed;
    SplitMix64 g(seed);
    std::uint64_t s = 0;
    for (int i = 0; i < d; ++i)
        s = g.next();
    return s;
}

ReplayParams sliceSetParams(const ReplayParams& params, int d) {
    ReplayParams p = params;
    p.seed = sliceSetSeed(params.seed, d);
    return p;
}

std::vector<SliceSampler> makeSamplers(const ReplayParams& params, const ModeParams& mode,
                                       std::size_t frameCount, double A) {
    return makeSamplers(params, mode, Timeline::whole(frameCount, params.policy), A);
}

std::vector<SliceSampler> makeSamplers(const ReplayParams& params, const ModeParams& mode,
                                       const Timeline& timeline, double A) {
    mode.validate();
    std::vector<SliceSampler> out;
    const int sets = mode.sliceSets();
    out.reserve(static_cast<std::size_t>(sets));
    for (int d = 0; d < sets; ++d)
        out.emplace_back(sliceSetParams(params, d), timeline, A);
    return out;
}

std::vector<std::uint32_t> framesUsed(std::span<const SliceSampler> samplers,
                                      std::span<const double> taus) {
    std::vector<std::uint32_t> all;
    for (const SliceSampler& s : samplers) {
        const std::vector<std::uint32_t> used = s.framesUsed(taus);
        all.insert(all.end(), used.begin(), used.end());
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
}

} // namespace swell::runtime
