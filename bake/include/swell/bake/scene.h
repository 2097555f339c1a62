#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "swell/bake/geometry.h"
#include "swell/bake/mps_params.h"
#include "swell/bake/mps_solver.h"
#include "swell/bake/piston_motion.h"

namespace swell::bake {

/// Settings for what a bake stores (used by the bake driver; the solver ignores them).
struct OutputParams {
    double frameInterval = 0.02; ///< simulated time between stored frames (s): 50 frames per second
    double splashRatio = 0.49;   ///< d1: water with n < d1 n0 is splash (paper eq. (4), Table 1)
    double surfaceRatio =
        0.96; ///< d2: water with d1 n0 <= n <= d2 n0 is surface (paper eq. (4), Table 1)
    /// Wave gauges: x positions (m) where probes report the free-surface elevation.
    std::vector<double> gauges;
    /// Still-water level (m) that gauge elevations are measured from; unset: the top of the
    /// highest water rectangle (the initial surface).
    std::optional<double> stillWaterLevel;
};

/// How long a scene runs and how fast its water is expected to move: read by the bake
/// driver, the piston and the scene's dt check, never by the solver. Scene keys
/// solver.end_time and solver.expected_speed (docs/scenes.md).
struct RunParams {
    double endTime = 1.0; ///< simulated time to run (s)
    /// Speed (m/s) the scene is expected to reach, used to check dt at load; 0: 2 sqrt(g H) with
    /// H the highest water top above the lowest water bottom (dam-break front speed, Ritter).
    double expectedSpeed = 0.0;
};

/// Inflow-outflow channel with particle recycling (paper Sec. 3.3.2; Algorithm 1 steps 3
/// "Add particles" and 8 "Delete particles"): water in the inflow zone [tank x0, inflowX1]
/// is driven at `velocity`; water that passes `outflowX` is moved back by outflowX - tank x0
/// (same height) with the inflow velocity, so the particle count is conserved.
struct RecyclingParams {
    double inflowX1 = 0.2; ///< downstream end of the inflow zone (m)
    double velocity = 0.2; ///< horizontal speed imposed in the inflow zone (m/s)
    double outflowX = 1.0; ///< water beyond this x (m) leaves and re-enters at the inflow
};

/// A scene file: separate physics, geometry, solver and output sections (docs/scenes.md).
struct Scene {
    std::string name;        ///< short identifier
    std::string description; ///< free text
    PhysicsParams physics;
    GeometryParams geometry;
    SolverParams solver;
    RunParams run;
    OutputParams output;
    std::uint64_t seed = 1; ///< seed of all that is random (piston cycles, water jitter)
    /// Piston wavemaker: when set, the tank's back wall moves with this motion (Sec. 3.3.1).
    std::optional<PistonParams> piston;
    /// Inflow-outflow recycling (Sec. 3.3.2), when set.
    std::optional<RecyclingParams> recycling;
};

/// Parses and validates a scene. Every key is optional (defaults in docs/scenes.md) except
/// geometry.water; unknown keys, wrong types and bad values throw SceneError naming the key.
/// Also generates the geometry once to reject unusable rectangles, and checks dt against
/// the Courant limit for the scene's expected speed (unless solver.adaptive_dt).
Scene parseScene(const nlohmann::json& json);

/// Parses a scene file's text as JSON; anything that is not (syntax, a number beyond a double)
/// throws SceneError (key "") naming `source`.
nlohmann::json parseSceneJson(std::string_view text, const std::string& source);

/// Reads a scene file, applies the "--set" overrides in order (applyOverride) and parses it;
/// unreadable files and JSON syntax errors also throw SceneError (key "") with the file name.
Scene loadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});

/// The fully resolved scene (every key, defaults filled in) as JSON; parseScene of it
/// gives the same scene.
nlohmann::json toJson(const Scene& scene);

/// Speed (m/s) used to check dt at load: run.expectedSpeed, or if that is 0,
/// 2 sqrt(g H) with H the water column height (Ritter's dam-break front speed).
double expectedSpeed(const Scene& scene);

/// Applies one "--set" override "section.key=value" to scene JSON before parseScene.
/// The value is parsed as JSON (numbers, true/false, arrays, objects) or else taken as a
/// string. Throws SceneError for a malformed assignment.
void applyOverride(nlohmann::json& json, const std::string& assignment);

/// Generates the scene's particles and builds a solver for them; with a piston, the tank's
/// back wall becomes a MovingWall driven by PistonMotion (seeded by scene.seed).
MpsSolver makeSolver(const Scene& scene);

/// Still-water level (m) of a scene: output.still_water_level or the top of the highest
/// water rectangle.
double stillWaterLevel(const Scene& scene);

} // namespace swell::bake
