#pragma once
// swell-play fidelity: the replay against the simulated surface it replays (docs/runtime.md,
// "Fidelity"), and the continuity of a long replay.

#include "play_common.h"

namespace swell::play {

struct FidelityOptions {
    int frames = 0;           ///< F = 0 part: window frames measured, evenly spread (0: all)
    int mixTimes = 24;        ///< F > 0 part: animation times measured
    double seamSeconds = 0.0; ///< continuity part: simulated seconds replayed (0: skip)
};

void addFidelityOptions(CLI::App* cmd, FidelityOptions& f);
int runFidelity(Options& o, const FidelityOptions& f);

} // namespace swell::play
