#pragma once
// The Lobovsky et al. (2014) dam break as a run (docs/validation.md, Lobovsky et al. (2014) dam
// break): the scene's column collapses, and after every step the water level is read at the
// gauges H1..H4 and the pressure on the far wall at Buchner's sensor P1 (buchner2002.h;
// docs/validation.md, Far-wall pressure). One run, as swell-validate lobovsky reports it and as
// the CI-resolution test (tests/bake/validation/validation_test.cpp) bounds it. No I/O.

#include <cstddef>
#include <string>
#include <vector>

#include "swell/bake/scene.h"
#include "swell/bake/step_stats.h"
#include "swell/bake/validation/lobovsky2014.h"

namespace swell::bake::validation {

/// The pressure at a wall sensor at one moment.
struct PressureSample {
    double t = 0.0; ///< (s)
    double p = 0.0; ///< (Pa)
};

struct LobovskyRun {
    /// "stable", or "stopped: " and the divergence detector's message.
    std::string outcome;
    double H = 0.0; ///< the column's height (m): the scene's first water rectangle
    std::size_t particles = 0;
    std::size_t water = 0;
    StepTotals totals;
    /// Per gauge (H1..H4, lobovskyH300Gauges), at t = 0 and after every step: the top of the
    /// highest non-splash water particle within l0 of the gauge, from the tank floor, 0 where
    /// dry (sampleProbes): what the check compares.
    std::vector<std::vector<LevelPoint>> top;
    /// Sensor P1 scaled to the scene: from (kBuchnerP1TopOverH - kBuchnerP1HeightOverH) H to
    /// kBuchnerP1TopOverH H above the tank floor (m), on the downstream wall.
    double sensorLow = 0.0;
    double sensorHigh = 0.0;
    /// How many wall particles the sensor averages (0: the band holds none at this spacing).
    std::size_t sensorParticles = 0;
    /// At t = 0 and after every step: the mean pressure of the downstream wall's first layer of
    /// wall particles whose centres lie in [sensorLow, sensorHigh]; 0 where none does.
    std::vector<PressureSample> farWallPressure;
};

/// Runs `scene` (which needs a tank; the gauges stand at tank.x0 + their x, the sensor on the
/// wall at tank.x1) to tEnd, or until the divergence detector stops it. Throws SceneError for a
/// scene without a tank.
LobovskyRun runLobovsky(const Scene& scene, double tEnd);

} // namespace swell::bake::validation
