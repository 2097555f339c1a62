#include "swell/cache/writer.h"

#include "format.h"
#include "swell/cache/checked_write.h"
#include "swell/cache/error.h"
#include "swell/cache/output_lock.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <zstd.h>

namespace swell::cache {
namespace fs = std::filesystem;

namespace {

std::string describe(const fs::path& p, const std::string& what) {
    return p.string() + ": " + what;
}

void validateHeader(const Header& h) {
    const Domain& d = h.domain;
    if (!(std::isfinite(d.xMin) && std::isfinite(d.xMax) && std::isfinite(d.yMin) &&
          std::isfinite(d.yMax)) ||
        !(d.xMax > d.xMin) || !(d.yMax > d.yMin))
        throw std::invalid_argument("cache header: domain bounds must be finite with max > min");
    if (!(h.dt > 0.0) || !std::isfinite(h.dt))
        throw std::invalid_argument("cache header: dt must be positive and finite");
    if (h.frameInterval == 0)
        throw std::invalid_argument("cache header: frame_interval must be at least 1");
    if (h.compressionLevel < 1 || h.compressionLevel > ZSTD_maxCLevel())
        throw std::invalid_argument("cache header: compression level must be in 1.." +
                                    std::to_string(ZSTD_maxCLevel()));
    if (h.metadataJson.size() > format::kMaxMetadataBytes)
        throw std::invalid_argument("cache header: metadata JSON larger than 16 MiB");
}

void validateFrame(const Header& h, const Frame& f, std::size_t index) {
    const auto where = [&] { return "cache frame " + std::to_string(index) + ": "; };
    if (f.surface.size() % 2 != 0)
        throw std::invalid_argument(where() + "surface array length is not a multiple of 2");
    if (f.splash.size() % 4 != 0)
        throw std::invalid_argument(where() + "splash array length is not a multiple of 4");
    if (f.surfaceCount() > UINT32_MAX / 2 || f.splashCount() > UINT32_MAX / 4 ||
        format::rawRecordSize(h.encoding, f.surfaceCount(), f.splashCount()) >
            format::kMaxRawFrameBytes)
        throw std::invalid_argument(where() + "frame larger than 256 MiB");
    const Domain& d = h.domain;
    for (std::size_t i = 0; i < f.surfaceCount(); ++i)
        if (!d.contains(f.surface[2 * i], f.surface[2 * i + 1]))
            throw std::invalid_argument(where() + "surface particle " + std::to_string(i) +
                                        " is outside the domain bounds or not finite");
    for (std::size_t i = 0; i < f.splashCount(); ++i) {
        if (!d.contains(f.splash[4 * i], f.splash[4 * i + 1]))
            throw std::invalid_argument(where() + "splash particle " + std::to_string(i) +
                                        " is outside the domain bounds or not finite");
        if (!std::isfinite(f.splash[4 * i + 2]) || !std::isfinite(f.splash[4 * i + 3]))
            throw std::invalid_argument(where() + "splash particle " + std::to_string(i) +
                                        " has a non-finite velocity");
    }
}

} // namespace

Writer::Writer(fs::path path, Header header)
    : m_path(std::move(path)), m_header(std::move(header)) {
    validateHeader(m_header);
    m_tmpPath = temporaryPath(m_path);
    m_file = std::fopen(m_tmpPath.c_str(), "w+b");
    if (!m_file)
        throw CacheError(describe(m_path, std::string("cannot create temporary file ") +
                                              m_tmpPath.string() + ": " + std::strerror(errno)));
    m_cctx = ZSTD_createCCtx();
    if (!m_cctx) {
        std::fclose(m_file);
        std::error_code ec;
        fs::remove(m_tmpPath, ec);
        throw CacheError(describe(m_path, "cannot create zstd context"));
    }
    ZSTD_CCtx_setParameter(static_cast<ZSTD_CCtx*>(m_cctx), ZSTD_c_compressionLevel,
                           m_header.compressionLevel);
    ZSTD_CCtx_setParameter(static_cast<ZSTD_CCtx*>(m_cctx), ZSTD_c_contentSizeFlag, 1);

    // Fixed header with frame count, index offset and checksum still zero; patched by finish().
    std::vector<std::uint8_t> head(format::kFixedHeaderSize, 0);
    std::memcpy(head.data(), format::kMagic, sizeof format::kMagic);
    using namespace format;
    putField<std::uint32_t>(&head[kOffVersion], kFormatVersion);
    putField<std::uint32_t>(
        &head[kOffHeaderSize],
        static_cast<std::uint32_t>(kFixedHeaderSize + m_header.metadataJson.size()));
    putField<std::uint32_t>(&head[kOffEncoding], static_cast<std::uint32_t>(m_header.encoding));
    putField<std::uint32_t>(&head[kOffFlags], (m_header.shuffle ? kFlagShuffle : 0u) |
                                                  (m_header.delta ? kFlagDelta : 0u));
    putField<float>(&head[kOffDomain + 0], m_header.domain.xMin);
    putField<float>(&head[kOffDomain + 4], m_header.domain.yMin);
    putField<float>(&head[kOffDomain + 8], m_header.domain.xMax);
    putField<float>(&head[kOffDomain + 12], m_header.domain.yMax);
    putField<double>(&head[kOffDt], m_header.dt);
    putField<std::uint32_t>(&head[kOffFrameInterval], m_header.frameInterval);
    putField<std::uint32_t>(&head[kOffLevel],
                            static_cast<std::uint32_t>(m_header.compressionLevel));
    putField<std::uint64_t>(&head[kOffSeed], m_header.seed);
    putField<float>(&head[kOffMaxError], m_header.maxPositionError());
    putField<std::uint32_t>(&head[kOffMetadataLength],
                            static_cast<std::uint32_t>(m_header.metadataJson.size()));
    try {
        writeBytes(head.data(), head.size());
        writeBytes(m_header.metadataJson.data(), m_header.metadataJson.size());
    } catch (...) {
        // No destructor runs for a constructor that throws: clean up here (a full disk
        // already at the header must not leave the temporary behind).
        ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(m_cctx));
        std::fclose(m_file);
        std::error_code ec;
        fs::remove(m_tmpPath, ec);
        throw;
    }
}

