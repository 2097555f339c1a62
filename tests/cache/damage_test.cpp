// The reader against damaged files: every defect is a CacheError naming the file
// (and the frame where there is one) — never a crash, hang or wild allocation.
// Run under ASan/UBSan with SWELL_SANITIZE=1 tools/test.
#include "cache_test_util.h"

#include "swell/cache/error.h"
#include "swell/cache/reader.h"

using namespace swell::cache;
using namespace swell::cache::testing;

namespace {

/// Opens and decodes everything; returns the error message, or "" when the file
/// reads whole (then it must decode to `expected`).
std::string tryRead(const fs::path& p, const std::vector<Frame>* expected = nullptr) {
    try {
        const Reader r(p);
        const auto frames = r.readAll();
        for (std::size_t i = 0; i < r.frameCount(); ++i)
            (void)r.readFrame(i);
        if (expected) {
            EXPECT_EQ(frames.size(), expected->size());
            if (frames != *expected)
                ADD_FAILURE() << p << ": damaged file decoded without error to different data";
        }
        return "";
    } catch (const CacheError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(p.string()), std::string::npos)
            << "message does not name the file: " << msg;
        return msg;
    }
}

class Damage : public ::testing::Test {
protected:
    void SetUp() override {
        const auto w = smallWave(12, 2);
        m_frames = writeSynthetic(m_dir / "good.swell", headerFor(w), w, 3);
        m_good = readBytes(m_dir / "good.swell");
        m_bad = m_dir / "bad.swell";
    }
    /// Writes `bytes` and expects an error containing each of `needles`.
    void expectError(const std::vector<std::uint8_t>& bytes,
                     std::initializer_list<const char*> needles) {
        writeBytes(m_bad, bytes);
        const std::string msg = tryRead(m_bad);
        ASSERT_FALSE(msg.empty()) << "damage not detected";
        for (const char* n : needles)
            EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
    }

    TempDir m_dir;
    std::vector<Frame> m_frames;
    std::vector<std::uint8_t> m_good;
    fs::path m_bad;
};

} // namespace

TEST_F(Damage, GoodFileReads) {
    EXPECT_EQ(tryRead(m_dir / "good.swell", &m_frames), "");
}

TEST_F(Damage, WrongMagic) {
    auto b = m_good;
    b[1] = 'X';
    expectError(b, {"bad magic"});
    expectError(std::vector<std::uint8_t>(200, 0), {"bad magic"});
}

TEST_F(Damage, NewerVersion) {
    auto b = m_good;
    poke<std::uint32_t>(b, kOffVersion, kFormatVersion + 1);
    resealHeader(b);
    expectError(b, {"version 2", "reads up to 1"});
}

TEST_F(Damage, HeaderBitFlipCaughtByChecksum) {
    auto b = m_good;
    b[41] ^= 0x10; // inside dt
    expectError(b, {"header checksum"});
}

TEST_F(Damage, MetadataThatIsNotJson) {
    auto b = m_good;
    b[kFixedHeader] = '#';
    resealHeader(b);
    expectError(b, {"not valid JSON"});
}

TEST_F(Damage, TruncatedAtEveryByte) {
    for (std::size_t n = 0; n < m_good.size(); ++n) {
        writeBytes(m_bad, std::vector<std::uint8_t>(m_good.begin(), m_good.begin() + n));
        ASSERT_FALSE(tryRead(m_bad).empty()) << "truncation at " << n << " not detected";
    }
    auto b = m_good;
    b.resize(b.size() - 1);
    expectError(b, {"truncated"});
}

TEST_F(Damage, TrailingBytes) {
    auto b = m_good;
    b.push_back(0);
    expectError(b, {"trailing data"});
}

TEST_F(Damage, EveryBitFlipIsDetectedOrHarmless) {
    for (std::size_t i = 0; i < m_good.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            auto b = m_good;
            b[i] ^= static_cast<std::uint8_t>(1u << bit);
            writeBytes(m_bad, b);
            tryRead(m_bad, &m_frames); // fails the test if it decodes to other data
        }
}

