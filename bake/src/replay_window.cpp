#include "swell/bake/replay_window.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "swell/bake/wave_theory.h"

namespace swell::bake {
namespace {

/// Round trips of the start-up long wave through a recycling channel before it is steady: one,
/// and half as much again for the seiche it leaves behind to decay (docs/scenes.md, "Replay
/// window": the gauges of ripple_small.json settle after 3-4 s, a round trip being 3.9 s; those
/// of ripple.json after about 4 s, a round trip being 3.1 s).
constexpr double kRecyclingRoundTrips = 1.5;

/// Near-critical inflow (U close to sqrt(g h)): the upstream-going wave is taken at no less than
/// this fraction of sqrt(g h), so the steady start stays finite.
constexpr double kMinReturnSpeed = 0.1;

/// Water extent along x: see replayWindow.
void waterExtent(const Scene& scene, ReplayWindow& w) {
    const GeometryParams& g = scene.geometry;
    if (!g.tank) {
        w.waterXMin = std::numeric_limits<double>::infinity();
        w.waterXMax = -std::numeric_limits<double>::infinity();
        for (const Box& b : g.water) {
            w.waterXMin = std::min(w.waterXMin, b.x0);
            w.waterXMax = std::max(w.waterXMax, b.x1);
        }
        return;
    }
    const Box& tank = *g.tank;
    w.waterXMin = tank.x0;
    w.waterXMax = tank.x1;
    if (scene.piston && scene.piston->kind == PistonKind::Sinusoidal) {
        // X(t) = r(t) S/2 sin(2 pi t / T) with the ramp 0 <= r <= 1 (piston_motion.h): the back
        // wall's inner face retreats to x0 - S/2. Random cycles S_i/2 (1 - cos) only push forward.
        w.waterXMin = tank.x0 - 0.5 * scene.piston->stroke;
    }
    if (scene.recycling) {
        // Water past the outflow is moved back to the inflow every step (Algorithm 1 step 8;
        // bake_driver.cpp, recycle()); only water that finds no free inflow slot waits beyond it.
        w.waterXMax = scene.recycling->outflowX;
    }
}

/// Piston: ramp + crossing of the tank by the first waves at the linear group velocity of the
/// slowest wave the piston makes (the shortest period).
void pistonSteadyStart(const Scene& scene, double depth, ReplayWindow& w) {
    const PistonParams& p = *scene.piston;
    const bool sinus = p.kind == PistonKind::Sinusoidal;
    const double period = sinus ? p.period : p.periodMin;
    const double length = scene.geometry.tank->width();
    const double cg = groupVelocity(2.0 * std::numbers::pi / period, depth, scene.physics.gravity);
    w.steadyStart = p.rampTime + length / cg;
    w.steadyReason = fmt::format(
        "piston ramp {:.2f} s + tank crossing {:.2f} m at the group velocity {:.2f} m/s "
        "(T = {:.2f} s{}, h = {:.2f} m, linear theory) = {:.2f} s",
        p.rampTime, length, cg, period, sinus ? "" : ", the shortest random period", depth,
        w.steadyStart);
}

/// Recycling channel: the inflow zone starts impulsively and sends a long wave (the start-up
/// bore) downstream at sqrt(g h) + U; it reflects at the front wall (water that waits for a free
/// inflow slot fills the basin beyond the outflow, so the channel's water reaches the front wall)
/// and comes back upstream at |sqrt(g h) - U|, and goes on sloshing (a seiche) while it decays:
/// kRecyclingRoundTrips round trips.
void recyclingSteadyStart(const Scene& scene, double depth, ReplayWindow& w) {
    const double u = std::abs(scene.recycling->velocity);
    const double length = scene.geometry.tank->width();
    const double c = std::sqrt(scene.physics.gravity * depth);
    const double back = std::max(std::abs(c - u), kMinReturnSpeed * c);
    const double roundTrip = length / (c + u) + length / back;
    w.steadyStart = kRecyclingRoundTrips * roundTrip;
    const bool floored = back > std::abs(c - u);
    w.steadyReason = fmt::format(
        "recycling channel: {:g} x the long-wave round trip of the {:.2f} m tank, down at "
        "sqrt(g h) + U = {:.2f} + {:.2f} m/s and back at |sqrt(g h) - U| = {:.2f} m/s{} "
        "(h = {:.2f} m): {:g} x {:.2f} s = {:.2f} s",
        kRecyclingRoundTrips, length, c, u, back,
        floored ? " (near-critical inflow: floored at 0.1 sqrt(g h))" : "", depth,
        kRecyclingRoundTrips, roundTrip, w.steadyStart);
}

} // namespace

ReplayWindow replayWindow(const Scene& scene) {
    ReplayWindow w;
    waterExtent(scene, w);
    w.stillWaterLevel = stillWaterLevel(scene);
    w.particleSpacing = scene.geometry.particleSpacing;
    const bool forced = scene.piston || scene.recycling;
    const double depth = scene.geometry.tank ? w.stillWaterLevel - scene.geometry.tank->y0 : 0.0;
    if (!forced) {
        w.steadyReason =
            "no forcing (no piston, no recycling): the flow only relaxes from its initial state";
    } else if (!(depth > 0.0)) {
        w.steadyReason = "forced, but the still-water level is not above the tank bed: no wave "
                         "speed to wait for";
    } else if (scene.piston) {
        pistonSteadyStart(scene, depth, w);
    } else {
        recyclingSteadyStart(scene, depth, w);
    }
    return w;
}

nlohmann::json toJson(const ReplayWindow& w) {
    return nlohmann::json{{"water_x_min", w.waterXMin},
                          {"water_x_max", w.waterXMax},
                          {"still_water_level", w.stillWaterLevel},
                          {"particle_spacing", w.particleSpacing},
                          {"steady_start_s", w.steadyStart},
                          {"steady_reason", w.steadyReason}};
}

} // namespace swell::bake
