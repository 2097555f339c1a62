#pragma once
// Streaming cache writer: frames go to disk as they come; the file appears at
// its final path only on finish() (written to a temporary name, then renamed).

#include "swell/cache/frame.h"
#include "swell/cache/header.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace swell::cache {

class Writer {
public:
    /// Opens `<path>.tmp-<pid>` next to `path`. Throws CacheError.
    Writer(std::filesystem::path path, Header header);
    /// Without finish(), removes the temporary file; `path` is left untouched.
    ~Writer();
    Writer(const Writer&) = delete;
    Writer& operator=(const Writer&) = delete;

    /// Compresses and appends one frame. Throws CacheError (I/O) or
    /// std::invalid_argument (counts not multiples of 2 / 4, non-finite values,
    /// positions outside the domain when quantizing).
    void addFrame(const Frame& frame);
    /// Writes the index, syncs, and atomically renames onto `path`.
    void finish();

    std::size_t frameCount() const { return m_index.size(); }
    std::uint64_t bytesWritten() const { return m_offset; }
    const std::filesystem::path& path() const { return m_path; }

private:
    void writeBytes(const void* data, std::size_t size);

    std::filesystem::path m_path;
    std::filesystem::path m_tmpPath;
    Header m_header;
    std::FILE* m_file = nullptr;
    std::uint64_t m_offset = 0;
    std::vector<FrameInfo> m_index; // 40 bytes per frame; frame data is not kept
    std::vector<std::uint8_t> m_raw, m_shuffled, m_compressed; // reused buffers
    void* m_cctx = nullptr;
    bool m_finished = false;
};

} // namespace swell::cache
