#pragma once
// Output files a reader never sees half-written: the content goes to a temporary name in the
// same folder, which is renamed onto the final name only once it is complete (rename is atomic
// within one file system), the pattern of cache::Writer. A failed write leaves no file under
// the final name (an older complete one stays) and no temporary behind.

#include <filesystem>
#include <functional>
#include <string>

namespace swell::runtime {

/// Calls `write(temporary)` with `<path>.tmp-<pid>` and renames it onto `path`. Whatever
/// `write` throws propagates after the temporary is removed; a failed rename throws
/// RuntimeError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` to `path` atomically. Throws RuntimeError naming `path` on I/O failure.
void writeTextAtomically(const std::filesystem::path& path, const std::string& text);

} // namespace swell::runtime
