#include "swell/runtime/replay_params.h"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

std::string toString(FramePolicy policy) {
    return policy == FramePolicy::Clamp ? "clamp" : "loop";
}

FramePolicy framePolicyFromString(const std::string& name) {
    if (name == "clamp")
        return FramePolicy::Clamp;
    if (name == "loop")
        return FramePolicy::Loop;
    throw std::invalid_argument(fmt::format("policy must be clamp or loop, got '{}'", name));
}

void ReplayParams::validate() const {
    if (cellsX < 1 || cellsX > 8192 || cellsZ < 1 || cellsZ > 8192) {
        throw std::invalid_argument(
            fmt::format("resolution must be 1..8192 cells per axis, got {}x{}", cellsX, cellsZ));
    }
    if (slices < 2 || slices > 16384) {
        throw std::invalid_argument(fmt::format("slices K must be in [2, 16384], got {}", slices));
    }
    // eq. (6): F |N| <= 1 with max |N| = 1 means F <= 1.
    if (!std::isfinite(fluctuation) || fluctuation < 0.0 || fluctuation > 1.0) {
        throw std::invalid_argument(fmt::format(
            "fluctuation F = {} breaks eq. (6) F |N| <= 1 (max |N| = 1): need 0 <= F <= 1",
            fluctuation));
    }
    if (!std::isfinite(timeUnitSeconds) || timeUnitSeconds <= 0.0) {
        throw std::invalid_argument(
            fmt::format("time_unit_seconds must be > 0, got {}", timeUnitSeconds));
    }
    if (!std::isfinite(sigma) || sigma <= 0.0) {
        throw std::invalid_argument(fmt::format("sigma must be > 0 cells, got {}", sigma));
    }
    if (!std::isfinite(extentZ) || extentZ < 0.0) {
        throw std::invalid_argument(fmt::format("extent_z must be >= 0 m, got {}", extentZ));
    }
    noise.validate();
}

Grid makeGrid(const cache::Header& header, const ReplayParams& params) {
    const double width = static_cast<double>(header.domain.xMax) - header.domain.xMin;
    if (!(width > 0.0)) {
        throw std::invalid_argument(fmt::format("cache domain has no width (xMin {}, xMax {})",
                                                header.domain.xMin, header.domain.xMax));
    }
    Grid g;
    g.cellsX = params.cellsX;
    g.cellsZ = params.cellsZ;
    g.slices = params.slices;
    g.x0 = header.domain.xMin;
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