TEST_F(Damage, IndexBitFlipCaughtByChecksum) {
    auto b = m_good;
    b[entryOffset(b, 1) + 3] ^= 1;
    expectError(b, {"index checksum"});
}

TEST_F(Damage, CountsDisagreeWithSizes) {
    auto b = m_good;
    const auto e = entryOffset(b, 1);
    poke<std::uint32_t>(b, e + 24, peek<std::uint32_t>(b, e + 24) + 1);
    resealIndex(b);
    expectError(b, {"frame 1", "disagrees"});
}

TEST_F(Damage, OffsetPastTheEnd) {
    auto b = m_good;
    poke<std::uint64_t>(b, entryOffset(b, 2), b.size() + 1000);
    resealIndex(b);
    expectError(b, {"frame 2", "past the frame data"});
    b = m_good;
    poke<std::uint64_t>(b, entryOffset(b, 2) + 8, 1u << 30); // compressed size
    resealIndex(b);
    expectError(b, {"frame 2"});
}

TEST_F(Damage, OverlappingFrames) {
    auto b = m_good;
    poke<std::uint64_t>(b, entryOffset(b, 1), peek<std::uint64_t>(b, entryOffset(b, 0)) + 1);
    resealIndex(b);
    expectError(b, {"frame 1", "overlaps frame 0"});
}

TEST_F(Damage, FrameChecksumMismatch) {
    auto b = m_good;
    poke<std::uint64_t>(b, entryOffset(b, 2) + 32,
                        peek<std::uint64_t>(b, entryOffset(b, 2) + 32) ^ 1);
    resealIndex(b);
    // The index is valid, so this is found only when the frame is decoded.
    writeBytes(m_bad, b);
    const Reader r(m_bad);
    EXPECT_NO_THROW((void)r.readFrame(1));
    try {
        (void)r.readFrame(2);
        FAIL() << "checksum mismatch not detected";
    } catch (const CacheError& e) {
        EXPECT_NE(std::string(e.what()).find("frame 2: checksum mismatch"), std::string::npos)
            << e.what();
    }
}

TEST_F(Damage, MetadataThatIsNotAnObject) {
    // docs/cache-format.md: the metadata is a JSON object; valid JSON of another kind is refused.
    for (const char* text : {"[1, 2]", "\"text\"", "3"}) {
        const auto w = smallWave(12, 2);
        Header h = headerFor(w);
        h.metadataJson = text;
        (void)writeSynthetic(m_bad, h, w, 1);
        const std::string msg = tryRead(m_bad);
        EXPECT_NE(msg.find("header metadata is not a JSON object"), std::string::npos)
            << text << ": " << msg;
    }
}

TEST_F(Damage, ARecordOfMoreThanOneZstdFrame) {
    // An empty zstd frame appended to frame 2's record (the last before the index), with the
    // index's compressed size and every checksum made to agree: a record is one zstd frame.
    static const std::uint8_t kEmptyFrame[] = {0x28, 0xb5, 0x2f, 0xfd, 0x20,
                                               0x00, 0x01, 0x00, 0x00};
    auto b = m_good;
    const std::size_t indexAt = peek<std::uint64_t>(b, kOffIndexOffset);
    b.insert(b.begin() + static_cast<std::ptrdiff_t>(indexAt), std::begin(kEmptyFrame),
             std::end(kEmptyFrame));
    poke<std::uint64_t>(b, kOffIndexOffset, indexAt + sizeof kEmptyFrame);
    const auto e = entryOffset(b, 2);
    poke<std::uint64_t>(b, e + 8, peek<std::uint64_t>(b, e + 8) + sizeof kEmptyFrame);
    resealIndex(b);
    resealHeader(b);
    expectError(b, {"frame 2", "not one zstd frame"});
}

