#include "swell/cache/reader.h"

#include "format.h"
#include "swell/cache/error.h"
#include "swell/cache/json_depth.h"
#include "swell/cache/output_lock.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

namespace swell::cache {
namespace fs = std::filesystem;
using namespace format;

/// Owns the POSIX file descriptor the reader was opened with.
struct Reader::File {
    explicit File(const fs::path& p) : fd(::open(p.c_str(), O_RDONLY | O_CLOEXEC)) {}
    ~File() {
        if (fd >= 0)
            ::close(fd);
    }
    File(const File&) = delete;
    File& operator=(const File&) = delete;
    int get() const { return fd; }
    int fd;
};

namespace {

struct DCtxDeleter {
    void operator()(ZSTD_DCtx* c) const { ZSTD_freeDCtx(c); }
};
using DCtx = std::unique_ptr<ZSTD_DCtx, DCtxDeleter>;

/// Reads exactly `size` bytes at `offset`; false on a short read or error.
bool readAt(int fd, void* dst, std::size_t size, std::uint64_t offset) {
    auto* p = static_cast<std::uint8_t*>(dst);
    while (size > 0) {
        const ssize_t n = ::pread(fd, p, size, static_cast<off_t>(offset));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        p += n;
        size -= static_cast<std::size_t>(n);
        offset += static_cast<std::uint64_t>(n);
    }
    return true;
}

/// Decompresses, unshuffles, checksums and decodes frame `i` from its compressed bytes.
Frame decodeFrame(const fs::path& path, const Header& h, const FrameInfo& e, std::size_t i,
                  const std::uint8_t* compressed, ZSTD_DCtx* dctx, std::vector<std::uint8_t>& buf,
                  std::vector<std::uint8_t>& raw) {
    auto fail = [&](const std::string& what) {
        return CacheError(path.string() + ": frame " + std::to_string(i) + ": " + what);
    };
    const unsigned long long stated = ZSTD_getFrameContentSize(compressed, e.compressedSize);
    if (stated == ZSTD_CONTENTSIZE_ERROR)
        throw fail("compressed data is not a zstd frame");
    if (stated != e.rawSize)
        throw fail("zstd content size disagrees with the index (" + std::to_string(e.rawSize) +
                   " bytes expected)");
    const std::size_t frameSize = ZSTD_findFrameCompressedSize(compressed, e.compressedSize);
    if (ZSTD_isError(frameSize) || frameSize != e.compressedSize)
        throw fail("the record is not one zstd frame of the index's " +
                   std::to_string(e.compressedSize) + " bytes");
    buf.resize(e.rawSize);
    const std::size_t n =
        ZSTD_decompressDCtx(dctx, buf.data(), buf.size(), compressed, e.compressedSize);
    if (ZSTD_isError(n))
        throw fail(std::string("decompression failed: ") + ZSTD_getErrorName(n));
    if (n != e.rawSize)
        throw fail("decompressed to " + std::to_string(n) + " bytes, index says " +
                   std::to_string(e.rawSize));
    std::vector<std::uint8_t>* rec = &buf;
    if (h.shuffle) {
        shuffle(h.encoding, e.surfaceCount, e.splashCount, buf, raw, true);
        rec = &raw;
    }
    if (h.delta)
        delta(h.encoding, e.surfaceCount, e.splashCount, *rec, true);
    if (checksum(rec->data(), rec->size()) != e.checksum)
        throw fail("checksum mismatch (data damaged)");
    return decodeRecord(h, *rec, e.surfaceCount, e.splashCount);
}

/// Makes the CacheError of the file being opened: "<path>: <what>".
struct Failure {
    const fs::path& path;
    CacheError operator()(const std::string& what) const {
        return CacheError(path.string() + ": " + what);
    }
};

/// Refuses the temporary file of a write that has not finished (output_lock.h).
void rejectUnfinishedWrite(const fs::path& path, const Failure& fail) {
    if (const long pid = temporaryFileWriter(path); pid > 0) {
        throw fail("a temporary file of an unfinished write by process " + std::to_string(pid) +
                   (processExists(pid) ? " (still running)"
                                       : " (no longer running: the next bake to that output "
                                         "removes it)") +
                   ", not a cache; a cache appears under its own name only when complete");
    }
}

/// Reads the fixed header and its metadata and checks the magic, the format version (stored
/// in `version`), the sizes and the header checksum. Returns the header's bytes, fixed part
/// then metadata.
std::vector<std::uint8_t> readHeaderBytes(int fd, std::uint64_t fileSize, std::uint32_t& version,
                                          const Failure& fail) {
    if (fileSize < kFixedHeaderSize)
        throw fail("truncated: " + std::to_string(fileSize) + " bytes, shorter than the " +
                   std::to_string(kFixedHeaderSize) + "-byte header");
    std::vector<std::uint8_t> head(kFixedHeaderSize);
    if (!readAt(fd, head.data(), head.size(), 0))
        throw fail("cannot read the header");
    if (std::memcmp(head.data(), kMagic, sizeof kMagic) != 0)
        throw fail("not a swell cache (bad magic)");
    version = getField<std::uint32_t>(&head[kOffVersion]);
    if (version == 0 || version > kFormatVersion)
        throw fail("format version " + std::to_string(version) +
                   " is not readable by this program (reads up to " +
                   std::to_string(kFormatVersion) + ")");
    const auto metaLen = getField<std::uint32_t>(&head[kOffMetadataLength]);
    const auto headerSize = getField<std::uint32_t>(&head[kOffHeaderSize]);
    if (metaLen > kMaxMetadataBytes || headerSize != kFixedHeaderSize + metaLen)
        throw fail("header damaged: metadata length " + std::to_string(metaLen) +
                   " disagrees with header size " + std::to_string(headerSize));
    if (headerSize > fileSize)
        throw fail("truncated inside the header metadata");
    head.resize(headerSize);
    if (!readAt(fd, head.data() + kFixedHeaderSize, metaLen, kFixedHeaderSize))
        throw fail("cannot read the header metadata");
    if (headerChecksum(head) != getField<std::uint64_t>(&head[kOffHeaderChecksum]))
        throw fail("header checksum mismatch (header damaged, or the file was never finished)");
    return head;
}

/// Decodes the header fields from its checked bytes (readHeaderBytes) and checks the encoding,
/// the flags, the domain, dt, the frame interval and the metadata JSON.
Header decodeHeader(const std::vector<std::uint8_t>& head, const Failure& fail) {
    Header h;
    const auto enc = getField<std::uint32_t>(&head[kOffEncoding]);
    if (enc > static_cast<std::uint32_t>(Encoding::Quantized16))
        throw fail("unknown encoding " + std::to_string(enc));
    h.encoding = static_cast<Encoding>(enc);
    const auto flags = getField<std::uint32_t>(&head[kOffFlags]);
    if (flags & ~(kFlagShuffle | kFlagDelta))
        throw fail("unknown flags " + std::to_string(flags));
    h.shuffle = (flags & kFlagShuffle) != 0;
    h.delta = (flags & kFlagDelta) != 0;
    h.domain = {getField<float>(&head[kOffDomain]), getField<float>(&head[kOffDomain + 4]),
                getField<float>(&head[kOffDomain + 8]), getField<float>(&head[kOffDomain + 12])};
    const Domain& d = h.domain;
    if (!(std::isfinite(d.xMin) && std::isfinite(d.xMax) && std::isfinite(d.yMin) &&
          std::isfinite(d.yMax) && d.xMax > d.xMin && d.yMax > d.yMin))
        throw fail("header damaged: invalid domain bounds");
    h.dt = getField<double>(&head[kOffDt]);
    h.frameInterval = getField<std::uint32_t>(&head[kOffFrameInterval]);
    if (!(h.dt > 0.0 && std::isfinite(h.dt)) || h.frameInterval == 0)
        throw fail("header damaged: invalid dt or frame interval");
    h.compressionLevel = static_cast<int>(getField<std::uint32_t>(&head[kOffLevel]));
    h.seed = getField<std::uint64_t>(&head[kOffSeed]);
    h.metadataJson.assign(reinterpret_cast<const char*>(head.data() + kFixedHeaderSize),
                          head.size() - kFixedHeaderSize);
    if (const std::string deep = jsonDepthProblem(h.metadataJson); !deep.empty())
        throw fail("header metadata " + deep);
    const nlohmann::json meta = nlohmann::json::parse(h.metadataJson, nullptr, false);
    if (meta.is_discarded())
        throw fail("header metadata is not valid JSON");
    if (!meta.is_object())
        throw fail("header metadata is not a JSON object");
    return h;
}

/// Reads the frame index at `indexOffset` (count * 40 bytes, then its checksum), after
/// checking that it lies between the header and the end of the file and ends the file;
/// checks its checksum.
std::vector<std::uint8_t> readIndexBytes(int fd, std::uint64_t fileSize, std::uint64_t headerSize,
                                         std::uint64_t count, std::uint64_t indexOffset,
                                         const Failure& fail) {
    if (indexOffset < headerSize || indexOffset > fileSize)
        throw fail("index offset " + std::to_string(indexOffset) + " outside the file (" +
                   std::to_string(fileSize) + " bytes)");
    if (count > (fileSize - indexOffset) / kIndexEntrySize)
        throw fail("truncated: the index of " + std::to_string(count) +
                   " frames does not fit in the file");
    const std::uint64_t expectedSize = indexOffset + count * kIndexEntrySize + 8;
    if (fileSize != expectedSize)
        throw fail((fileSize < expectedSize ? "truncated: " : "trailing data: ") +
                   std::to_string(fileSize) + " bytes, the header implies " +
                   std::to_string(expectedSize));
    std::vector<std::uint8_t> index(count * kIndexEntrySize + 8);
    if (!readAt(fd, index.data(), index.size(), indexOffset))
        throw fail("cannot read the frame index");
    if (checksum(index.data(), count * kIndexEntrySize) !=
        getField<std::uint64_t>(&index[count * kIndexEntrySize]))
        throw fail("frame index checksum mismatch (index damaged)");
    return index;
}

/// Checks index entry `i` against its particle counts and the frame data, which runs from
/// the end of the previous frame (`expectedOffset`) up to the index (`indexOffset`).
void checkIndexEntry(const FrameInfo& e, std::size_t i, Encoding encoding,
                     std::uint64_t expectedOffset, std::uint64_t indexOffset, const Failure& fail) {
    auto bad = [&](const std::string& what) {
        return fail("frame " + std::to_string(i) + ": " + what);
    };
    const std::uint64_t expectRaw = rawRecordSize(encoding, e.surfaceCount, e.splashCount);
    if (e.rawSize != expectRaw)
        throw bad("raw size " + std::to_string(e.rawSize) + " disagrees with " +
                  std::to_string(e.surfaceCount) + " surface and " + std::to_string(e.splashCount) +
                  " splash particles (" + std::to_string(expectRaw) + " bytes)");
    if (e.rawSize > kMaxRawFrameBytes)
        throw bad("raw size " + std::to_string(e.rawSize) +
                  " bytes exceeds the 256 MiB frame limit");
    if (e.compressedSize == 0 || e.compressedSize > ZSTD_compressBound(e.rawSize))
        throw bad("compressed size " + std::to_string(e.compressedSize) +
                  " impossible for raw size " + std::to_string(e.rawSize));
    if (!rawSizeFits(e.rawSize, e.compressedSize))
        throw bad("raw size " + std::to_string(e.rawSize) + " from " +
                  std::to_string(e.compressedSize) +
                  " compressed bytes is beyond the format's bound of 1 MiB + 1024 x the "
                  "compressed size");
    if (e.offset > indexOffset || e.compressedSize > indexOffset - e.offset)
        throw bad("offset " + std::to_string(e.offset) + " + size " +
                  std::to_string(e.compressedSize) + " extends past the frame data (ends at " +
                  std::to_string(indexOffset) + ")");
    if (e.offset < expectedOffset)
        throw bad(i == 0 ? "starts inside the header" : "overlaps frame " + std::to_string(i - 1));
    if (e.offset > expectedOffset)
        throw bad("unaccounted gap of " + std::to_string(e.offset - expectedOffset) +
                  " bytes before the frame");
}

/// Decodes the `count` entries of the frame index and checks that the frames tile the data
/// between the header (`headerSize` bytes) and the index, in order, with no gaps.
std::vector<FrameInfo> decodeIndex(const std::vector<std::uint8_t>& index, std::uint64_t count,
                                   Encoding encoding, std::uint64_t headerSize,
                                   std::uint64_t indexOffset, const Failure& fail) {
    std::vector<FrameInfo> entries(count);
    std::uint64_t expectedOffset = headerSize;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* p = &index[i * kIndexEntrySize];
        FrameInfo& e = entries[i];
        e = {getField<std::uint64_t>(p),      getField<std::uint64_t>(p + 8),
             getField<std::uint64_t>(p + 16), getField<std::uint32_t>(p + 24),
             getField<std::uint32_t>(p + 28), getField<std::uint64_t>(p + 32)};
        checkIndexEntry(e, i, encoding, expectedOffset, indexOffset, fail);
        expectedOffset = e.offset + e.compressedSize;
    }
    if (expectedOffset != indexOffset)
        throw fail(std::to_string(indexOffset - expectedOffset) +
                   " unaccounted bytes between the last frame and the index");
    return entries;
}

} // namespace

