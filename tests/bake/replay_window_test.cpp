// Replay window (replay_window.h): the water extent and steady start of every shipped scene,
// the criteria's assumptions about the piston, and the metadata block's schema.
#include "swell/bake/replay_window.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "swell/bake/piston_motion.h"
#include "swell/bake/scene.h"

using namespace swell::bake;
using nlohmann::json;

namespace {

Scene shipped(const std::string& name) {
    return loadScene(std::string(SWELL_SCENES_DIR) + "/" + name);
}

/// Smallest piston displacement over the scene's run, sampled every dt.
double furthestRetreat(const Scene& scene) {
    const PistonMotion motion(*scene.piston, scene.run.endTime);
    double lowest = 0.0;
    for (double t = 0.0; t <= scene.run.endTime; t += scene.solver.time.dt) {
        lowest = std::min(lowest, motion.at(t).displacement);
    }
    return lowest;
}

} // namespace

TEST(ReplayWindow, WaterExtentOfEveryShippedScene) {
    struct Case {
        const char* file;
        double xMin, xMax;
    };
    // Tank interior; the regular-wave piston retreats S/2 = 1.5 cm behind x0; recycling channels
    // end at their outflow.
    for (const Case& c :
         {Case{"surging.json", 0.0, 2.8}, Case{"surging_small.json", 0.0, 2.0},
          Case{"ripple.json", 0.0, 2.3}, Case{"ripple_small.json", 0.0, 1.6},
          Case{"regular_wave.json", -0.015, 4.0}, Case{"regular_wave_small.json", -0.015, 4.0},
          Case{"dam_break.json", 0.0, 0.5}, Case{"dam_break_small.json", 0.0, 0.5},
          Case{"still_tank.json", 0.0, 0.4}, Case{"still_tank_small.json", 0.0, 0.2}}) {
        const Scene scene = shipped(c.file);
        const ReplayWindow w = replayWindow(scene);
        EXPECT_NEAR(w.waterXMin, c.xMin, 1e-12) << c.file;
        EXPECT_NEAR(w.waterXMax, c.xMax, 1e-12) << c.file;
        EXPECT_DOUBLE_EQ(w.stillWaterLevel, stillWaterLevel(scene)) << c.file;
        EXPECT_DOUBLE_EQ(w.particleSpacing, scene.geometry.particleSpacing) << c.file;
    }
}

TEST(ReplayWindow, PistonRetreatMatchesItsMotion) {
    // The extent's assumption about piston_motion.h: random cycles never move behind the rest
    // position; a sinusoidal piston reaches x0 - S/2 (ramped in, within a sampling step).
    const Scene surging = shipped("surging.json");
    EXPECT_GE(furthestRetreat(surging), 0.0);
    EXPECT_DOUBLE_EQ(replayWindow(surging).waterXMin, surging.geometry.tank->x0);
    const Scene regular = shipped("regular_wave.json");
    const double retreat = furthestRetreat(regular);
    EXPECT_NEAR(retreat, -0.015, 1e-6);
    EXPECT_NEAR(replayWindow(regular).waterXMin, regular.geometry.tank->x0 + retreat, 1e-6);
}

TEST(ReplayWindow, WithoutATankTheWaterRectanglesUnion) {
    const Scene scene = parseScene(json::parse(R"({
        "geometry": { "particle_spacing": 0.02,
                      "water": [ { "x0": 0.3, "y0": 0.0, "x1": 0.7, "y1": 0.2 },
                                 { "x0": -0.4, "y0": 0.5, "x1": 0.1, "y1": 0.6 } ] } })"));
    const ReplayWindow w = replayWindow(scene);
    EXPECT_DOUBLE_EQ(w.waterXMin, -0.4);
    EXPECT_DOUBLE_EQ(w.waterXMax, 0.7);
    EXPECT_DOUBLE_EQ(w.stillWaterLevel, 0.6);
    EXPECT_EQ(w.steadyStart, 0.0);
}

