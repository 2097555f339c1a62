#pragma once
// The exit statuses of every swell program (swell-bake, swell-cache, swell-play, swell-validate,
// swell-mps-bench, swell-capi-bench); README "Exit statuses" prints the same table.

#include <exception>
#include <stdexcept>

#include "swell/cache/error.h"
#include "swell/cache/output_lock.h"

namespace swell::cli {

enum ExitCode : int {
    kExitOk = 0,          ///< done
    kExitFailed = 1,      ///< the run failed: I/O, GPU / GL, out of memory, anything not below
    kExitBadInput = 2,    ///< a bad command line, scene or parameter, or a size that cannot fit
    kExitDiverged = 3,    ///< the simulation diverged or its detector stopped it
    kExitBadCache = 4,    ///< a cache cannot be read or written: missing, damaged, truncated
    kExitCheckpoint = 5,  ///< a checkpoint cannot be used for --resume
    kExitBusy = 6,        ///< the output is being written by another process
    kExitMissed = 7,      ///< a comparison ran and missed its bound (bench --reference)
    kExitCancelled = 130, ///< stopped by SIGINT or SIGTERM
};

/// The status for an error every program may meet; bake's own (diverged, checkpoint,
/// cancelled) are mapped by swell-bake itself.
inline int exitCodeFor(const std::exception& e) {
    if (dynamic_cast<const cache::OutputBusy*>(&e) != nullptr)
        return kExitBusy;
    if (dynamic_cast<const cache::CacheError*>(&e) != nullptr)
        return kExitBadCache;
    if (dynamic_cast<const std::invalid_argument*>(&e) != nullptr)
        return kExitBadInput;
    return kExitFailed;
}

} // namespace swell::cli
