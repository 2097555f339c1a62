#pragma once
// The complete state of an MpsSolver between two steps (checkpoint / resume, docs/scenes.md
// "Checkpoints"): everything a later step reads that is not rebuilt from the scene. A solver built
// from the same scene that imports it continues bit for bit as the solver that exported it. Plain
// data; the checkpoint file format (checkpoint.h) serialises it.

#include <cstdint>
#include <vector>

#include "swell/bake/particles.h"

namespace swell::bake {

struct MpsState {
    long step = 0;             ///< steps taken
    double time = 0.0;         ///< simulated time (s)
    double lastMaxSpeed = 0.0; ///< max |u| of the last step (m/s): the adaptive dt of the next
    /// Positions, velocities, pressures (the PPE warm start), number densities and kinds.
    Particles particles;
    /// Positions at the last neighbour-list build (Verlet skin reference). The lists are
    /// rebuilt from them on import, so the next step sees the same lists in the same order.
    /// NaN for a particle moved between steps (recycling): the next step rebuilds anyway.
    std::vector<double> neighborX, neighborY;
    /// Rest x of the moving-wall (piston) particles, index = particle; empty without one.
    /// The wall's motion itself is a pure function of time, rebuilt from the scene.
    std::vector<double> wallRestX;
    /// Water taken out of the run (MpsSolver::removeWater), as indices in the scene's initial
    /// particles, ascending; `particles` holds the others in their order.
    std::vector<std::uint32_t> removedWater;
};

} // namespace swell::bake