Reader::Reader(fs::path path) : m_path(std::move(path)) {
    const Failure fail{m_path};
    rejectUnfinishedWrite(m_path, fail);
    auto file = std::make_shared<const File>(m_path);
    const File& fd = *file;
    if (fd.get() < 0)
        throw fail(std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
        throw fail("not a regular file");
    m_fileSize = static_cast<std::uint64_t>(st.st_size);

    const std::vector<std::uint8_t> head = readHeaderBytes(fd.get(), m_fileSize, m_version, fail);
    m_header = decodeHeader(head, fail);

    // The frame index, at the end of the file.
    const std::uint64_t headerSize = head.size();
    const auto count = getField<std::uint64_t>(&head[kOffFrameCount]);
    const auto indexOffset = getField<std::uint64_t>(&head[kOffIndexOffset]);
    const std::vector<std::uint8_t> index =
        readIndexBytes(fd.get(), m_fileSize, headerSize, count, indexOffset, fail);
    m_index = decodeIndex(index, count, m_header.encoding, headerSize, indexOffset, fail);
    m_file = std::move(file);
}

Frame Reader::readFrame(std::size_t i) const {
    const FrameInfo& e = m_index.at(i);
    std::vector<std::uint8_t> compressed(e.compressedSize);
    if (!readAt(m_file->get(), compressed.data(), compressed.size(), e.offset))
        throw CacheError(m_path.string() + ": frame " + std::to_string(i) +
                         ": cannot read (file truncated since it was opened)");
    DCtx dctx(ZSTD_createDCtx());
    std::vector<std::uint8_t> buf, raw;
    return decodeFrame(m_path, m_header, e, i, compressed.data(), dctx.get(), buf, raw);
}

std::vector<Frame> Reader::readAll() const {
    std::vector<Frame> frames;
    if (m_index.empty())
        return frames;
    // One read of the whole data section, then decode frame by frame.
    const std::uint64_t begin = m_index.front().offset;
    const std::uint64_t end = m_index.back().offset + m_index.back().compressedSize;
    std::vector<std::uint8_t> data(end - begin);
    if (!readAt(m_file->get(), data.data(), data.size(), begin))
        throw CacheError(m_path.string() +
                         ": cannot read frame data (file truncated since it was opened)");
    DCtx dctx(ZSTD_createDCtx());
    std::vector<std::uint8_t> buf, raw;
    frames.reserve(m_index.size());
    for (std::size_t i = 0; i < m_index.size(); ++i)
        frames.push_back(decodeFrame(m_path, m_header, m_index[i], i,
                                     data.data() + (m_index[i].offset - begin), dctx.get(), buf,
                                     raw));
    return frames;
}

} // namespace swell::cache
