#pragma once
// What the runtime needs to know about a bake and cannot guess from the frames (the
// "replay" block of the cache metadata, docs/cache-format.md): the x range where water can
// be (the header's domain is the solver's padded domain) and the simulated time from which
// the flow is statistically steady (a bake starts from still water and ramps its forcing up).
// Pure functions of the scene; no I/O.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "swell/bake/scene.h"

namespace swell::bake {

/// Where the water is and when the flow is steady (docs/scenes.md, "Replay window").
struct ReplayWindow {
    double waterXMin = 0.0;       ///< lowest x where water can be (m)
    double waterXMax = 0.0;       ///< highest x where water can be (m)
    double stillWaterLevel = 0.0; ///< y of the still water surface (m)
    double particleSpacing = 0.0; ///< l0 (m)
    double steadyStart = 0.0; ///< simulated time from which the flow is statistically steady (s)
    std::string steadyReason; ///< how steadyStart was derived, with the numbers
};

/// The scene's water extent and steady start:
/// - extent: the tank's interior from the piston's furthest retreat (x0 - S/2 for a
///   sinusoidal piston; a random piston only moves forward) to the front wall, or to
///   recycling.outflow_x in a recycling channel; without a tank, the water rectangles' union;
/// - steady start: with a piston, the ramp plus the time the slowest wave it makes (its
///   shortest period) needs to cross the tank at the linear group velocity; with recycling,
///   1.5 round trips of the start-up long wave through the tank, down at sqrt(g h) + U and
///   back at sqrt(g h) - U; else 0 (no forcing).
ReplayWindow replayWindow(const Scene& scene);

/// The metadata block: {"water_x_min", "water_x_max", "still_water_level",
/// "particle_spacing", "steady_start_s", "steady_reason"}.
nlohmann::json toJson(const ReplayWindow& window);

} // namespace swell::bake
