#pragma once
// One writer per output (README.md, "Resuming a bake"): an advisory lock (fcntl F_SETLK) on
// `<output>.lock` beside the output, taken before a bake reads its checkpoint or writes
// anything and held until it ends. The kernel releases it when the process dies, so a bake
// killed with SIGKILL never leaves a lock that blocks the next one. A second process gets
// OutputBusy, naming the holder's PID (from F_GETLK, not from the file's contents).

#include <filesystem>

#include "swell/cache/error.h"

namespace swell::cache {

/// The output is being written by another process. The message names the output, the
/// holder's PID and the lock file, on one line.
class OutputBusy : public CacheError {
public:
    using CacheError::CacheError;
};

/// Where the lock of `output` lives: `output` + ".lock".
std::filesystem::path lockPath(const std::filesystem::path& output);

/// Holds the lock of one output for its lifetime; the lock file is removed on release.
class OutputLock {
public:
    /// Takes the lock without waiting. Throws OutputBusy when another process holds it,
    /// CacheError when the lock file cannot be created.
    explicit OutputLock(const std::filesystem::path& output);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    std::filesystem::path m_path;
    int m_fd = -1;
};

/// Where this process writes `path` before renaming it into place: `<path>.tmp-<pid>`, the one
/// name every swell writer uses (and temporaryFileWriter reads).
std::filesystem::path temporaryPath(const std::filesystem::path& path);

/// The PID in the name of a temporary file `<name>.tmp-<pid>` (as every swell writer names
/// them), or 0 when `path` is not named so.
long temporaryFileWriter(const std::filesystem::path& path);

/// True when a process `pid` exists (kill(pid, 0) does not fail with ESRCH).
bool processExists(long pid);

} // namespace swell::cache