Writer::~Writer() {
    if (m_cctx)
        ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(m_cctx));
    if (m_file)
        std::fclose(m_file);
    if (!m_finished) {
        std::error_code ec;
        fs::remove(m_tmpPath, ec); // nothing at the final path was touched
    }
}

void Writer::writeBytes(const void* data, std::size_t size) {
    if (const int err = size ? writeAll(m_file, data, size, m_tmpPath) : 0; err != 0)
        throw CacheError(describe(m_path, "cannot write " + m_tmpPath.filename().string() + ": " +
                                              std::strerror(err) + "; no cache written"));
    m_offset += size;
}

void Writer::addFrame(const Frame& frame) {
    if (m_finished)
        throw std::logic_error("swell::cache::Writer::addFrame after finish()");
    validateFrame(m_header, frame, m_index.size());
    const auto ns = static_cast<std::uint32_t>(frame.surfaceCount());
    const auto nsp = static_cast<std::uint32_t>(frame.splashCount());

    format::encodeRecord(m_header, frame, m_raw);
    FrameInfo info;
    info.offset = m_offset;
    info.rawSize = m_raw.size();
    info.surfaceCount = ns;
    info.splashCount = nsp;
    info.checksum = format::checksum(m_raw.data(), m_raw.size());

    if (m_header.delta)
        format::delta(m_header.encoding, ns, nsp, m_raw, false); // m_raw is scratch from here
    const std::vector<std::uint8_t>* src = &m_raw;
    if (m_header.shuffle) {
        format::shuffle(m_header.encoding, ns, nsp, m_raw, m_shuffled, false);
        src = &m_shuffled;
    }
    m_compressed.resize(ZSTD_compressBound(src->size()));
    const std::size_t n = ZSTD_compress2(static_cast<ZSTD_CCtx*>(m_cctx), m_compressed.data(),
                                         m_compressed.size(), src->data(), src->size());
    if (ZSTD_isError(n))
        throw CacheError(
            describe(m_path, std::string("zstd compression failed: ") + ZSTD_getErrorName(n)));
    info.compressedSize = n;
    if (!format::rawSizeFits(info.rawSize, n))
        throw CacheError(describe(
            m_path, "frame " + std::to_string(m_index.size()) + ": " +
                        std::to_string(info.rawSize) + " raw bytes compress to " +
                        std::to_string(n) +
                        ", beyond the format's bound of 1 MiB + 1024 x the compressed size: "
                        "not particle data"));
    writeBytes(m_compressed.data(), n);
    m_index.push_back(info);
}