TEST(ReplayWindow, SteadyStartOfSurgingIsRampPlusTankCrossingAtTheGroupVelocity) {
    // Shortest random period T = 1.0 s at h = 0.3 m: c_g = 0.929481 m/s (wave_theory_test), so
    // 1.0 s + 2.8 m / 0.929481 m/s = 4.0124 s.
    const ReplayWindow w = replayWindow(shipped("surging.json"));
    EXPECT_NEAR(w.steadyStart, 1.0 + 2.8 / 0.929481, 1e-5);
    EXPECT_EQ(
        w.steadyReason,
        "piston ramp 1.00 s + tank crossing 2.80 m at the group velocity 0.93 m/s (T = 1.00 s, "
        "the shortest random period, h = 0.30 m, linear theory) = 4.01 s");
    // A sinusoidal piston uses its period: regular_wave.json, T = 1.03 s, h = 0.2 m, 4 m tank,
    // ramp 2.06 s: c_g = 0.949666 m/s.
    const ReplayWindow r = replayWindow(shipped("regular_wave.json"));
    EXPECT_NEAR(r.steadyStart, 2.06 + 4.0 / 0.949666, 1e-5);
}

TEST(ReplayWindow, SteadyStartOfRecyclingIsALongWaveRoundTripThroughTheTank) {
    // ripple.json: 2.6 m tank, h = 0.3 m, U = 0.3 m/s, sqrt(g h) = 1.715517 m/s: a round trip
    // 2.6 / 2.015517 + 2.6 / 1.415517 = 1.2900 + 1.8368 = 3.1268 s, 1.5 of them 4.6902 s.
    const ReplayWindow w = replayWindow(shipped("ripple.json"));
    EXPECT_NEAR(w.steadyStart, 4.6902, 1e-4);
    EXPECT_EQ(
        w.steadyReason,
        "recycling channel: 1.5 x the long-wave round trip of the 2.60 m tank, down at "
        "sqrt(g h) + U = 1.72 + 0.30 m/s and back at |sqrt(g h) - U| = 1.42 m/s (h = 0.30 m): "
        "1.5 x 3.13 s = 4.69 s");
    // Near-critical inflow: the return speed is floored, the start stays finite.
    Scene critical = shipped("ripple_small.json");
    critical.recycling->velocity = std::sqrt(9.81 * 0.12);
    const ReplayWindow c = replayWindow(critical);
    EXPECT_NEAR(c.steadyStart,
                1.5 * (2.0 / (2.0 * std::sqrt(9.81 * 0.12)) + 2.0 / (0.1 * std::sqrt(9.81 * 0.12))),
                1e-9);
    EXPECT_NE(c.steadyReason.find("near-critical"), std::string::npos) << c.steadyReason;
}

TEST(ReplayWindow, UnforcedScenesAreSteadyFromTheStart) {
    for (const char* file : {"still_tank.json", "dam_break.json"}) {
        const ReplayWindow w = replayWindow(shipped(file));
        EXPECT_EQ(w.steadyStart, 0.0) << file;
        EXPECT_EQ(w.steadyReason.rfind("no forcing", 0), 0u) << w.steadyReason;
    }
}

TEST(ReplayWindow, ShippedWaveScenesLeaveAtLeastFourSteadySeconds) {
    // The runtime needs 2 F x time unit = 2.4 s of steady frames by default, plus margin for a
    // seamless loop.
    for (const char* file :
         {"surging.json", "surging_small.json", "ripple.json", "ripple_small.json"}) {
        const Scene scene = shipped(file);
        const ReplayWindow w = replayWindow(scene);
        EXPECT_GT(w.steadyStart, 0.0) << file;
        EXPECT_GE(scene.run.endTime - w.steadyStart, 4.0)
            << file << ": steady from " << w.steadyStart << " s";
    }
}

TEST(ReplayWindow, MetadataBlockHasExactlyTheSchemaKeys) {
    const ReplayWindow w = replayWindow(shipped("surging.json"));
    const json j = toJson(w);
    EXPECT_EQ(j.size(), 6u);
    EXPECT_EQ(j["water_x_min"], 0.0);
    EXPECT_EQ(j["water_x_max"], 2.8);
    EXPECT_EQ(j["still_water_level"], 0.3);
    EXPECT_EQ(j["particle_spacing"], 0.01);
    EXPECT_EQ(j["steady_start_s"], w.steadyStart);
    EXPECT_EQ(j["steady_reason"], w.steadyReason);
}
