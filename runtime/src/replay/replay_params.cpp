#include "swell/runtime/replay/replay_params.h"

#include "../json_read.h"

#include "swell/runtime/replay/bake_record.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <tuple>

namespace swell::runtime {

std::string toString(FramePolicy policy) {
    switch (policy) {
    case FramePolicy::Clamp:
        return "clamp";
    case FramePolicy::Loop:
        return "loop";
    case FramePolicy::Seamless:
        break;
    }
    return "seamless";
}

FramePolicy framePolicyFromString(const std::string& name) {
    if (name == "clamp")
        return FramePolicy::Clamp;
    if (name == "loop")
        return FramePolicy::Loop;
    if (name == "seamless")
        return FramePolicy::Seamless;
    throw std::invalid_argument(
        fmt::format("policy must be seamless, loop or clamp, got '{}'", name));
}

std::string toString(ExtentX extent) {
    return extent == ExtentX::Water ? "water" : extent == ExtentX::Domain ? "domain" : "explicit";
}

std::string toString(Reconstruction r) {
    return r == Reconstruction::Paper ? "paper" : "envelope";
}

Reconstruction reconstructionFromString(const std::string& name) {
    if (name == "paper")
        return Reconstruction::Paper;
    if (name == "envelope")
        return Reconstruction::Envelope;
    throw std::invalid_argument(
        fmt::format("reconstruction must be envelope or paper, got '{}'", name));
}

std::string toString(TimeSampling sampling) {
    return sampling == TimeSampling::Nearest ? "nearest" : "linear";
}

TimeSampling timeSamplingFromString(const std::string& name) {
    if (name == "nearest")
        return TimeSampling::Nearest;
    if (name == "linear")
        return TimeSampling::Linear;
    throw std::invalid_argument(
        fmt::format("time_sampling must be linear or nearest, got '{}'", name));
}

void ReplayParams::validate() const {
    if (cellsX < 1 || cellsX > 8192 || cellsZ < 1 || cellsZ > 8192) {
        throw std::invalid_argument(fmt::format(
            "cells_x x cells_z must be 1..8192 cells per axis, got {}x{}", cellsX, cellsZ));
    }
    if (slices < 2 || slices > 16384) {
        throw std::invalid_argument(fmt::format("slices must be in [2, 16384], got {}", slices));
    }
    // eq. (6): F |N| <= 1 with max |N| = 1 means F <= 1.
    if (!std::isfinite(fluctuation) || fluctuation < 0.0 || fluctuation > 1.0) {
        throw std::invalid_argument(fmt::format(
            "fluctuation must be in [0, 1] (eq. (6): F |N| <= 1 with max |N| = 1), got {}",
            fluctuation));
    }
    if (!std::isfinite(timeUnitSeconds) || timeUnitSeconds <= 0.0) {
        throw std::invalid_argument(
            fmt::format("time_unit_seconds must be > 0, got {}", timeUnitSeconds));
    }
    // Eq. (7)'s window reaches 1.5 cells in x and 1 in z from a cell centre: below 0.25 cells
    // the float32 weights of the GPU underflow to 0 inside the window (exp(-3.25 / (2 sigma^2))
    // < 1e-38 at sigma 0.136) where the double-precision reference's do not, so the two would
    // disagree by whole wave heights (found by tools/stress).
    if (!std::isfinite(sigma) || sigma < kMinSigma) {
        throw std::invalid_argument(fmt::format(
            "sigma must be >= {} cells (float32 Gaussian weights underflow inside the window "
            "below it), got {}",
            kMinSigma, sigma));
    }
    if (!std::isfinite(extentZ) || extentZ < 0.0) {
        throw std::invalid_argument(fmt::format("extent_z must be >= 0 m, got {}", extentZ));
    }
    if (extentX == ExtentX::Explicit &&
        !(std::isfinite(extentX0) && std::isfinite(extentX1) && extentX1 > extentX0)) {
        throw std::invalid_argument(fmt::format(
            "extent_x must be [x0, x1] with x1 > x0 (metres), got [{}, {}]", extentX0, extentX1));
    }
    if (!std::isfinite(crossfadeSeconds) || crossfadeSeconds < 0.0 || crossfadeSeconds > 60.0) {
        throw std::invalid_argument(
            fmt::format("crossfade_seconds must be in [0, 60] s, got {}", crossfadeSeconds));
    }
    noise.validate();
}

namespace {

std::string filterName(NoiseFilter f) {
    return f == NoiseFilter::LowPass ? "low" : f == NoiseFilter::HighPass ? "high" : "none";
}

NoiseFilter filterFromName(const std::string& name) {
    if (name == "low")
        return NoiseFilter::LowPass;
    if (name == "high")
        return NoiseFilter::HighPass;
    if (name == "none")
        return NoiseFilter::None;
    throw std::invalid_argument(
        fmt::format("noise.filter must be low, high or none, got '{}'", name));
}

using json_read::read;

void rejectUnknown(const nlohmann::json& j, std::initializer_list<const char*> known,
                   const std::string& prefix) {
    json_read::rejectUnknown(j, known, prefix, prefix.empty() ? "replay parameters" : prefix);
}

} // namespace

nlohmann::json toJson(const ReplayParams& p) {
    return {{"cells_x", p.cellsX},
            {"cells_z", p.cellsZ},
            {"slices", p.slices},
            {"fluctuation", p.fluctuation},
            {"time_unit_seconds", p.timeUnitSeconds},
            {"policy", toString(p.policy)},
            {"sigma", p.sigma},
            {"extent_z", p.extentZ},
            {"seed", p.seed},
            {"noise",
             {{"time_samples", p.noise.timeSamples},
              {"beta", p.noise.beta},
              {"cutoff", p.noise.cutoff},
              {"filter", filterName(p.noise.filter)}}},
            {"extent_x", p.extentX == ExtentX::Explicit
                             ? nlohmann::json::array({p.extentX0, p.extentX1})
                             : nlohmann::json(toString(p.extentX))},
            {"reconstruction", toString(p.reconstruction)},
            {"window", p.steadyWindow ? "steady" : "all"},
            {"crossfade_seconds", p.crossfadeSeconds},
            {"time_sampling", toString(p.timeSampling)}};
}

ReplayParams replayParamsFromJson(const nlohmann::json& j) {
    return replayParamsFromJson(j, ReplayParams{});
}

ReplayParams replayParamsFromJson(const nlohmann::json& j, const ReplayParams& base) {
    rejectUnknown(j,
                  {"cells_x", "cells_z", "slices", "fluctuation", "time_unit_seconds", "policy",
                   "sigma", "extent_z", "seed", "noise", "extent_x", "reconstruction", "window",
                   "crossfade_seconds", "time_sampling"},
                  "");
    ReplayParams p = base;
    read(j, "cells_x", "", p.cellsX);
    read(j, "cells_z", "", p.cellsZ);
    read(j, "slices", "", p.slices);
    read(j, "fluctuation", "", p.fluctuation);
    read(j, "time_unit_seconds", "", p.timeUnitSeconds);
    read(j, "sigma", "", p.sigma);
    read(j, "extent_z", "", p.extentZ);
    read(j, "seed", "", p.seed);
    std::string policy = toString(p.policy);
    read(j, "policy", "", policy);
    p.policy = framePolicyFromString(policy);
    read(j, "crossfade_seconds", "", p.crossfadeSeconds);
    std::string reconstruction = toString(p.reconstruction);
    read(j, "reconstruction", "", reconstruction);
    p.reconstruction = reconstructionFromString(reconstruction);
    std::string sampling = toString(p.timeSampling);
    read(j, "time_sampling", "", sampling);
    p.timeSampling = timeSamplingFromString(sampling);
    std::string window = p.steadyWindow ? "steady" : "all";
    read(j, "window", "", window);
    if (window != "steady" && window != "all")
        throw std::invalid_argument(fmt::format("window must be steady or all, got '{}'", window));
    p.steadyWindow = window == "steady";
    if (j.contains("extent_x")) {
        const nlohmann::json& e = j.at("extent_x");
        if (e.is_string() && (e == "water" || e == "domain")) {
            p.extentX = e == "water" ? ExtentX::Water : ExtentX::Domain;
        } else if (e.is_array() && e.size() == 2 && e[0].is_number() && e[1].is_number()) {
            p.extentX = ExtentX::Explicit;
            p.extentX0 = e[0].get<double>();
            p.extentX1 = e[1].get<double>();
        } else {
            throw std::invalid_argument(fmt::format(
                "extent_x must be \"water\", \"domain\" or [x0, x1], got {}", e.dump()));
        }
    }
    if (j.contains("noise")) {
        const nlohmann::json& n = j.at("noise");
        rejectUnknown(n, {"time_samples", "beta", "cutoff", "filter"}, "noise.");
        read(n, "time_samples", "noise.", p.noise.timeSamples);
        read(n, "beta", "noise.", p.noise.beta);
        read(n, "cutoff", "noise.", p.noise.cutoff);
        std::string filter = filterName(p.noise.filter);
        read(n, "filter", "noise.", filter);
        p.noise.filter = filterFromName(filter);
    }
    p.validate();
    return p;
}

Grid makeGrid(const cache::Header& header, const ReplayParams& params) {
    double x0 = header.domain.xMin;
    double x1 = header.domain.xMax;
    if (params.extentX == ExtentX::Water) {
        const BakeRecord record = bakeRecord(header); // the domain when nothing is recorded
        std::tie(x0, x1) = shownWaterX(record);
    } else if (params.extentX == ExtentX::Explicit) {
        x0 = params.extentX0;
        x1 = params.extentX1;
    }
    const double width = x1 - x0;
    if (!(width > 0.0) || !std::isfinite(width)) {
        throw std::invalid_argument(
            fmt::format("the replay's x range [{}, {}] has no width", x0, x1));
    }
    Grid g;
    g.cellsX = params.cellsX;
    g.cellsZ = params.cellsZ;
    g.slices = params.slices;
    g.x0 = x0;
    g.dx = width / params.cellsX;
    g.extentZ = params.extentZ > 0.0 ? params.extentZ : g.dx * params.cellsZ;
    g.dz = g.extentZ / params.cellsZ;
    return g;
}

double framesPerTimeUnit(const cache::Header& header, const ReplayParams& params) {
    const double frameTime = header.dt * header.frameInterval;
    if (!(frameTime > 0.0) || !std::isfinite(frameTime)) {
        throw std::invalid_argument(
            fmt::format("cache frame time dt * frame_interval = {} * {} is not positive", header.dt,
                        header.frameInterval));
    }
    return params.timeUnitSeconds / frameTime;
}

} // namespace swell::runtime
