#pragma once
// Every byte swell writes to a file goes through writeAll (the cache writer, checkpoints,
// height and render exports, JSON sidecars), so a full disk or an I/O error is reported the
// same way at every write site, and can be provoked in tests without a full disk: the
// environment variable SWELL_FAULT_INJECT=enospc:after=N (or eio:after=N) makes the writes of
// a process fail with ENOSPC (EIO) once N bytes have been written in all, as a disk that fills
// up does (the write that crosses N writes its first bytes, then fails; every later one fails).
// With ":match=TEXT" appended only files whose path contains TEXT count and fail (one write
// site at a time: "match=.ckpt", "match=render.json").

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace swell::cache {

/// Writes all `size` bytes of `data` to `file`. Returns 0, or the errno of the failure (a real
/// one, or an injected ENOSPC / EIO); callers name the file in their error. Throws only
/// std::invalid_argument, for a malformed SWELL_FAULT_INJECT.
/// `path` names the file (for the injected fault's match).
int writeAll(std::FILE* file, const void* data, std::size_t size,
             const std::filesystem::path& path);

/// Writes `size` bytes of `data` to a new file at `path` (truncating one that exists), flushes
/// and fsyncs it. Returns 0 or the errno of the failure; on failure the file may be partial
/// (callers write to a temporary name and remove it).
int writeFile(const std::filesystem::path& path, const void* data, std::size_t size);

/// What replaceFile did: error 0, or the errno of the failed step and that step's name
/// ("write" the temporary, "rename" it over the file), for the caller's message.
struct ReplaceResult {
    int error = 0;
    const char* step = "";
    std::filesystem::path temporary; ///< the temporary name it wrote (removed on failure)
};

/// Replaces the file at `path` with `size` bytes of `data`, whole or not at all: writes them to
/// temporaryPath(path) with writeFile, renames that over `path` and fsyncs the folder, so the
/// rename itself survives a power cut. On failure the temporary is removed and `path` keeps
/// what it held (or stays absent).
ReplaceResult replaceFile(const std::filesystem::path& path, const void* data, std::size_t size);

/// An injected fault: writes to files whose path contains `match` fail with `error` (ENOSPC,
/// EIO) once `afterBytes` bytes have been written to such files.
struct WriteFault {
    int error = 0;
    std::uint64_t afterBytes = 0;
    std::string match; ///< empty: every file
};

/// Arms `fault` (tests), replacing what SWELL_FAULT_INJECT armed; disarmWriteFault() ends it.
void armWriteFault(const WriteFault& fault);
void disarmWriteFault();

/// Parses a SWELL_FAULT_INJECT value ("enospc:after=N" or "eio:after=N", then optionally
/// ":match=TEXT"); throws std::invalid_argument naming the variable otherwise.
WriteFault parseWriteFault(const std::string& spec);

} // namespace swell::cache
