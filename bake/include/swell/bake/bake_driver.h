#pragma once
// The bake driver (README.md "Programs", docs/scenes.md): runs a scene's MPS
// simulation, classifies water by eq. (4) on every stored frame and streams the surface and
// splash particles into a cache. The I/O lives here, not in the solver.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "swell/bake/replay_window.h"
#include "swell/bake/scene.h"

namespace swell::bake {

/// A bake stopped on request (Ctrl-C, SIGTERM): no cache was written.
class BakeCancelled : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Where a running bake is; passed to BakeOptions::onProgress after every step.
struct BakeProgress {
    long step = 0;            ///< steps done
    long firstStep = 0;       ///< step the run started from (> 0 when resumed from a checkpoint)
    long totalSteps = 0;      ///< steps the bake will take
    double time = 0.0;        ///< simulated time (s)
    double wallSeconds = 0.0; ///< wall time since this run's first step (s)
    std::size_t frames = 0;   ///< frames stored so far
};

/// What to do besides the scene.
struct BakeOptions {
    std::filesystem::path output;       ///< cache path; the file appears there only when complete
    std::filesystem::path probes;       ///< probes CSV path, empty: no probes
    std::string sceneFile;              ///< scene file name, recorded in the cache metadata
    std::vector<std::string> overrides; ///< "--set" assignments, recorded in the metadata
    int threads = 1;                    ///< OpenMP threads (recorded; the caller sets them)
    std::string programVersion;         ///< recorded in the metadata
    /// Called after every step (cheap callers only: the app throttles its own output).
    std::function<void(const BakeProgress&)> onProgress;
    /// Polled after every step; true stops the bake with BakeCancelled (after writing a
    /// checkpoint when checkpoints are on).
    std::function<bool()> cancelled;
    /// Steps between checkpoints (checkpointPath(output), checkpoint.h); 0: none. A resumed
    /// bake without its own value keeps the interval of the checkpoint it resumed from.
    long checkpointEvery = 0;
    /// Continue from the checkpoint at checkpointPath(output) (CheckpointError when it is
    /// missing, damaged, from a different bake or of another numerics version); the cache is
    /// byte-identical to that of an uninterrupted bake by the same program.
    bool resume = false;
};

/// Conservation figures of the water particles at one instant (per metre of the 2D section).
struct Conservation {
    std::size_t water = 0;  ///< water particles
    std::size_t inTank = 0; ///< of them inside the tank's inner box (all when there is no tank)
    /// Water volume (area, m^2) from the mean number density of the interior water
    /// (n >= surface_ratio n0): water l0^2 n0 / mean n. Equal to water l0^2 at rest on the lattice.
    double volume = 0.0;
    double kineticEnergy = 0.0;   ///< sum 1/2 rho l0^2 |u|^2 (J/m)
    double potentialEnergy = 0.0; ///< sum rho l0^2 g (y - bed) (J/m), bed: tank y0 or lowest water
};

/// Conservation figures of `solver`'s water now; `bed` is the potential energy's zero level.
Conservation measureConservation(const MpsSolver& solver, const Scene& scene, double bed);

/// Per-run figures (the --json summary of swell-bake).
struct BakeSummary {
    std::size_t particlesWater = 0;
    std::size_t particlesWall = 0; ///< fixed particles: wall and dummy layers (piston included)
    long steps = 0;
    long frameIntervalSteps = 0; ///< steps between stored frames
    std::size_t frames = 0;      ///< stored frames (the initial state is frame 0)
    double surfaceMean = 0.0;    ///< surface particles per stored frame
    double splashMean = 0.0;     ///< splash particles per stored frame
    std::size_t keptMax = 0;     ///< most surface + splash particles in one frame
    double reduction = 0.0;      ///< water particles / mean kept per frame (paper Table 3)
    double wallSeconds = 0.0;    ///< whole bake, cache writing included (s)
    double msPerStep = 0.0;      ///< solver wall time per step (ms)
    double ppeIterationsMean = 0.0;
    double maxCourant = 0.0;      ///< largest Courant number of a (sub-)step
    std::uint64_t splitSteps = 0; ///< steps taken in sub-steps (solver.substep_courant)
    std::uint64_t substeps = 0;   ///< sub-steps those steps were split into, all together
    std::uint64_t recycled =
        0; ///< water particles moved from the outflow to the inflow (Sec. 3.3.2)
    std::uint64_t spilled = 0;    ///< water particles gone over the tank's walls (spill.h)
    std::uint64_t cacheBytes = 0; ///< size of the cache file
    std::uint64_t rawBytes = 0;   ///< float32 bytes of the stored particles before compression
    /// The scene's warnings (sceneWarnings), then the run's: e.g. a piston wave steeper than the
    /// breaking limit, water gone over the tank's walls.
    std::vector<std::string> warnings;
    ReplayWindow replay;               ///< water extent and steady start, as in the cache metadata
    long resumedFromStep = 0;          ///< step of the checkpoint this run resumed from (0: none)
    std::size_t checkpoints = 0;       ///< checkpoints written by this run
    std::uint64_t checkpointBytes = 0; ///< size of the last one
    double checkpointSeconds = 0.0;    ///< wall time spent writing them (s)
    /// Conservation figures of the water, at the start (before the first step) and the end.
    Conservation start, end;
};

nlohmann::json toJson(const BakeSummary& summary);

/// Steps (of dt) between stored frames: output.frame_interval / dt, which must be a whole
/// number. Throws SceneError (output.frame_interval, solver.adaptive_dt, solver.end_time).
long frameIntervalSteps(const Scene& scene);
/// Total steps: solver.end_time / dt, rounded to the nearest whole step.
long totalSteps(const Scene& scene);

/// Warnings about a scene that a bake should print, e.g. a piston whose linear-theory wave
/// (piston transfer function, dispersion) is steeper than the Miche breaking limit.
std::vector<std::string> sceneWarnings(const Scene& scene);

/// Runs the bake, holding the output's lock (cache::OutputLock) throughout; first removes the
/// temporaries (output, checkpoint, probes) of killed bakes. Throws cache::OutputBusy when
/// another process is writing the same output, SceneError (scene unusable for a bake),
/// DivergenceError (the simulation diverged), BakeCancelled, CheckpointError, cache::CacheError or
/// std::runtime_error (I/O). On any throw nothing is left at options.output (the cache writer
/// renames only when done); the last checkpoint, if any, stays. After a successful bake
/// with checkpoints (or resumed) the checkpoint is removed.
BakeSummary runBake(const Scene& scene, const BakeOptions& options);

} // namespace swell::bake
