#pragma once
// What the bake records about its water for the replay (cache metadata key "replay",
// docs/cache-format.md): where the water can be, the still-water level, the particle spacing
// l0 and when the flow becomes statistically steady. Caches written before the record existed
// fall back to the cache domain and the whole bake, with a note saying so.

#include "swell/cache/header.h"

#include <string>
#include <utility>

namespace swell::runtime {

struct BakeRecord {
    bool recorded = false;  ///< the cache carries the "replay" block
    double waterXMin = 0.0; ///< m: lowest x where water can be (fallback: domain xMin)
    double waterXMax = 0.0; ///< m: highest x where water can be (fallback: domain xMax)
    /// m: y of the still-water surface (fallback: the metadata's "still_water_level", else NaN).
    double stillWaterLevel = 0.0;
    /// m: the end of the wave maker's own zone, the scene's recycling.inflow_x1 (NaN when the
    /// scene has none): the water before it is where waves are made, not where they are.
    double waveMakerXMax = 0.0;
    /// m: y of the tank's floor, the scene's geometry.tank.y0 (fallback: the domain's yMin).
    double floorLevel = 0.0;
    /// m: l0 (fallback: scene.geometry.particle_spacing, else 0: unknown).
    double particleSpacing = 0.0;
    double steadyStartSeconds = 0.0; ///< s of simulated time; 0 when not recorded
    std::string steadyReason;        ///< the bake's sentence, or why there is none
    std::string note;                ///< non-empty when something fell back (say it to the user)
};

/// The record of `header`'s metadata. Throws std::invalid_argument naming the key when the
/// block is present but malformed (wrong type, non-finite, x_max <= x_min, negative start).
BakeRecord bakeRecord(const cache::Header& header);

/// The x range a replay shows with ExtentX::Water: the recorded water extent less the wave
/// maker's zone (when it leaves some water).
std::pair<double, double> shownWaterX(const BakeRecord& record);

} // namespace swell::runtime
