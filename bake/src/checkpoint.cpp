#include "swell/bake/checkpoint.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <span>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <xxhash.h>
#include <zstd.h>

#include "swell/cache/byte_fields.h"
#include "swell/cache/checked_write.h"
#include "swell/cache/json_depth.h"

namespace swell::bake {
namespace {

namespace fs = std::filesystem;
using cache::getField;
using cache::putField;

// Header: magic, u32 version, u32 flags (0), u64 payload bytes (compressed), u64 payload
// bytes (raw), u64 XXH3-64 of the compressed payload, u64 XXH3-64 of the 40 bytes before it.
constexpr std::uint8_t kMagic[8] = {0x89, 'S', 'W', 'K', '\r', '\n', 0x1a, '\n'};
constexpr std::uint32_t kVersion = 3;       // 2: the sub-step counters; 3: water removed, spills
constexpr std::uint32_t kOldestVersion = 2; // read as having removed and spilled no water
constexpr std::size_t kHeaderSize = 48;
constexpr std::uint64_t kMaxRawPayload = std::uint64_t{64}
                                         << 30; // 64 GiB: a damaged size fails fast
constexpr int kLevel = 3;

std::string where(const fs::path& p) {
    return p.string();
}

/// Little-endian payload writer (the project is little-endian only, as the cache format).
class Out {
public:
    template <class T> void pod(T v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
        m_bytes.insert(m_bytes.end(), b, b + sizeof(T));
    }
    template <class T> void vec(const std::vector<T>& v) {
        pod<std::uint64_t>(v.size());
        const auto* b = reinterpret_cast<const std::uint8_t*>(v.data());
        m_bytes.insert(m_bytes.end(), b, b + v.size() * sizeof(T));
    }
    void str(const std::string& s) {
        pod<std::uint64_t>(s.size());
        m_bytes.insert(m_bytes.end(), s.begin(), s.end());
    }
    std::vector<std::uint8_t>& bytes() { return m_bytes; }

private:
    std::vector<std::uint8_t> m_bytes;
};

/// Bounds-checked reader of the payload; any overrun is damage.
class In {
public:
    In(std::span<const std::uint8_t> b, const fs::path& path) : m_b(b), m_path(path) {}
    template <class T> T pod() {
        need(sizeof(T));
        T v;
        std::memcpy(&v, m_b.data() + m_pos, sizeof(T));
        m_pos += sizeof(T);
        return v;
    }
    template <class T> std::vector<T> vec() {
        const std::uint64_t n = pod<std::uint64_t>();
        if (n > (m_b.size() - m_pos) / sizeof(T))
            damaged("an array runs past the end of the payload");
        std::vector<T> v(static_cast<std::size_t>(n));
        if (!v.empty())
            std::memcpy(v.data(), m_b.data() + m_pos, v.size() * sizeof(T));
        m_pos += v.size() * sizeof(T);
        return v;
    }
    std::string str() {
        const std::uint64_t n = pod<std::uint64_t>();
        need(n);
        std::string s(reinterpret_cast<const char*>(m_b.data() + m_pos),
                      static_cast<std::size_t>(n));
        m_pos += static_cast<std::size_t>(n);
        return s;
    }
    void end() const {
        if (m_pos != m_b.size())
            damaged(fmt::format("{} unread bytes after the payload", m_b.size() - m_pos));
    }
    [[noreturn]] void damaged(const std::string& what) const {
        throw CheckpointError(fmt::format("{}: damaged checkpoint: {}", where(m_path), what));
    }

private:
    void need(std::uint64_t n) const {
        if (n > m_b.size() - m_pos)
            damaged("the payload ends early");
    }
    std::span<const std::uint8_t> m_b;
    std::size_t m_pos = 0;
    const fs::path& m_path;
};

void putParticles(Out& o, const Particles& p) {
    o.vec(p.x);
    o.vec(p.y);
    o.vec(p.vx);
    o.vec(p.vy);
    o.vec(p.p);
    o.vec(p.n);
    o.vec(p.kind);
}

Particles getParticles(In& in) {
    Particles p;
    p.x = in.vec<double>();
    p.y = in.vec<double>();
    p.vx = in.vec<double>();
    p.vy = in.vec<double>();
    p.p = in.vec<double>();
    p.n = in.vec<double>();
    p.kind = in.vec<ParticleKind>();
    if (!p.consistent())
        in.damaged("particle arrays differ in length");
    for (ParticleKind k : p.kind) {
        if (k != ParticleKind::Water && k != ParticleKind::Wall && k != ParticleKind::Dummy) {
            in.damaged("unknown particle kind");
        }
    }
    return p;
}

std::vector<std::uint8_t> encodePayload(const Checkpoint& c) {
    Out o;
    o.str(c.fingerprint);
    o.pod<std::int64_t>(c.checkpointEvery);
    o.pod<std::int64_t>(c.writerPid);
    const MpsState& s = c.solver;
    o.pod<std::int64_t>(s.step);
    o.pod<double>(s.time);
    o.pod<double>(s.lastMaxSpeed);
    putParticles(o, s.particles);
    o.vec(s.neighborX);
    o.vec(s.neighborY);
    o.vec(s.wallRestX);
    const BakeTotals& t = c.totals;
    o.pod(t.surface);
    o.pod(t.splash);
    o.pod(t.keptMax);
    o.pod(t.rawBytes);
    o.pod(t.solverSeconds);
    o.pod(t.ppeIterations);
    o.pod(t.maxCourant);
    o.pod(t.recycled);
    o.pod(t.splitSteps);
    o.pod(t.substeps);
    o.pod<std::uint64_t>(c.frames.size());
    for (const cache::Frame& f : c.frames) {
        o.vec(f.surface);
        o.vec(f.splash);
    }
    o.pod<std::uint64_t>(c.probeRows.size());
    for (const std::string& r : c.probeRows)
        o.str(r);
    // Version 3 appends:
    o.vec(s.removedWater);
    o.pod(t.spilled);
    o.pod(t.firstSpillTime);
    return std::move(o.bytes());
}

Checkpoint decodePayload(std::span<const std::uint8_t> raw, const fs::path& path,
                         std::uint32_t version) {
    In in(raw, path);
    Checkpoint c;
    c.fingerprint = in.str();
    c.checkpointEvery = static_cast<long>(in.pod<std::int64_t>());
    c.writerPid = in.pod<std::int64_t>();
    MpsState& s = c.solver;
    s.step = static_cast<long>(in.pod<std::int64_t>());
    s.time = in.pod<double>();
    s.lastMaxSpeed = in.pod<double>();
    s.particles = getParticles(in);
    s.neighborX = in.vec<double>();
    s.neighborY = in.vec<double>();
    s.wallRestX = in.vec<double>();
    BakeTotals& t = c.totals;
    t.surface = in.pod<double>();
    t.splash = in.pod<double>();
    t.keptMax = in.pod<std::uint64_t>();
    t.rawBytes = in.pod<std::uint64_t>();
    t.solverSeconds = in.pod<double>();
    t.ppeIterations = in.pod<double>();
    t.maxCourant = in.pod<double>();
    t.recycled = in.pod<std::uint64_t>();
    t.splitSteps = in.pod<std::uint64_t>();
    t.substeps = in.pod<std::uint64_t>();
    const std::uint64_t frames = in.pod<std::uint64_t>();
    if (frames > raw.size())
        in.damaged("impossible frame count");
    c.frames.resize(static_cast<std::size_t>(frames));
    for (cache::Frame& f : c.frames) {
        f.surface = in.vec<float>();
        f.splash = in.vec<float>();
        if (f.surface.size() % 2 != 0 || f.splash.size() % 4 != 0)
            in.damaged("a frame has a partial particle");
    }
    const std::uint64_t rows = in.pod<std::uint64_t>();
    if (rows > raw.size())
        in.damaged("impossible probe row count");
    c.probeRows.resize(static_cast<std::size_t>(rows));
    for (std::string& r : c.probeRows)
        r = in.str();
    if (version >= 3) {
        s.removedWater = in.vec<std::uint32_t>();
        t.spilled = in.pod<std::uint64_t>();
        t.firstSpillTime = in.pod<double>();
    }
    in.end();
    if (s.step < 0 || c.checkpointEvery < 0)
        in.damaged("negative step or checkpoint interval");
    if (s.neighborX.size() != s.particles.size() || s.neighborY.size() != s.particles.size() ||
        (!s.wallRestX.empty() && s.wallRestX.size() != s.particles.size())) {
        in.damaged("solver arrays differ in length");
    }
    if (c.probeRows.size() != c.frames.size())
        in.damaged("probe rows and frames differ in number");
    return c;
}

std::string shorten(const nlohmann::json& v) {
    std::string s = v.dump();
    if (s.size() > 80)
        s = s.substr(0, 77) + "...";
    return s;
}

} // namespace

fs::path checkpointPath(const fs::path& cache) {
    fs::path p = cache;
    p += ".ckpt";
    return p;
}

std::uint64_t writeCheckpoint(const fs::path& path, const Checkpoint& c) {
    const std::vector<std::uint8_t> raw = encodePayload(c);
    std::vector<std::uint8_t> file(kHeaderSize + ZSTD_compressBound(raw.size()));
    const std::size_t n = ZSTD_compress(file.data() + kHeaderSize, file.size() - kHeaderSize,
                                        raw.data(), raw.size(), kLevel);
    if (ZSTD_isError(n)) {
        throw CheckpointError(fmt::format("{}: cannot compress the checkpoint: {}", where(path),
                                          ZSTD_getErrorName(n)));
    }
    file.resize(kHeaderSize + n);
    std::uint8_t* h = file.data();
    std::memcpy(h, kMagic, sizeof kMagic);
    putField<std::uint32_t>(h + 8, kVersion);
    putField<std::uint32_t>(h + 12, 0);
    putField<std::uint64_t>(h + 16, n);
    putField<std::uint64_t>(h + 24, raw.size());
    putField<std::uint64_t>(h + 32, XXH3_64bits(file.data() + kHeaderSize, n));
    putField<std::uint64_t>(h + 40, XXH3_64bits(h, 40));

    if (const cache::ReplaceResult r = cache::replaceFile(path, file.data(), file.size());
        r.error != 0) {
        throw CheckpointError(fmt::format("{}: cannot write the checkpoint ({} {}): {}; the "
                                          "previous checkpoint, if any, is unchanged",
                                          where(path), r.step, r.temporary.string(),
                                          std::strerror(r.error)));
    }
    return file.size();
}

Checkpoint readCheckpoint(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        throw CheckpointError(
            fmt::format("{}: no checkpoint to resume from (a bake writes one with "
                        "--checkpoint-every N, or when stopped by SIGINT/SIGTERM with it)",
                        where(path)));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw CheckpointError(
            fmt::format("{}: cannot open the checkpoint: {}", where(path), std::strerror(errno)));
    }
    const std::vector<std::uint8_t> file{std::istreambuf_iterator<char>(in),
                                         std::istreambuf_iterator<char>()};
    if (in.bad())
        throw CheckpointError(fmt::format("{}: cannot read the checkpoint", where(path)));
    const auto damaged = [&](const std::string& what) {
        throw CheckpointError(fmt::format(
            "{}: damaged checkpoint: {}; bake without --resume to start over", where(path), what));
    };
    if (file.size() < kHeaderSize) {
        damaged(fmt::format("{} bytes, shorter than the {}-byte header", file.size(), kHeaderSize));
    }
    const std::uint8_t* h = file.data();
    if (std::memcmp(h, kMagic, sizeof kMagic) != 0) {
        throw CheckpointError(
            fmt::format("{}: not a swell-bake checkpoint (wrong magic bytes)", where(path)));
    }
    if (getField<std::uint64_t>(h + 40) != XXH3_64bits(h, 40))
        damaged("header checksum mismatch");
    const auto version = getField<std::uint32_t>(h + 8);
    if (version < kOldestVersion || version > kVersion) {
        throw CheckpointError(
            fmt::format("{}: checkpoint format version {}; this swell-bake reads versions {} to {}",
                        where(path), version, kOldestVersion, kVersion));
    }
    const auto packed = getField<std::uint64_t>(h + 16);
    const auto rawSize = getField<std::uint64_t>(h + 24);
    if (packed != file.size() - kHeaderSize) {
        damaged(fmt::format("{} payload bytes, the header says {} (truncated?)",
                            file.size() - kHeaderSize, packed));
    }
    if (getField<std::uint64_t>(h + 32) != XXH3_64bits(h + kHeaderSize, packed))
        damaged("payload checksum mismatch");
    // Sizes are checked before the payload is allocated: a damaged (or forged) header must not
    // make the reader allocate gigabytes. The writer's zstd frame records the raw size, and
    // solver state never compresses 1000-fold.
    if (rawSize > kMaxRawPayload || rawSize > packed * 1000 + (std::uint64_t{1} << 20))
        damaged("impossible payload size");
    if (ZSTD_getFrameContentSize(h + kHeaderSize, packed) != rawSize)
        damaged("payload does not decompress to its recorded size");
    std::vector<std::uint8_t> raw(static_cast<std::size_t>(rawSize));
    const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), h + kHeaderSize, packed);
    if (ZSTD_isError(n) || n != raw.size())
        damaged("payload does not decompress to its recorded size");
    return decodePayload(raw, path, version);
}

