#pragma once
// Synthetic frames with known shape: a travelling sine wave sampled by jittered
// surface particles, plus splash particles above the crests. For tests, demos and
// benchmarks of the format and the runtime before (or without) a real bake.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"

#include <cstddef>
#include <cstdint>

#include <nlohmann/json_fwd.hpp>

namespace swell::cache {

struct SyntheticWave {
    std::size_t surfaceCount = 400; ///< surface particles per frame
    std::size_t splashCount = 0;    ///< splash particles per frame
    float length = 4.0f;            ///< tank length (m); x in [0, length]
    float depth = 0.5f;             ///< still-water depth (m)
    float amplitude = 0.05f;        ///< wave amplitude (m)
    float wavelength = 1.0f;        ///< wavelength (m)
    float period = 0.8f;            ///< wave period (s)
    double frameTime = 0.02;        ///< simulated seconds between frames
    std::uint64_t seed = 1;         ///< jitter and splash placement
};

/// Bounds that hold every particle the generator can produce.
Domain syntheticDomain(const SyntheticWave& w);
/// Surface height eta(x, t) of the generator's wave (m, above the bed).
double syntheticHeight(const SyntheticWave& w, double x, double t);
/// Frame `index` (time index * frameTime); deterministic in (w, index).
Frame syntheticFrame(const SyntheticWave& w, std::size_t index);
/// The metadata's "replay" block for a synthetic cache, in the schema swell-bake writes
/// (docs/cache-format.md): water over [0, length], still water at `depth`, particle spacing
/// length / (surfaceCount - 1), steady from t = 0 (the wave is periodic from the first frame).
nlohmann::json syntheticReplayJson(const SyntheticWave& w);

} // namespace swell::cache
