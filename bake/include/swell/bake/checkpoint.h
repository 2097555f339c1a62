#pragma once
// Checkpoints of a long bake (docs/scenes.md, "Checkpoints"): everything a bake
// needs to continue as if it had never stopped, in one self-contained file written
// atomically next to the cache (CACHE.ckpt). The solver state comes from
// MpsSolver::exportState; this file only stores and checks it. Format: a 48-byte header
// (magic, version, sizes, XXH3-64 checksums of the header and of the payload) and a
// zstd-compressed payload; any damage is reported, never silently used.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "swell/bake/mps_state.h"
#include "swell/cache/frame.h"

namespace swell::bake {

/// A checkpoint that is missing, damaged, from a different bake, or cannot be written.
/// The message starts with the checkpoint's path.
class CheckpointError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Bake counters a resumed bake continues from (they feed the summary, not the cache).
struct BakeTotals {
    double surface = 0.0;       ///< surface particles summed over the stored frames
    double splash = 0.0;        ///< splash particles summed over the stored frames
    std::uint64_t keptMax = 0;  ///< most surface + splash particles in one frame
    std::uint64_t rawBytes = 0; ///< float32 bytes of the stored particles
    double solverSeconds = 0.0; ///< solver wall time of the steps done (s)
    double ppeIterations = 0.0; ///< PCG iterations summed over the steps done
    double maxCourant = 0.0;
    std::uint64_t recycled = 0;   ///< water particles recycled outflow -> inflow
    std::uint64_t splitSteps = 0; ///< steps taken in sub-steps
    std::uint64_t substeps = 0;   ///< sub-steps of those steps
    std::uint64_t spilled = 0;    ///< water particles gone over the tank's walls (spill.h)
    double firstSpillTime = 0.0;  ///< when the first of them went (s); 0 without any
};

/// What a checkpoint holds.
struct Checkpoint {
    /// What must be equal for a resume (JSON text): the numerics version (numerics_version.h),
    /// every resolved scene value and the --set overrides (and "threads": "any": the thread
    /// count changes nothing). Nothing that changes with a rebuild alone.
    std::string fingerprint;
    long checkpointEvery = 0;           ///< steps between checkpoints of the bake that wrote it
    MpsState solver;                    ///< solver state after step solver.step
    std::vector<cache::Frame> frames;   ///< frames stored so far (frame 0 = initial state)
    std::vector<std::string> probeRows; ///< the probes CSV row of each stored frame
    BakeTotals totals;
    std::int64_t writerPid = 0; ///< process that wrote it (for diagnostics)
};

/// Where the checkpoint of a bake to `cache` lives: `cache` + ".ckpt".
std::filesystem::path checkpointPath(const std::filesystem::path& cache);

/// Writes `c` to `path` atomically: to `path`.tmp-<pid>, flushed and fsynced, then renamed
/// over `path` (and the directory fsynced), so `path` always holds a whole checkpoint.
/// Returns the bytes written. Throws CheckpointError.
std::uint64_t writeCheckpoint(const std::filesystem::path& path, const Checkpoint& c);

/// Reads and checks a checkpoint. Throws CheckpointError naming the file when it is missing,
/// truncated, damaged (checksum), of another format version or inconsistent.
Checkpoint readCheckpoint(const std::filesystem::path& path);

/// Throws CheckpointError naming `path` and the first value that differs when the
/// fingerprint stored in a checkpoint is not `current`.
void checkFingerprint(const std::filesystem::path& path, const std::string& stored,
                      const std::string& current);

} // namespace swell::bake