void checkFingerprint(const fs::path& path, const std::string& stored, const std::string& current) {
    if (stored == current)
        return;
    using nlohmann::json;
    // A fingerprint nested deeper than any scene record is damaged: diff would recurse into it.
    const auto parsed = [](const std::string& text) {
        return cache::jsonDepthAcceptable(text) ? json::parse(text, nullptr, false)
                                                : json(json::value_t::discarded);
    };
    const json a = parsed(stored);
    const json b = parsed(current);
    std::string what = "its fingerprint differs";
    if (!a.is_discarded() && !b.is_discarded()) {
        const json patch = json::diff(a, b);
        const json::json_pointer version("/numerics_version");
        if (!a.contains(version) || !b.contains(version) || a.at(version) != b.at(version)) {
            throw CheckpointError(fmt::format(
                "{}: checkpoint written with numerics version {}, this swell-bake has {}: the "
                "solver's results changed in between, so the resumed cache would not match; bake "
                "without --resume to start over",
                where(path),
                a.contains(version) ? a.at(version).dump() : "none (an older swell-bake)",
                b.contains(version) ? b.at(version).dump() : "none"));
        }
        if (!patch.empty()) {
            json::json_pointer ptr(patch[0].at("path").get<std::string>());
            // A difference inside an array (the --set list) is shown as the whole arrays.
            const auto inArray = [&](const json::json_pointer& p) {
                const json::json_pointer up = p.parent_pointer();
                return !p.empty() && ((a.contains(up) && a.at(up).is_array()) ||
                                      (b.contains(up) && b.at(up).is_array()));
            };
            while (inArray(ptr))
                ptr = ptr.parent_pointer();
            what = fmt::format("{} is {} there, {} now", ptr.to_string(),
                               a.contains(ptr) ? shorten(a.at(ptr)) : "absent",
                               b.contains(ptr) ? shorten(b.at(ptr)) : "absent");
        }
    }
    throw CheckpointError(
        fmt::format("{}: checkpoint of a different bake ({}); resume with the same scene and --set "
                    "overrides, or bake without --resume to start over",
                    where(path), what));
}

} // namespace swell::bake