void Writer::finish() {
    if (m_finished)
        return;
    using namespace format;
    const std::uint64_t indexOffset = m_offset;
    std::vector<std::uint8_t> index(m_index.size() * kIndexEntrySize);
    for (std::size_t i = 0; i < m_index.size(); ++i) {
        std::uint8_t* p = &index[i * kIndexEntrySize];
        const FrameInfo& e = m_index[i];
        putField<std::uint64_t>(p, e.offset);
        putField<std::uint64_t>(p + 8, e.compressedSize);
        putField<std::uint64_t>(p + 16, e.rawSize);
        putField<std::uint32_t>(p + 24, e.surfaceCount);
        putField<std::uint32_t>(p + 28, e.splashCount);
        putField<std::uint64_t>(p + 32, e.checksum);
    }
    writeBytes(index.data(), index.size());
    const std::uint64_t indexSum = checksum(index.data(), index.size());
    writeBytes(&indexSum, sizeof indexSum);

    // Patch frame count and index offset, then checksum the header + metadata.
    std::uint8_t patch[16];
    putField<std::uint64_t>(patch, m_index.size());
    putField<std::uint64_t>(patch + 8, indexOffset);
    std::vector<std::uint8_t> head(kFixedHeaderSize + m_header.metadataJson.size());
    int err = 0;
    auto fail = [&](const char* what) {
        throw CacheError(describe(m_path, std::string(what) + ": " +
                                              std::strerror(err ? err : errno) +
                                              "; no cache written"));
    };
    if (std::fflush(m_file) != 0 || std::fseek(m_file, kOffFrameCount, SEEK_SET) != 0 ||
        (err = writeAll(m_file, patch, sizeof patch, m_tmpPath)) != 0 || std::fflush(m_file) != 0 ||
        std::fseek(m_file, 0, SEEK_SET) != 0 ||
        std::fread(head.data(), 1, head.size(), m_file) != head.size())
        fail("cannot patch header");
    const std::uint64_t headSum = headerChecksum(head);
    if (std::fseek(m_file, kOffHeaderChecksum, SEEK_SET) != 0 ||
        (err = writeAll(m_file, &headSum, sizeof headSum, m_tmpPath)) != 0 ||
        std::fflush(m_file) != 0 || ::fsync(::fileno(m_file)) != 0)
        fail("cannot finish header");
    const int closed = std::fclose(m_file);
    m_file = nullptr;
    if (closed != 0)
        fail("cannot close the temporary file");

    std::error_code ec;
    fs::rename(m_tmpPath, m_path, ec); // atomic: readers see the old file or the whole new one
    if (ec)
        throw CacheError(describe(m_path, "cannot rename temporary file: " + ec.message()));
    const fs::path dir = m_path.has_parent_path() ? m_path.parent_path() : fs::path(".");
    if (int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY); dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    m_finished = true;
}

} // namespace swell::cache
