#pragma once
// Cache reader: validates the header and the whole frame index on open, then
// decodes any frame on demand. Every defect throws CacheError naming the file,
// the frame (if any) and what is wrong.

#include "swell/cache/frame.h"
#include "swell/cache/header.h"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace swell::cache {

class Reader {
public:
    /// Opens and validates. Throws CacheError.
    explicit Reader(std::filesystem::path path);

    const std::filesystem::path& path() const { return m_path; }
    const Header& header() const { return m_header; }
    std::uint32_t version() const { return m_version; }
    std::size_t frameCount() const { return m_index.size(); }
    const FrameInfo& frameInfo(std::size_t i) const { return m_index.at(i); }
    std::uint64_t fileSize() const { return m_fileSize; }

    /// Decodes frame `i` (random access). Throws CacheError (damage) or
    /// std::out_of_range (i >= frameCount()).
    Frame readFrame(std::size_t i) const;
    /// Decodes every frame in order.
    std::vector<Frame> readAll() const;

private:
    struct File; // open descriptor, shared by copies; frames are read with pread
    std::shared_ptr<const File> m_file;
    std::filesystem::path m_path;
    Header m_header;
    std::uint32_t m_version = 0;
    std::uint64_t m_fileSize = 0;
    std::vector<FrameInfo> m_index;
};

} // namespace swell::cache