TEST_F(Damage, HugeFramesFromAFewBytesAreRefusedWhenOpened) {
    // A frame stating far more raw bytes than its compressed size could hold as particle data
    // (1 MiB + 1024 x the compressed size) is damage, refused before decoding; the writer
    // refuses to write one (a frame of zeros compresses some 30,000 times).
    const auto w = smallWave(12, 2);
    Writer writer(m_dir / "zeros.swell", headerFor(w));
    Frame zeros;
    zeros.surface.assign(2 * 300'000, 0.0f);
    try {
        writer.addFrame(zeros);
        ADD_FAILURE() << "the writer wrote a frame of zeros";
    } catch (const CacheError& e) {
        EXPECT_NE(std::string(e.what()).find("beyond the format's bound"), std::string::npos)
            << e.what();
    }
    // The reader: frame 0 of the good file, its stated raw size (and counts) raised so that the
    // raw size passes every other check.
    auto b = m_good;
    const auto ent = entryOffset(b, 0);
    const auto compressed = peek<std::uint64_t>(b, ent + 8);
    const std::uint64_t ns = ((1u << 20) + 1024 * compressed) / 8 + 1;
    poke<std::uint32_t>(b, ent + 24, static_cast<std::uint32_t>(ns));
    poke<std::uint32_t>(b, ent + 28, 0u);
    poke<std::uint64_t>(b, ent + 16, 8 * ns);
    resealIndex(b);
    expectError(b, {"frame 0: raw size", "beyond the format's bound of 1 MiB + 1024 x"});
}

TEST_F(Damage, DecompressionBomb) {
    // Consistent counts and raw size, but 4 GiB per frame: refused before allocating.
    auto b = m_good;
    const auto e = entryOffset(b, 0);
    poke<std::uint32_t>(b, e + 24, 0x20000000u);       // surface count
    poke<std::uint32_t>(b, e + 28, 0u);                // splash count
    poke<std::uint64_t>(b, e + 16, 0x20000000ull * 8); // raw size
    resealIndex(b);
    expectError(b, {"frame 0", "256 MiB"});
    // Raw size within limits but disagreeing with the zstd frame's own content size.
    b = m_good;
    poke<std::uint32_t>(b, e + 24, 1000u);
    poke<std::uint32_t>(b, e + 28, 0u);
    poke<std::uint64_t>(b, e + 16, 8000u);
    resealIndex(b);
    expectError(b, {"frame 0"});
}

TEST_F(Damage, DeterministicMutationLoop) {
    // 10,000 damaged files from a fixed generator: byte sets, bit flips, truncations,
    // insertions, deletions and block copies, each also with the checksums resealed so
    // the structural checks behind them are reached.
    std::uint64_t state = 0x5eed;
    auto next = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return state >> 33;
    };
    int detected = 0;
    for (int iter = 0; iter < 10000; ++iter) {
        auto b = m_good;
        const int kind = static_cast<int>(next() % 6);
        const std::size_t at = next() % b.size();
        switch (kind) {
        case 0:
            b[at] = static_cast<std::uint8_t>(next());
            break;
        case 1:
            b[at] ^= static_cast<std::uint8_t>(1u << (next() % 8));
            break;
        case 2:
            b.resize(at);
            break;
        case 3:
            b.insert(b.begin() + static_cast<long>(at), static_cast<std::uint8_t>(next()));
            break;
        case 4:
            b.erase(b.begin() + static_cast<long>(at));
            break;
        case 5: {
            const std::size_t from = next() % b.size();
            const std::size_t n =
                std::min({std::size_t{1} + next() % 16, b.size() - at, b.size() - from});
            std::copy_n(m_good.begin() + static_cast<long>(from), n,
                        b.begin() + static_cast<long>(at));
            break;
        }
        }
        if (iter % 2 == 1 && b.size() >= kFixedHeader) { // reseal what still parses
            const auto count = peek<std::uint64_t>(b, kOffFrameCount);
            const auto off = peek<std::uint64_t>(b, kOffIndexOffset);
            const auto meta = peek<std::uint32_t>(b, 68);
            if (kFixedHeader + std::uint64_t{meta} <= b.size())
                resealHeader(b);
            if (count < 1000 && off <= b.size() && off + count * kEntry + 8 <= b.size())
                resealIndex(b);
        }
        writeBytes(m_bad, b);
        if (b == m_good)
            continue;
        detected += !tryRead(m_bad, &m_frames).empty();
        if (HasFailure())
            FAIL() << "mutation " << iter << " (kind " << kind << " at " << at << ")";
    }
    EXPECT_GT(detected, 9000);
}
