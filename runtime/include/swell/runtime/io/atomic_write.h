#pragma once
// Output files a reader never sees half-written: the content goes to a temporary name in the
// same folder, which is renamed onto the final name only once it is complete (rename is atomic
// within one file system), the pattern of cache::Writer. A failed write leaves no file under
// the final name (an older complete one stays) and no temporary behind.

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace swell::runtime {

/// Defers the renames of writeAtomically on this thread until commit(), for a run that writes
/// a folder of files (swell-play render, heights): the previous files stay untouched until
/// every new one is complete, and a run that fails (no commit, an exception) removes its
/// temporaries in the destructor, so the folder is exactly as before. One at a time per thread.
class DeferredRenames {
public:
    DeferredRenames();
    ~DeferredRenames();
    DeferredRenames(const DeferredRenames&) = delete;
    DeferredRenames& operator=(const DeferredRenames&) = delete;
    /// Renames every temporary onto its name, in the order they were written, and ends the
    /// deferral. Throws RuntimeError naming the file when a rename fails.
    void commit();
    /// True until commit().
    bool deferring() const { return m_active; }
    /// After commit(): removes from each folder a file was written to every numbered file of
    /// swell's output sequences (frame_NNNNN.png, height_NNNNN.png|exr, normal_NNNNN.exr,
    /// disp_NNNN.exr, surface_NNNNN.ply, splashes_NNNNN.ply) that this run did not write, so a
    /// shorter run leaves no frames of an older one beside its own.
    void removeStaleSequenceFiles() const;

private:
    friend void writeAtomically(const std::filesystem::path&,
                                const std::function<void(const std::filesystem::path&)>&);
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> m_pending; // tmp, path
    std::vector<std::filesystem::path> m_committed;
    bool m_active = true;
};

/// The output folders of a run, made when missing: a run that fails before keep() (the
/// destructor without it) removes those it made, once they are empty again, so a failed run
/// leaves no empty output folder behind. Folders that were there stay, whatever happens.
class NewFolders {
public:
    NewFolders() = default;
    NewFolders(const NewFolders&) = delete;
    NewFolders& operator=(const NewFolders&) = delete;
    ~NewFolders();
    /// Creates `folder` and its missing parents. Throws RuntimeError naming it on failure.
    void make(const std::filesystem::path& folder);
    /// The run succeeded: its folders stay.
    void keep() { m_made.clear(); }

private:
    std::vector<std::filesystem::path> m_made; // in the order made, parents first
};

/// Calls `write(temporary)` with `<path>.tmp-<pid>` and renames it onto `path` (at once, or
/// at DeferredRenames::commit() while one is active on this thread). Whatever
/// `write` throws propagates after the temporary is removed; a failed rename throws
/// RuntimeError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write);

/// Writes `bytes` to `path` atomically, through cache::writeFile (so a full disk, an I/O error
/// or an injected fault, SWELL_FAULT_INJECT, is reported). Throws RuntimeError naming `path`
/// and the reason; `path` then keeps what it held before and no temporary is left.
void writeBytesAtomically(const std::filesystem::path& path, std::string_view bytes);

/// Writes `text` to `path` atomically (writeBytesAtomically).
void writeTextAtomically(const std::filesystem::path& path, const std::string& text);

} // namespace swell::runtime
